// Test helper: the published test vectors of data/test_vectors/ (CSV with a header line) as rows of
// text cells, for tests that parse each cell as they need.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "skylight/core/numbers.h"

namespace skylight::testing_support {

inline std::string test_vector_path(const std::string& name) {
  // Through a path join (GCC 12 warns falsely about chained string concatenation here).
  std::string path = SKYLIGHT_TEST_DATA_DIR;
  path.append("/test_vectors/").append(name);
  return path;
}

// The rows after the header of data/test_vectors/`name`: comma-separated cells, no quoting; blank
// lines are skipped.
inline std::vector<std::vector<std::string>> read_test_vector_csv(const std::string& name) {
  std::ifstream f(test_vector_path(name));
  EXPECT_TRUE(f.good()) << "cannot open " << test_vector_path(name);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  std::getline(f, line);  // header
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// A cell as a number / an integer, by the library's strict parsers (a malformed cell throws and
// fails the test).
inline double cell_number(const std::string& cell) {
  return parse_number(cell, "test vector field");
}
inline int cell_integer(const std::string& cell) {
  return static_cast<int>(parse_integer(cell, "test vector field"));
}

}  // namespace skylight::testing_support
