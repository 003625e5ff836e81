// The embedded data files as the build writes them (cmake/embed_data.cmake, embedded_data.cpp);
// read through data::embedded_file() (core/data.h).
#pragma once

#include <cstddef>

namespace skylight::data::detail {

struct EmbeddedFile {
  const char* path;
  const char* content;
};
extern const EmbeddedFile kEmbeddedFiles[];
extern const std::size_t kEmbeddedFileCount;

}  // namespace skylight::data::detail
