// Numeric tables as files: a header and rows of numbers as CSV, or NumPy's .npy (format 1.0,
// little-endian float64, C order, shape (rows, columns)) that numpy.load reads. The annual series
// of `skylight daylight --epw` and `skylight irradiance --epw` (docs/DAYLIGHT.md,
// docs/IRRADIANCE.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace skylight::io {

// The .npy header of a (rows, columns) float64 table: magic, version 1.0, the header length and
// the dictionary, padded with spaces to a multiple of 64 bytes.
std::string npy_header(std::size_t rows, std::size_t columns);
// Appends one float64 value, little-endian.
void append_npy_value(std::string& out, double value);

// A whole table of `values` (row-major, columns.size() per row): CSV with the column names as its
// header line (each value with `digits` significant digits, "{:.<digits>g}"), or .npy (the column
// names are not stored; a caller documents them).
std::string table_csv(const std::vector<std::string>& columns, const std::vector<double>& values,
                      int digits = 10);
std::string table_npy(std::size_t columns, const std::vector<double>& values);

}  // namespace skylight::io
