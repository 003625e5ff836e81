#include "skylight/io/table.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>

#include "skylight/core/error.h"

namespace skylight::io {

static_assert(std::endian::native == std::endian::little, "the .npy writer writes '<f8'");

std::string npy_header(std::size_t rows, std::size_t columns) {
  std::string header =
      fmt::format("{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}", rows, columns);
  // Magic (6) + version (2) + length (2) + header + '\n', padded with spaces to 64 bytes.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>((header.size() >> 8) & 0xff);
  out += header;
  return out;
}

void append_npy_value(std::string& out, double value) {
  unsigned char b[8];
  std::memcpy(b, &value, 8);  // little-endian hosts (the static_assert above)
  out.append(reinterpret_cast<const char*>(b), 8);
}

std::string table_csv(const std::vector<std::string>& columns, const std::vector<double>& values,
                      int digits) {
  SKYLIGHT_CHECK(!columns.empty() && values.size() % columns.size() == 0,
                 "a table's values fill whole rows");
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c)
    out += columns[c] + (c + 1 < columns.size() ? "," : "\n");
  for (std::size_t i = 0; i < values.size(); ++i)
    out += fmt::format("{:.{}g}{}", values[i], digits, (i + 1) % columns.size() ? ',' : '\n');
  return out;
}

std::string table_npy(std::size_t columns, const std::vector<double>& values) {
  SKYLIGHT_CHECK(columns > 0 && values.size() % columns == 0, "a table's values fill whole rows");
  std::string out = npy_header(values.size() / columns, columns);
  out.reserve(out.size() + 8 * values.size());
  for (double v : values) append_npy_value(out, v);
  return out;
}

}  // namespace skylight::io
