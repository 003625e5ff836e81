// The Kider et al. 2014 reader and the shipped subset (kider.h).
#include "skylight/io/kider.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <system_error>

#include "skylight/core/colorimetry.h"
#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kRadianceSuffix = ".asd.rad.txt";
// How deep below the given path the reader looks for capture folders (root/date/RADIANCE/capture).
constexpr int kMaxSearchDepth = 4;

// The lines of `text` (without '\n' or a trailing '\r'), each with its 1-based number.
struct Line {
  std::string_view text;
  std::size_t number = 0;
};
std::vector<Line> lines_of(std::string_view text) {
  std::vector<Line> out;
  std::size_t start = 0, number = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.push_back({line, ++number});
    start = end + 1;
  }
  return out;
}

// Fields separated by any run of spaces or tabs.
std::vector<std::string_view> whitespace_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::vector<std::string_view> comma_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(',', start);
    out.push_back(trim(line.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

[[noreturn]] void bad_line(std::string_view source, std::size_t line, const std::string& what) {
  throw InvalidArgument(fmt::format("{} line {}: {}", source, line, what));
}

double number_at(std::string_view source, std::size_t line, std::string_view field,
                 std::string_view what) {
  const auto v = parse_number(field);
  if (!v)
    bad_line(source, line, fmt::format("{} '{}' {}", what, excerpt(field), number_problem(field)));
  return *v;
}

// "YYYY-MM-DD___HH.MM.SS" -> "YYYY-MM-DDTHH:MM:SS"; nullopt if the name is not of that form.
std::optional<std::string> capture_local_time(std::string_view name) {
  if (name.size() != 21 || name.substr(10, 3) != "___") return std::nullopt;
  const std::string_view date = name.substr(0, 10), time = name.substr(13);
  const auto digits = [](std::string_view s, std::initializer_list<std::size_t> at) {
    return std::all_of(at.begin(), at.end(),
                       [&](std::size_t i) { return s[i] >= '0' && s[i] <= '9'; });
  };
  if (!digits(date, {0, 1, 2, 3, 5, 6, 8, 9}) || date[4] != '-' || date[7] != '-' ||
      !digits(time, {0, 1, 3, 4, 6, 7}) || time[2] != '.' || time[5] != '.')
    return std::nullopt;
  const int month = (date[5] - '0') * 10 + (date[6] - '0'),
            day = (date[8] - '0') * 10 + (date[9] - '0');
  const int hour = (time[0] - '0') * 10 + (time[1] - '0'),
            minute = (time[3] - '0') * 10 + (time[4] - '0');
  const int second = (time[6] - '0') * 10 + (time[7] - '0');
  if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 23 || minute > 59 || second > 59)
    return std::nullopt;
  return fmt::format("{}T{}:{}:{}", date, time.substr(0, 2), time.substr(3, 2), time.substr(6, 2));
}

// The pyranometer file's name for a capture: "YYYY.MM.DD.HH.MM.SS.txt".
std::string pyranometer_file_name(std::string_view local_time) {
  std::string s(local_time);
  std::replace(s.begin(), s.end(), '-', '.');
  std::replace(s.begin(), s.end(), 'T', '.');
  std::replace(s.begin(), s.end(), ':', '.');
  return s + ".txt";
}

KiderSample make_sample(const KiderFileName& name, std::vector<double> radiance,
                        const std::vector<double>& wavelengths, std::string source) {
  KiderSample s;
  s.index = name.index;
  s.file_azimuth_deg = name.file_azimuth_deg;
  s.elevation_deg = name.elevation_deg;
  s.zenith = deg_to_rad(90.0 - name.elevation_deg);
  s.azimuth = wrap_azimuth(deg_to_rad(360.0 - name.file_azimuth_deg));
  s.luminance = luminance_380_780(wavelengths, radiance);
  s.radiance = std::move(radiance);
  s.source = std::move(source);
  return s;
}

// Sample 0 replaced by the mean of its ring neighbours (kider.h); checks that all 81 are there.
void complete_capture(KiderCapture& c, std::string_view where) {
  std::sort(c.samples.begin(), c.samples.end(),
            [](const KiderSample& a, const KiderSample& b) { return a.index < b.index; });
  for (std::size_t i = 1; i < c.samples.size(); ++i)
    if (c.samples[i].index == c.samples[i - 1].index)
      throw InvalidArgument(fmt::format("{}: sample {} given twice ('{}' and '{}')", where,
                                        c.samples[i].index, c.samples[i - 1].source,
                                        c.samples[i].source));
  for (int i = 0; i < kKiderSampleCount; ++i)
    if (static_cast<int>(c.samples.size()) <= i ||
        c.samples[static_cast<std::size_t>(i)].index != i)
      throw InvalidArgument(
          fmt::format("{}: sample {} of the {} is missing", where, i, kKiderSampleCount));
  KiderSample& zero = c.samples[0];
  const KiderSample& a = c.samples[kKiderSampleZeroNeighbours[0]];
  const KiderSample& b = c.samples[kKiderSampleZeroNeighbours[1]];
  for (std::size_t k = 0; k < zero.radiance.size(); ++k)
    zero.radiance[k] = 0.5 * (a.radiance[k] + b.radiance[k]);
  zero.luminance = 0.5 * (a.luminance + b.luminance);
  zero.replaced = true;
}

std::vector<PyranometerReading> find_pyranometer(const fs::path& capture_dir,
                                                 const std::string& local_time,
                                                 std::string& source) {
  const fs::path file =
      capture_dir.parent_path().parent_path() / "IRRADIANCE" / pyranometer_file_name(local_time);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return {};
  source = file.string();
  return parse_pyranometer(read_text_file(file), shown_path(file));
}

KiderCapture read_capture(const fs::path& dir) {
  KiderCapture c;
  c.name = dir.filename().string();
  const auto time = capture_local_time(c.name);
  if (!time)
    throw InvalidArgument(fmt::format(
        "'{}': a capture folder's name must be its local date and time, YYYY-MM-DD___HH.MM.SS",
        shown_path(dir)));
  c.local_time = *time;
  std::error_code ec;
  std::vector<fs::path> files;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && parse_kider_file_name(it->path().filename().string()))
      files.push_back(it->path());
  if (ec) throw_read_error(dir, ec.message());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const std::string shown = shown_path(f);
    KiderSpectrum s = parse_kider_radiance(read_text_file(f), shown);
    if (c.wavelengths_nm.empty()) {
      c.wavelengths_nm = s.wavelengths_nm;
    } else if (s.wavelengths_nm != c.wavelengths_nm) {
      throw InvalidArgument(fmt::format(
          "{}: its wavelengths ({} values, {}-{} nm) differ from the capture's other files' ({}, "
          "{}-{} nm)",
          shown, s.wavelengths_nm.size(), s.wavelengths_nm.front(), s.wavelengths_nm.back(),
          c.wavelengths_nm.size(), c.wavelengths_nm.front(), c.wavelengths_nm.back()));
    }
    c.samples.push_back(make_sample(*parse_kider_file_name(f.filename().string()),
                                    std::move(s.radiance), c.wavelengths_nm, shown));
  }
  complete_capture(c, shown_path(dir));
  c.pyranometer = find_pyranometer(dir, c.local_time, c.pyranometer_source);
  return c;
}

