// The image list of `nn train --images` (estimate/sky_sequence.h), apart from the sampling so
// that the parser builds alone (the fuzz target sequence_list links only what it reads).
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/estimate/sky_sequence.h"

namespace skylight::estimate {
namespace {

constexpr std::array<std::string_view, 5> kColumns = {"file", "sun_zenith_deg", "sun_azimuth_deg",
                                                      "time", "mask"};

std::vector<std::string_view> split_cells(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t end = line.find(',', pos);
    cells.push_back(trim(line.substr(pos, end == std::string_view::npos ? end : end - pos)));
    if (end == std::string_view::npos) return cells;
    pos = end + 1;
  }
}

// The error of line `line` of the list `where`.
InvalidArgument line_error(const std::string& where, int line, const std::string& why) {
  return InvalidArgument(fmt::format("{}:{}: {}", where, line, why));
}

// The header's columns: per cell, its index into kColumns (each known, none twice, 'file' among
// them).
std::vector<int> header_columns(const std::vector<std::string_view>& cells,
                                const std::string& where, int line) {
  std::vector<int> column;
  for (std::string_view c : cells) {
    const auto it = std::find(kColumns.begin(), kColumns.end(), c);
    if (it == kColumns.end())
      throw line_error(where, line,
                       fmt::format("unknown column '{}' (file, sun_zenith_deg, sun_azimuth_deg, "
                                   "time, mask)",
                                   excerpt(c)));
    const int k = static_cast<int>(it - kColumns.begin());
    if (std::find(column.begin(), column.end(), k) != column.end())
      throw line_error(where, line, fmt::format("column '{}' given twice", excerpt(c)));
    column.push_back(k);
  }
  if (std::find(column.begin(), column.end(), 0) == column.end())
    throw line_error(where, line, "the header has no 'file' column");
  return column;
}

// An angle cell `c` of column `name`: a number within [lo, hi].
double angle_cell(std::string_view c, std::string_view name, double lo, double hi,
                  const std::string& where, int line) {
  const auto v = parse_number(c);
  if (!v)
    throw line_error(where, line, fmt::format("{} '{}' {}", name, excerpt(c), number_problem(c)));
  if (*v < lo || *v > hi)
    throw line_error(where, line,
                     fmt::format("{} '{}' is outside [{}, {}]", name, excerpt(c), lo, hi));
  return *v;
}

// A file or mask cell names a file: not a folder (trailing '/', '.', '..'; found by the
// fuzz target sequence_list: "b.exr../" was a folder) and no control character (a NUL
// would cut the name the system sees).
std::filesystem::path file_cell(std::string_view c, std::string_view name,
                                const std::filesystem::path& folder, const std::string& where,
                                int line) {
  if (std::any_of(c.begin(), c.end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    throw line_error(where, line,
                     fmt::format("{} '{}' holds a control character", name, excerpt(c)));
  const std::filesystem::path cell{std::string(c)};
  const std::string last = cell.filename().string();
  if (last.empty() || last == "." || last == "..")
    throw line_error(where, line,
                     fmt::format("{} '{}' names a folder, not a file", name, excerpt(c)));
  return folder / cell;
}

}  // namespace

std::vector<SequenceEntry> parse_sequence_list(std::string_view text, const std::string& where,
                                               const std::filesystem::path& folder) {
  std::vector<int> column;  // cell index -> index into kColumns
  std::vector<SequenceEntry> rows;
  int line = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view raw = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    const std::string_view t = trim(raw);
    if (t.empty() || t.front() == '#') continue;
    const auto cells = split_cells(t);
    auto fail = [&](const std::string& why) { return line_error(where, line, why); };
    if (column.empty()) {
      column = header_columns(cells, where, line);
      continue;
    }
    if (cells.size() != column.size())
      throw fail(fmt::format("{} cells, the header has {}", cells.size(), column.size()));
    SequenceEntry e;
    e.line = line;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string_view c = cells[i];
      if (c.empty()) continue;
      switch (column[i]) {
        case 0:
          e.file = file_cell(c, "file", folder, where, line);
          break;
        case 1:
          e.sun_zenith_deg = angle_cell(c, "sun_zenith_deg", 0.0, 90.0, where, line);
          break;
        case 2:
          e.sun_azimuth_deg = angle_cell(c, "sun_azimuth_deg", -360.0, 360.0, where, line);
          break;
        case 3:
          e.time = std::string(c);
          break;
        default:
          e.mask = file_cell(c, "mask", folder, where, line);
          break;
      }
    }
    if (e.file.empty()) throw fail("no file");
    if (e.sun_zenith_deg.has_value() != e.sun_azimuth_deg.has_value())
      throw fail("sun_zenith_deg and sun_azimuth_deg go together");
    if (e.sun_zenith_deg && !e.time.empty()) throw fail("the sun's angles and a time both given");
    rows.push_back(std::move(e));
  }
  if (rows.empty()) throw InvalidArgument(fmt::format("{}: no images listed", where));
  return rows;
}

}  // namespace skylight::estimate
