// The project's published data tables (data/, see data/PROVENANCE.md), embedded at build time, and
// the one checked loader that parses them. A malformed field is reported as
// "<file> line L column C: <what>", so a corrupt table never turns into silent garbage.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::data {

// Content of an embedded data file by its path relative to data/, e.g.
// "cie_colorimetry/CIE_xyz_1931_2deg.csv". Throws skylight::IoError for an unknown path.
std::string_view embedded_file(std::string_view relative_path);
// Paths of all embedded files.
std::vector<std::string_view> embedded_files();

// A parsed comma-separated table. Blank lines are skipped; CRLF is accepted.
class CsvTable {
 public:
  // Parses `text`; `source` names it in error messages. With `has_header`, the first line is the
  // column names. Every row must have exactly `columns` fields (0: as many as the first row).
  CsvTable(std::string_view text, std::string source, bool has_header, std::size_t columns = 0);

  std::size_t rows() const { return cells_.size(); }
  std::size_t columns() const { return columns_; }
  const std::vector<std::string>& header() const { return header_; }
  // Column index by header name; throws IoError naming the table if absent.
  std::size_t column(std::string_view name) const;
  const std::string& text(std::size_t row, std::size_t col) const;
  // The 1-based line of the source text that holds data row `row`.
  std::size_t line(std::size_t row) const;
  // The field as a finite double; throws IoError "<source> line L column C: '<field>' is not a
  // finite number".
  double number(std::size_t row, std::size_t col) const;
  // A whole column as numbers.
  std::vector<double> numbers(std::size_t col) const;

 private:
  std::string source_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<std::size_t> line_numbers_;
  std::size_t columns_ = 0;
};

// Parses an embedded table (shorthand for CsvTable(embedded_file(path), path, ...)).
CsvTable load_table(std::string_view relative_path, bool has_header, std::size_t columns = 0);

}  // namespace skylight::data
