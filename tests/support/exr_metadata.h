// Test helper: one entry of an image's metadata (io::read_exr_metadata) by key.
#pragma once

#include <string>

#include "skylight/io/image.h"

namespace skylight::testing_support {

// What metadata_value gives for a key the metadata does not hold.
inline const std::string kMissingMetadata = "<missing>";

// The value of `key` in `md`, kMissingMetadata when there is none.
inline std::string metadata_value(const io::Metadata& md, const std::string& key) {
  for (const auto& [k, value] : md)
    if (k == key) return value;
  return kMissingMetadata;
}

}  // namespace skylight::testing_support