// The folders under `root` (itself included) that hold a radiance file.
void find_capture_dirs(const fs::path& dir, int depth, std::vector<fs::path>& out) {
  std::error_code ec;
  bool holds_radiance = false;
  std::vector<fs::path> subdirs;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_directory(ec))
      subdirs.push_back(it->path());
    else if (parse_kider_file_name(it->path().filename().string()))
      holds_radiance = true;
  }
  if (ec) throw_read_error(dir, ec.message());
  if (holds_radiance) out.push_back(dir);
  if (depth >= kMaxSearchDepth) return;
  for (const fs::path& d : subdirs) find_capture_dirs(d, depth + 1, out);
}

// Drops the leading '#' comment lines; the rest keeps its line numbers.
std::vector<Line> data_lines(std::string_view text) {
  std::vector<Line> out;
  for (const Line& l : lines_of(text))
    if (!trim(l.text).empty() && trim(l.text).front() != '#') out.push_back(l);
  return out;
}

}  // namespace

double luminance_380_780(const std::vector<double>& nm, const std::vector<double>& L) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < nm.size(); ++i) {
    if (nm[i] < 380.0 || nm[i + 1] > 780.0) continue;
    const double a = L[i] * cie1931_cmf(nm[i]).y, b = L[i + 1] * cie1931_cmf(nm[i + 1]).y;
    sum += 0.5 * (a + b) * (nm[i + 1] - nm[i]);
  }
  return kMaxLuminousEfficacy * sum;
}

