#include "skylight/core/data.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "skylight/core/detail/embedded_files.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"

namespace skylight::data {

std::string_view embedded_file(std::string_view relative_path) {
  for (std::size_t i = 0; i < detail::kEmbeddedFileCount; ++i) {
    if (relative_path == detail::kEmbeddedFiles[i].path) return detail::kEmbeddedFiles[i].content;
  }
  throw IoError(fmt::format("no embedded data file '{}'", relative_path));
}

std::vector<std::string_view> embedded_files() {
  std::vector<std::string_view> out;
  for (std::size_t i = 0; i < detail::kEmbeddedFileCount; ++i)
    out.emplace_back(detail::kEmbeddedFiles[i].path);
  return out;
}

namespace {

std::vector<std::string> split_fields(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.emplace_back(
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

CsvTable::CsvTable(std::string_view text, std::string source, bool has_header, std::size_t columns)
    : source_(std::move(source)), columns_(columns) {
  std::size_t line_no = 0;
  std::size_t pos = 0;
  bool header_pending = has_header;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line = trim(text.substr(pos, nl == text.npos ? text.npos : nl - pos));
    ++line_no;
    pos = (nl == text.npos) ? text.size() + 1 : nl + 1;
    if (line.empty()) continue;
    auto fields = split_fields(line);
    if (columns_ == 0) columns_ = fields.size();
    if (fields.size() != columns_) {
      throw IoError(fmt::format("{} line {}: expected {} comma-separated fields, found {}", source_,
                                line_no, columns_, fields.size()));
    }
    if (header_pending) {
      header_ = std::move(fields);
      header_pending = false;
      continue;
    }
    cells_.push_back(std::move(fields));
    line_numbers_.push_back(line_no);
  }
  if (header_pending) throw IoError(fmt::format("{}: empty table (no header line)", source_));
}

std::size_t CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return i;
  throw IoError(fmt::format("{}: no column '{}'", source_, name));
}

const std::string& CsvTable::text(std::size_t row, std::size_t col) const {
  SKYLIGHT_CHECK(row < cells_.size() && col < columns_, "CsvTable index out of range");
  return cells_[row][col];
}

std::size_t CsvTable::line(std::size_t row) const {
  SKYLIGHT_CHECK(row < line_numbers_.size(), "CsvTable row out of range");
  return line_numbers_[row];
}

double CsvTable::number(std::size_t row, std::size_t col) const {
  const std::string& field = text(row, col);
  const auto value = parse_number(field);
  if (!value)
    throw IoError(fmt::format("{} line {} column {}: '{}' {}", source_, line_numbers_[row], col + 1,
                              excerpt(field), number_problem(field)));
  return *value;
}

std::vector<double> CsvTable::numbers(std::size_t col) const {
  std::vector<double> out(rows());
  for (std::size_t r = 0; r < rows(); ++r) out[r] = number(r, col);
  return out;
}

CsvTable load_table(std::string_view relative_path, bool has_header, std::size_t columns) {
  return CsvTable(embedded_file(relative_path), std::string(relative_path), has_header, columns);
}

}  // namespace skylight::data
