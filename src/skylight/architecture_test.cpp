// The library's dependency direction, as docs/ARCHITECTURE.md states it ("Layers"): every
// `#include "skylight/<folder>/..."` of a library source points to its own folder or to a folder
// of a lower layer; headers under detail/ are included by sources, never by a public header; and
// the library includes nothing outside src/skylight (no CLI, no benchmark fixture). Tests
// (*_test.cpp) are not part of the library: they may use any folder to build their fixtures.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(SKYLIGHT_SOURCE_DIR);
const fs::path kLibrary = kRoot / "src" / "skylight";

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The layer of each folder from docs/ARCHITECTURE.md: the lines "N  folder, folder" between
// "<!-- layers -->" and "<!-- end layers -->".
std::map<std::string, int> documented_layers() {
  const std::string doc = read(kRoot / "docs" / "ARCHITECTURE.md");
  const auto begin = doc.find("<!-- layers -->"), end = doc.find("<!-- end layers -->");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return {};
  std::map<std::string, int> layers;
  std::istringstream lines(doc.substr(begin, end - begin));
  const std::regex row(R"(^(\d+)\s+([a-z_, ]+?)\s*(#.*)?$)");
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    std::istringstream folders(m[2].str());
    for (std::string f; std::getline(folders, f, ',');) {
      f.erase(0, f.find_first_not_of(' '));
      f.erase(f.find_last_not_of(' ') + 1);
      EXPECT_FALSE(layers.count(f)) << f << " is in two layers";
      layers[f] = std::stoi(m[1].str());
    }
  }
  return layers;
}

struct Include {
  fs::path file;  // relative to src/skylight
  int line = 0;
  std::string target;
};

bool is_test(const fs::path& p) {
  return p.filename().string().find("_test") != std::string::npos;
}

bool in_detail(const fs::path& p) {
  for (const auto& part : p)
    if (part == "detail") return true;
  return false;
}

// Every quoted include of the library's sources (tests included; callers filter).
std::vector<Include> library_includes() {
  std::vector<Include> out;
  const std::regex include(R"(^\s*#\s*include\s*"([^"]+)\")");
  for (const auto& e : fs::recursive_directory_iterator(kLibrary)) {
    if (!e.is_regular_file()) continue;
    const auto ext = e.path().extension();
    if (ext != ".h" && ext != ".cpp") continue;
    std::ifstream in(e.path());
    int n = 0;
    for (std::string line; std::getline(in, line);) {
      ++n;
      std::smatch m;
      if (std::regex_search(line, m, include))
        out.push_back({fs::relative(e.path(), kLibrary), n, m[1].str()});
    }
  }
  return out;
}

// "skylight/<folder>/..." -> folder; "" for other paths and root headers (skylight/version.h).
std::string folder_of(const std::string& include) {
  const std::string prefix = "skylight/";
  if (include.rfind(prefix, 0) != 0) return "";
  const auto slash = include.find('/', prefix.size());
  return slash == std::string::npos ? "" : include.substr(prefix.size(), slash - prefix.size());
}

TEST(Architecture, EveryFolderHasADocumentedLayer) {
  const auto layers = documented_layers();
  ASSERT_FALSE(layers.empty()) << "docs/ARCHITECTURE.md: no <!-- layers --> block";
  std::set<std::string> folders;
  for (const auto& e : fs::directory_iterator(kLibrary))
    if (e.is_directory()) folders.insert(e.path().filename().string());
  for (const auto& f : folders)
    EXPECT_TRUE(layers.count(f)) << "src/skylight/" << f << "/ has no layer in the docs";
  for (const auto& [f, layer] : layers)
    EXPECT_TRUE(folders.count(f)) << "the docs' layer " << layer << " names " << f
                                  << ", which is not a folder of src/skylight";
}

TEST(Architecture, IncludesPointToLowerLayers) {
  const auto layers = documented_layers();
  ASSERT_FALSE(layers.empty());
  int checked = 0;
  for (const auto& inc : library_includes()) {
    if (is_test(inc.file)) continue;
    const std::string where =
        "src/skylight/" + inc.file.generic_string() + ":" + std::to_string(inc.line);
    // Only the library's own headers (and the generated version header) are included by path.
    ASSERT_EQ(inc.target.rfind("skylight/", 0), 0u)
        << where << " includes \"" << inc.target << "\" from outside the library";
    const std::string from = inc.file.begin()->string(), to = folder_of(inc.target);
    if (to.empty() || to == from) continue;
    ASSERT_TRUE(layers.count(from) && layers.count(to)) << where;
    EXPECT_LT(layers.at(to), layers.at(from))
        << where << ": " << from << "/ (layer " << layers.at(from) << ") includes " << inc.target
        << " (" << to << "/, layer " << layers.at(to) << ")";
    ++checked;
  }
  EXPECT_GT(checked, 100) << "the include scan found too few includes to be working";
}

TEST(Architecture, DetailHeadersStayInternal) {
  // A public header never includes a detail/ header (those are not installed).
  for (const auto& inc : library_includes()) {
    if (is_test(inc.file) || in_detail(inc.file) || inc.file.extension() != ".h") continue;
    EXPECT_EQ(inc.target.find("/detail/"), std::string::npos)
        << "src/skylight/" << inc.file.generic_string() << ":" << inc.line
        << ": a public header includes " << inc.target;
  }
  // A header whose declarations are all internal (its namespace is a detail namespace) lives in
  // a detail/ folder.
  const std::regex first_namespace(R"(namespace\s+([A-Za-z_:]+)\s*\{)");
  for (const auto& e : fs::recursive_directory_iterator(kLibrary)) {
    if (!e.is_regular_file() || e.path().extension() != ".h") continue;
    const auto rel = fs::relative(e.path(), kLibrary);
    if (in_detail(rel)) continue;
    const std::string text = read(e.path());
    std::smatch m;
    if (!std::regex_search(text, m, first_namespace)) continue;
    const std::string ns = m[1].str();
    EXPECT_FALSE(ns.size() >= 8 && ns.compare(ns.size() - 8, 8, "::detail") == 0)
        << "src/skylight/" << rel.generic_string() << " is internal (namespace " << ns
        << ") but not in a detail/ folder";
  }
}

}  // namespace