std::optional<KiderFileName> parse_kider_file_name(std::string_view name) {
  if (name.size() <= kRadianceSuffix.size() ||
      name.substr(name.size() - kRadianceSuffix.size()) != kRadianceSuffix)
    return std::nullopt;
  const std::string_view stem = name.substr(0, name.size() - kRadianceSuffix.size());
  const std::size_t dash = stem.rfind("_-_");
  const std::size_t az = stem.find("____", dash == std::string_view::npos ? 0 : dash);
  const std::size_t el = stem.find("___", az == std::string_view::npos ? 0 : az + 4);
  const auto bad = [&](std::string_view what) -> InvalidArgument {
    return InvalidArgument(fmt::format(
        "'{}': {} (a radiance file is named ..._-_<i>____<azimuth>___<elevation>.asd.rad.txt)",
        excerpt(name, 96), what));
  };
  if (dash == std::string_view::npos || az == std::string_view::npos ||
      el == std::string_view::npos)
    throw bad("the name does not hold a sample index, an azimuth and an elevation");
  const std::string_view index_text = stem.substr(dash + 3, az - dash - 3);
  const std::string_view az_text = stem.substr(az + 4, el - az - 4);
  const std::string_view el_text = stem.substr(el + 3);
  KiderFileName f;
  const auto index = parse_integer(index_text);
  if (!index || *index < 0 || *index >= kKiderSampleCount)
    throw bad(fmt::format("sample index '{}' is not an integer in 0..{}", excerpt(index_text),
                          kKiderSampleCount - 1));
  f.index = static_cast<int>(*index);
  const auto a = parse_number(az_text), e = parse_number(el_text);
  if (!a || *a < 0.0 || *a >= 360.0)
    throw bad(fmt::format("azimuth '{}' is not a number in [0, 360)", excerpt(az_text)));
  if (!e || *e < 0.0 || *e > 90.0)
    throw bad(fmt::format("elevation '{}' is not a number in [0, 90]", excerpt(el_text)));
  f.file_azimuth_deg = *a;
  f.elevation_deg = *e;
  return f;
}

KiderSpectrum parse_kider_radiance(std::string_view text, std::string_view source) {
  const std::vector<Line> lines = lines_of(text);
  if (lines.empty() || trim(lines.front().text).empty())
    throw InvalidArgument(fmt::format("{}: no header line (Wavelength<TAB>name)", source));
  KiderSpectrum s;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const Line& l = lines[i];
    const auto fields = whitespace_fields(l.text);
    if (fields.empty()) continue;
    if (fields.size() != 2)
      bad_line(source, l.number,
               fmt::format("expected 2 fields (nm and radiance), found {}", fields.size()));
    const double nm = number_at(source, l.number, fields[0], "wavelength");
    const double value = number_at(source, l.number, fields[1], "radiance");
    if (!(nm > 0.0)) bad_line(source, l.number, fmt::format("wavelength {} nm is not > 0", nm));
    if (!s.wavelengths_nm.empty() && !(nm > s.wavelengths_nm.back()))
      bad_line(source, l.number,
               fmt::format("wavelength {} nm does not follow {} nm in ascending order", nm,
                           s.wavelengths_nm.back()));
    s.wavelengths_nm.push_back(nm);
    s.radiance.push_back(value);
  }
  if (s.wavelengths_nm.size() < 2)
    throw InvalidArgument(
        fmt::format("{}: fewer than 2 wavelengths after the header line", source));
  return s;
}

