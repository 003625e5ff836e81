#include "skylight/core/colorimetry.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/spectrum.h"

namespace skylight {
namespace {

// The three columns of a table on a uniform wavelength grid (wavelength + 3 values per row).
struct UniformTriple {
  std::array<Spectrum, 3> columns;
  std::array<double, 3> at(double nm) const {
    return {columns[0](nm), columns[1](nm), columns[2](nm)};
  }
};

UniformTriple load_uniform(std::string_view path, double expected_step) {
  const auto table = data::load_table(path, /*has_header=*/false, 4);
  SKYLIGHT_CHECK(table.rows() >= 2, "colorimetric table too short");
  const double first_nm = table.number(0, 0);
  std::array<std::vector<double>, 3> values;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double nm = table.number(r, 0);
    if (std::abs(nm - (first_nm + static_cast<double>(r) * expected_step)) > 1e-9) {
      throw IoError(std::string(path) + " line " + std::to_string(r + 1) +
                    ": wavelengths are not on a uniform grid");
    }
    for (int k = 0; k < 3; ++k) values[k].push_back(table.number(r, k + 1));
  }
  const double step = table.number(1, 0) - first_nm;
  UniformTriple t;
  for (int k = 0; k < 3; ++k)
    t.columns[k] = Spectrum::uniform(first_nm, step, std::move(values[k]),
                                     fmt::format("{} column {}", path, k + 2));
  return t;
}

const UniformTriple& cmf_table() {
  static const UniformTriple t = load_uniform("cie_colorimetry/CIE_xyz_1931_2deg.csv", 1.0);
  return t;
}

const UniformTriple& daylight_table() {
  static const UniformTriple t = load_uniform("cie_colorimetry/CIE_illum_Dxx_comp.csv", 5.0);
  return t;
}

// s_mel: column 6 of the a-opic table (the cone columns hold NaN where CIE gives no value; only
// the wavelength and s_mel are read).
const Spectrum& melanopic_table() {
  static const Spectrum s = [] {
    const char* path = "cie_colorimetry/CIE_a-opic_action_spectra.csv";
    const auto table = data::load_table(path, /*has_header=*/false, 6);
    std::vector<double> values;
    for (std::size_t r = 0; r < table.rows(); ++r) {
      if (std::abs(table.number(r, 0) - (380.0 + static_cast<double>(r))) > 1e-9)
        throw IoError(fmt::format("{} line {}: wavelengths are not 380, 381, ... nm", path, r + 1));
      values.push_back(table.number(r, 5));
    }
    return Spectrum::uniform(380.0, 1.0, std::move(values), fmt::format("{} column 6", path));
  }();
  return s;
}

Matrix3 invert(const Matrix3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  SKYLIGHT_CHECK(std::abs(det) > 1e-12, "singular colour matrix");
  Matrix3 inv{};
  inv[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  inv[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  inv[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return inv;
}

// RGB -> XYZ from primaries and white point: columns are the primaries' XYZ (Y = 1) scaled so
// that r = g = b = 1 gives the white point with Y = 1.
Matrix3 make_srgb_to_xyz() {
  const std::array<Chromaticity, 3> primaries{{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}};
  Matrix3 p{};
  for (int c = 0; c < 3; ++c) {
    const Xyz v = xyY_to_xyz(primaries[c], 1.0);
    p[0][c] = v.X;
    p[1][c] = v.Y;
    p[2][c] = v.Z;
  }
  const Xyz w = xyY_to_xyz(kD65WhiteSrgb, 1.0);
  const Matrix3 pinv = invert(p);
  std::array<double, 3> s{};
  for (int i = 0; i < 3; ++i) s[i] = pinv[i][0] * w.X + pinv[i][1] * w.Y + pinv[i][2] * w.Z;
  Matrix3 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = p[r][c] * s[c];
  return m;
}

}  // namespace

Cmf cie1931_cmf(double nm) {
  const auto v = cmf_table().at(nm);
  return {v[0], v[1], v[2]};
}

double melanopic_sensitivity(double nm) {
  return melanopic_table()(nm);
}

Xyz spectrum_to_xyz(std::span<const double> wavelengths_nm, std::span<const double> values) {
  SKYLIGHT_CHECK(wavelengths_nm.size() == values.size(), "spectrum: size mismatch");
  Xyz sum;
  for (std::size_t i = 0; i + 1 < wavelengths_nm.size(); ++i) {
    const double h = wavelengths_nm[i + 1] - wavelengths_nm[i];
    SKYLIGHT_CHECK(h > 0.0, "spectrum: wavelengths must ascend");
    const Cmf a = cie1931_cmf(wavelengths_nm[i]);
    const Cmf b = cie1931_cmf(wavelengths_nm[i + 1]);
    sum.X += 0.5 * h * (a.x * values[i] + b.x * values[i + 1]);
    sum.Y += 0.5 * h * (a.y * values[i] + b.y * values[i + 1]);
    sum.Z += 0.5 * h * (a.z * values[i] + b.z * values[i + 1]);
  }
  return sum;
}

Xyz spectral_radiance_to_xyz(std::span<const double> wavelengths_nm,
                             std::span<const double> radiance) {
  const Xyz s = spectrum_to_xyz(wavelengths_nm, radiance);
  return {kMaxLuminousEfficacy * s.X, kMaxLuminousEfficacy * s.Y, kMaxLuminousEfficacy * s.Z};
}

Xyz xyY_to_xyz(Chromaticity xy, double Y) {
  if (!(xy.y > 0.0)) return {};
  return {xy.x * Y / xy.y, Y, (1.0 - xy.x - xy.y) * Y / xy.y};
}

Chromaticity chromaticity(const Xyz& c) {
  const double sum = c.X + c.Y + c.Z;
  if (!(std::abs(sum) > 0.0) || !std::isfinite(sum)) return kD65WhiteSrgb;
  return {c.X / sum, c.Y / sum};
}

const Matrix3& srgb_to_xyz_matrix() {
  static const Matrix3 m = make_srgb_to_xyz();
  return m;
}

const Matrix3& xyz_to_srgb_matrix() {
  static const Matrix3 m = invert(srgb_to_xyz_matrix());
  return m;
}

Rgb xyz_to_linear_srgb(const Xyz& c) {
  const Matrix3& m = xyz_to_srgb_matrix();
  return {m[0][0] * c.X + m[0][1] * c.Y + m[0][2] * c.Z,
          m[1][0] * c.X + m[1][1] * c.Y + m[1][2] * c.Z,
          m[2][0] * c.X + m[2][1] * c.Y + m[2][2] * c.Z};
}

Xyz linear_srgb_to_xyz(const Rgb& c) {
  const Matrix3& m = srgb_to_xyz_matrix();
  return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b,
          m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
          m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
}

DaylightBasis daylight_basis(double nm) {
  const auto v = daylight_table().at(nm);
  return {v[0], v[1], v[2]};
}

std::array<double, 2> daylight_m1_m2(Chromaticity xy) {
  const double m = 0.0241 + 0.2562 * xy.x - 0.7341 * xy.y;
  if (std::abs(m) < 1e-9) return {0.0, 0.0};
  return {(-1.3515 - 1.7703 * xy.x + 5.9114 * xy.y) / m,
          (0.0300 - 31.4424 * xy.x + 30.0717 * xy.y) / m};
}

DaylightSpectrum::DaylightSpectrum(Chromaticity xy) {
  const auto m = daylight_m1_m2(xy);
  m1_ = m[0];
  m2_ = m[1];
}

double DaylightSpectrum::operator()(double nm) const {
  const DaylightBasis b = daylight_basis(nm);
  return b.s0 + m1_ * b.s1 + m2_ * b.s2;
}

Xyz DaylightSpectrum::integral_xyz() const {
  std::vector<double> nm, s;
  for (int l = 360; l <= 830; ++l) {
    nm.push_back(l);
    s.push_back((*this)(l));
  }
  return spectrum_to_xyz(nm, s);
}

const std::array<double, 3>& daylight_basis_ybar_integrals() {
  static const std::array<double, 3> integrals = [] {
    std::array<double, 3> out{};
    // Trapezoid on the 1 nm CMF grid; S_i are interpolated linearly from their 5 nm table.
    for (int l = 360; l < 830; ++l) {
      const DaylightBasis a = daylight_basis(l), b = daylight_basis(l + 1);
      const double ya = cie1931_cmf(l).y, yb = cie1931_cmf(l + 1).y;
      out[0] += 0.5 * (a.s0 * ya + b.s0 * yb);
      out[1] += 0.5 * (a.s1 * ya + b.s1 * yb);
      out[2] += 0.5 * (a.s2 * ya + b.s2 * yb);
    }
    return out;
  }();
  return integrals;
}

Chromaticity daylight_chromaticity(double cct_kelvin) {
  const double t = std::clamp(cct_kelvin, 4000.0, 25000.0);
  const double t1 = 1.0 / t, t2 = t1 * t1, t3 = t2 * t1;
  const double x = t <= 7000.0 ? -4.6070e9 * t3 + 2.9678e6 * t2 + 0.09911e3 * t1 + 0.244063
                               : -2.0064e9 * t3 + 1.9018e6 * t2 + 0.24748e3 * t1 + 0.237040;
  return {x, -3.0 * x * x + 2.870 * x - 0.275};
}

double cct_mccamy(Chromaticity xy) {
  const double n = (xy.x - 0.3320) / (0.1858 - xy.y);
  return ((449.0 * n + 3525.0) * n + 6823.3) * n + 5520.33;
}

}  // namespace skylight
