// Camera spectral sensitivities: data/camera_sensitivity/PROVENANCE.md; docs/HAZE.md.
#include "skylight/haze/sensitivity.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/core/text.h"
#include "skylight/io/file.h"

namespace skylight::haze {
namespace {

constexpr std::string_view kTable =
    "camera_sensitivity/physlight_camera_sensitivities_380_780_5nm.csv";
constexpr double kTableStepNm = 5.0;
constexpr std::size_t kTableSamples = 81;  // 380 .. 780 nm in 5 nm steps

std::string unquote(std::string_view s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return std::string(s);
}

// "Canon", "EOS 5D" -> "canon-eos-5d".
std::string camera_key(const std::string& manufacturer, const std::string& model) {
  std::string key = manufacturer + " " + model;
  for (char& ch : key) {
    ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ch == ' ') ch = '-';
  }
  return key;
}

const std::map<std::string, CameraSensitivity>& embedded_cameras() {
  static const std::map<std::string, CameraSensitivity> cameras = [] {
    const data::CsvTable table = data::load_table(kTable, true, 3 + kTableSamples);
    if (table.header()[3] != "380nm" || table.header().back() != "780nm")
      throw IoError(fmt::format("{}: columns must run from 380nm to 780nm", kTable));
    std::map<std::string, CameraSensitivity> out;
    std::map<std::string, int> channels_seen;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      const std::string manufacturer = unquote(table.text(row, 0));
      const std::string model = unquote(table.text(row, 1));
      const std::string key = camera_key(manufacturer, model);
      const std::string& channel = table.text(row, 2);
      const int c = channel == "R" ? 0 : channel == "G" ? 1 : channel == "B" ? 2 : -1;
      if (c < 0)
        throw IoError(fmt::format("{} line {}: channel '{}' is not R, G or B", kTable,
                                  table.line(row), excerpt(channel)));
      std::vector<double> values;
      for (std::size_t i = 0; i < kTableSamples; ++i) values.push_back(table.number(row, 3 + i));
      CameraSensitivity& cam = out[key];
      cam.name = key;
      cam.description = manufacturer + " " + model;
      if (!cam.channel[static_cast<std::size_t>(c)].empty())
        throw IoError(fmt::format("{} line {}: {} channel {} given twice", kTable, table.line(row),
                                  key, channel));
      cam.channel[static_cast<std::size_t>(c)] =
          Spectrum::uniform(kVisibleFirstNm, kTableStepNm, std::move(values), key + " " + channel);
      ++channels_seen[key];
    }
    for (const auto& [key, n] : channels_seen)
      if (n != 3) throw IoError(fmt::format("{}: {} has {} of 3 channels", kTable, key, n));
    return out;
  }();
  return cameras;
}

}  // namespace

std::vector<std::string> camera_names() {
  std::vector<std::string> names;
  for (const auto& [key, cam] : embedded_cameras()) names.push_back(key);
  return names;
}

const CameraSensitivity& find_camera(std::string_view name) {
  const auto& cameras = embedded_cameras();
  const auto it = cameras.find(std::string(name));
  if (it != cameras.end()) return it->second;
  const std::vector<std::string> names = camera_names();
  throw InvalidArgument(
      fmt::format("unknown camera '{}'{} (`skylight haze cameras` lists the {}; or {})",
                  excerpt(name), did_you_mean(name, names), names.size(), spelled("camera-csv")));
}

CameraSensitivity parse_camera_csv(std::string_view text, const std::string& source) {
  std::vector<double> nm;
  std::array<std::vector<double>, 3> q;
  std::size_t line_no = 0;
  bool header_seen = false;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_no;
    line = trim(line);
    if (line.empty()) continue;
    std::vector<std::string_view> fields;
    for (std::size_t pos = 0;;) {
      const std::size_t comma = line.find(',', pos);
      fields.push_back(
          trim(line.substr(pos, comma == std::string_view::npos ? line.npos : comma - pos)));
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    if (!header_seen) {
      if (fields.size() != 4 || fields[0] != "nm" || fields[1] != "r" || fields[2] != "g" ||
          fields[3] != "b")
        throw InvalidArgument(fmt::format("{} line {}: the header must be 'nm,r,g,b', not '{}'",
                                          source, line_no, excerpt(line)));
      header_seen = true;
      continue;
    }
    if (fields.size() != 4)
      throw InvalidArgument(fmt::format("{} line {}: {} fields, expected 4 (nm,r,g,b)", source,
                                        line_no, fields.size()));
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < 4; ++i) {
      const std::optional<double> x = parse_number(fields[i]);
      if (!x)
        throw InvalidArgument(fmt::format("{} line {} column {}: '{}' {}", source, line_no, i + 1,
                                          excerpt(fields[i]), number_problem(fields[i])));
      if (i > 0 && *x < 0.0)
        throw InvalidArgument(
            fmt::format("{} line {} column {}: '{}' is negative (a sensitivity "
                        "is >= 0)",
                        source, line_no, i + 1, excerpt(fields[i])));
      v[i] = *x;
    }
    if (!nm.empty() && !(v[0] > nm.back()))
      throw InvalidArgument(
          fmt::format("{} line {}: wavelength {} nm is not above the previous {} nm", source,
                      line_no, v[0], nm.back()));
    nm.push_back(v[0]);
    for (std::size_t c = 0; c < 3; ++c) q[c].push_back(v[c + 1]);
  }
  if (!header_seen)
    throw InvalidArgument(fmt::format("{}: empty (expected a header 'nm,r,g,b')", source));
  if (nm.size() < 2 || nm.front() > kVisibleFirstNm || nm.back() < kVisibleLastNm)
    throw InvalidArgument(fmt::format("{}: the wavelengths must cover {} .. {} nm", source,
                                      kVisibleFirstNm, kVisibleLastNm));
  CameraSensitivity cam;
  cam.name = source;
  cam.description = "user sensitivities " + source;
  static constexpr const char* kChannel[] = {"r", "g", "b"};
  for (std::size_t c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t i = 0; i < nm.size(); ++i)
      if (nm[i] >= kVisibleFirstNm && nm[i] <= kVisibleLastNm) sum += q[c][i];
    if (!(sum > 0.0))
      throw InvalidArgument(fmt::format("{}: channel {} is zero over {} .. {} nm", source,
                                        kChannel[c], kVisibleFirstNm, kVisibleLastNm));
    cam.channel[c] = Spectrum(nm, q[c], source + " " + kChannel[c]);
  }
  return cam;
}

CameraSensitivity load_camera_csv(const std::filesystem::path& path) {
  const std::vector<char> bytes = io::read_file(path);
  return parse_camera_csv(std::string_view(bytes.data(), bytes.size()), io::shown_path(path));
}

}  // namespace skylight::haze