std::vector<PyranometerReading> parse_pyranometer(std::string_view text, std::string_view source) {
  std::vector<PyranometerReading> out;
  for (const Line& l : lines_of(text)) {
    const auto fields = whitespace_fields(l.text);
    if (fields.empty()) continue;
    if (fields.size() != 2)
      bad_line(source, l.number,
               fmt::format("expected 2 fields (W/m^2 and time), found {}", fields.size()));
    const double v = number_at(source, l.number, fields[0], "irradiance");
    if (v < 0.0) bad_line(source, l.number, fmt::format("irradiance {} W/m^2 is negative", v));
    out.push_back({v, std::string(fields[1])});
  }
  if (out.empty()) throw InvalidArgument(fmt::format("{}: no readings", source));
  return out;
}

std::optional<double> KiderCapture::global_horizontal_w_m2() const {
  if (pyranometer.empty()) return std::nullopt;
  double sum = 0.0;
  for (const auto& r : pyranometer) sum += r.global_horizontal_w_m2;
  return sum / static_cast<double>(pyranometer.size());
}

std::vector<KiderCapture> read_kider(const std::filesystem::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec))
    throw_read_error(path, fs::exists(path, ec) ? "not a folder" : "no such folder");
  if (fs::is_regular_file(path / kKiderSubsetRadianceFile, ec)) {
    const fs::path pyr = path / kKiderSubsetPyranometerFile;
    return parse_kider_subset(read_text_file(path / kKiderSubsetRadianceFile),
                              fs::is_regular_file(pyr, ec) ? read_text_file(pyr) : std::string(),
                              shown_path(path));
  }
  std::vector<fs::path> dirs;
  find_capture_dirs(path, 0, dirs);
  if (dirs.empty())
    throw InvalidArgument(fmt::format(
        "'{}': no Kider capture in it (folders of *{} files up to {} levels down, or the subset's "
        "{})",
        shown_path(path), kRadianceSuffix, kMaxSearchDepth, kKiderSubsetRadianceFile));
  std::sort(dirs.begin(), dirs.end());
  std::vector<KiderCapture> out;
  for (const fs::path& d : dirs) out.push_back(read_capture(d));
  return out;
}

namespace {

// The shipped subset's pyranometer.csv (capture,global_horizontal_w_m2,time), each reading added
// to its capture of the radiance file.
void add_subset_pyranometer(std::map<std::string, KiderCapture>& captures,
                            std::string_view pyranometer_csv, const std::string& pyr_source) {
  const std::vector<Line> plines = data_lines(pyranometer_csv);
  if (!plines.empty() && trim(plines.front().text) != "capture,global_horizontal_w_m2,time")
    bad_line(pyr_source, plines.front().number,
             "the header must be capture,global_horizontal_w_m2,time");
  for (std::size_t r = 1; r < plines.size(); ++r) {
    const auto f = comma_fields(plines[r].text);
    if (f.size() != 3)
      bad_line(pyr_source, plines[r].number, fmt::format("expected 3 fields, found {}", f.size()));
    const auto it = captures.find(std::string(f[0]));
    if (it == captures.end())
      bad_line(pyr_source, plines[r].number,
               fmt::format("capture '{}' has no radiance samples", excerpt(f[0])));
    const double v = number_at(pyr_source, plines[r].number, f[1], "global_horizontal_w_m2");
    if (v < 0.0) bad_line(pyr_source, plines[r].number, "global_horizontal_w_m2 is negative");
    it->second.pyranometer.push_back({v, std::string(f[2])});
    it->second.pyranometer_source = pyr_source;
  }
}

}  // namespace

