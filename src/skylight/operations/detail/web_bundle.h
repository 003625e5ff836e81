// `skylight view`'s page as the build embedded it (cmake/embed_web.cmake, generated): index.html,
// viewer.js and skylight_web.js (the library compiled to WebAssembly; absent from a build without
// Emscripten). Internal to operations/.
#pragma once

#include <string_view>
#include <vector>

namespace skylight::operations::detail {

struct WebFile {
  std::string_view name;
  std::string_view content;
};
const std::vector<WebFile>& web_bundle();

}  // namespace skylight::operations::detail
