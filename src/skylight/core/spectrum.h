// One tabulated spectrum type: a function of wavelength [nm] given at samples and interpolated
// linearly between them, with a documented value outside the table. Every spectral table of the
// project (CIE colour-matching functions and daylight basis, Preetham's absorption coefficients and
// solar radiance, the ASTM G-173 solar irradiance, ozone cross-sections) is one of these.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skylight {

namespace data {
class CsvTable;
}

class Spectrum {
 public:
  Spectrum() = default;  // empty: value 0 everywhere
  // Samples (nm[i], values[i]); wavelengths finite, > 0 and strictly ascending, values finite, at
  // least one sample. Throws InvalidArgument naming `name` and the bad sample otherwise.
  Spectrum(std::vector<double> nm, std::vector<double> values, std::string name = "spectrum");
  // Samples on the uniform grid first_nm + i step_nm (looked up in O(1)).
  static Spectrum uniform(double first_nm, double step_nm, std::vector<double> values,
                          std::string name = "spectrum");
  // Columns `nm_column` and `value_column` of a data table; a bad table is an IoError naming the
  // table and row.
  static Spectrum from_table(const data::CsvTable& table, std::size_t nm_column,
                             std::size_t value_column, std::string_view name);

  // The value at `nm`: linear between the two samples around it (a sample's own value exactly at
  // a sample); `outside` beyond the first and last sample.
  double operator()(double nm, double outside = 0.0) const;
  // The same, nullopt outside the table.
  std::optional<double> at(double nm) const;
  // This spectrum with every value multiplied by `factor`.
  Spectrum scaled(double factor) const;

  bool empty() const { return nm_.empty(); }
  std::size_t size() const { return nm_.size(); }
  double min_nm() const;
  double max_nm() const;
  const std::vector<double>& wavelengths() const { return nm_; }
  const std::vector<double>& values() const { return values_; }
  const std::string& name() const { return name_; }

 private:
  std::vector<double> nm_, values_;
  std::string name_;
  bool uniform_ = false;
  double first_nm_ = 0.0, step_nm_ = 1.0;
};

}  // namespace skylight