std::vector<KiderCapture> parse_kider_subset(std::string_view radiance_csv,
                                             std::string_view pyranometer_csv,
                                             std::string_view source) {
  const std::string rad_source = fmt::format("{}/{}", source, kKiderSubsetRadianceFile);
  const std::vector<Line> lines = data_lines(radiance_csv);
  if (lines.empty()) throw InvalidArgument(fmt::format("{}: no header line", rad_source));
  const auto header = comma_fields(lines.front().text);
  constexpr std::array<std::string_view, 5> kColumns = {"capture", "index", "file_azimuth_deg",
                                                        "elevation_deg", "luminance_cd_m2"};
  if (header.size() < kColumns.size() + 2 ||
      !std::equal(kColumns.begin(), kColumns.end(), header.begin()))
    bad_line(rad_source, lines.front().number,
             "the header must be capture,index,file_azimuth_deg,elevation_deg,luminance_cd_m2 "
             "followed by at least 2 wavelengths [nm]");
  std::vector<double> nm;
  for (std::size_t i = kColumns.size(); i < header.size(); ++i) {
    nm.push_back(number_at(rad_source, lines.front().number, header[i], "wavelength"));
    if (nm.size() > 1 && !(nm.back() > nm[nm.size() - 2]))
      bad_line(rad_source, lines.front().number, "the wavelengths do not ascend");
  }
  std::map<std::string, KiderCapture> captures;
  for (std::size_t r = 1; r < lines.size(); ++r) {
    const Line& l = lines[r];
    const auto f = comma_fields(l.text);
    if (f.size() != header.size())
      bad_line(rad_source, l.number,
               fmt::format("expected {} fields, found {}", header.size(), f.size()));
    const std::string name(f[0]);
    KiderCapture& c = captures[name];
    if (c.name.empty()) {
      const auto time = capture_local_time(name);
      if (!time)
        bad_line(rad_source, l.number,
                 fmt::format("capture '{}' is not a local date and time YYYY-MM-DD___HH.MM.SS",
                             excerpt(name)));
      c.name = name;
      c.local_time = *time;
      c.wavelengths_nm = nm;
    }
    const auto index = parse_integer(f[1]);
    if (!index || *index < 0 || *index >= kKiderSampleCount)
      bad_line(rad_source, l.number,
               fmt::format("index '{}' is not an integer in 0..{}", excerpt(f[1]),
                           kKiderSampleCount - 1));
    KiderFileName fn;
    fn.index = static_cast<int>(*index);
    fn.file_azimuth_deg = number_at(rad_source, l.number, f[2], "file_azimuth_deg");
    fn.elevation_deg = number_at(rad_source, l.number, f[3], "elevation_deg");
    if (fn.file_azimuth_deg < 0.0 || fn.file_azimuth_deg >= 360.0 || fn.elevation_deg < 0.0 ||
        fn.elevation_deg > 90.0)
      bad_line(rad_source, l.number,
               "the azimuth must be in [0, 360) and the elevation in [0, 90]");
    const double luminance = number_at(rad_source, l.number, f[4], "luminance_cd_m2");
    if (!(luminance > 0.0)) bad_line(rad_source, l.number, "luminance_cd_m2 must be > 0");
    std::vector<double> values;
    for (std::size_t i = kColumns.size(); i < f.size(); ++i)
      values.push_back(number_at(rad_source, l.number, f[i], "radiance"));
    KiderSample s =
        make_sample(fn, std::move(values), nm, fmt::format("{} line {}", rad_source, l.number));
    s.luminance = luminance;  // of the original 1 nm spectrum
    c.samples.push_back(std::move(s));
  }
  if (captures.empty()) throw InvalidArgument(fmt::format("{}: no samples", rad_source));
  add_subset_pyranometer(captures, pyranometer_csv,
                         fmt::format("{}/{}", source, kKiderSubsetPyranometerFile));
  std::vector<KiderCapture> out;
  for (auto& [name, c] : captures) {
    complete_capture(c, fmt::format("{} capture {}", rad_source, name));
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<KiderCapture> shipped_kider_subset() {
  const std::string dir(kKiderSubsetDataDir);
  return parse_kider_subset(
      data::embedded_file(fmt::format("{}/{}", dir, kKiderSubsetRadianceFile)),
      data::embedded_file(fmt::format("{}/{}", dir, kKiderSubsetPyranometerFile)),
      fmt::format("data/{}", dir));
}

}  // namespace skylight::io
