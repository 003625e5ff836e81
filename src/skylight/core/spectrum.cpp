#include "skylight/core/spectrum.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "skylight/core/data.h"
#include "skylight/core/error.h"

namespace skylight {

Spectrum::Spectrum(std::vector<double> nm, std::vector<double> values, std::string name)
    : nm_(std::move(nm)), values_(std::move(values)), name_(std::move(name)) {
  if (nm_.empty() || nm_.size() != values_.size())
    throw InvalidArgument(
        fmt::format("{}: {} wavelengths for {} values (need the same number, >= 1)", name_,
                    nm_.size(), values_.size()));
  for (std::size_t i = 0; i < nm_.size(); ++i) {
    if (!(std::isfinite(nm_[i]) && nm_[i] > 0.0 && (i == 0 || nm_[i] > nm_[i - 1])))
      throw InvalidArgument(
          fmt::format("{}: wavelength {} = {} nm must be finite, > 0 and above the previous one",
                      name_, i + 1, nm_[i]));
    if (!std::isfinite(values_[i]))
      throw InvalidArgument(fmt::format("{}: value {} = {} at {} nm is not finite", name_, i + 1,
                                        values_[i], nm_[i]));
  }
}

Spectrum Spectrum::uniform(double first_nm, double step_nm, std::vector<double> values,
                           std::string name) {
  if (!(std::isfinite(first_nm) && std::isfinite(step_nm) && step_nm > 0.0))
    throw InvalidArgument(
        fmt::format("{}: uniform grid {} + i {} nm needs a finite start and step > 0", name,
                    first_nm, step_nm));
  std::vector<double> nm(values.size());
  for (std::size_t i = 0; i < nm.size(); ++i) nm[i] = first_nm + static_cast<double>(i) * step_nm;
  Spectrum s(std::move(nm), std::move(values), std::move(name));
  s.uniform_ = true;
  s.first_nm_ = first_nm;
  s.step_nm_ = step_nm;
  return s;
}

Spectrum Spectrum::from_table(const data::CsvTable& table, std::size_t nm_column,
                              std::size_t value_column, std::string_view name) {
  std::vector<double> nm = table.numbers(nm_column), values = table.numbers(value_column);
  for (std::size_t r = 1; r < nm.size(); ++r)
    if (!(nm[r] > nm[r - 1]))
      throw IoError(
          fmt::format("{} line {}: wavelength {} nm does not ascend", name, table.line(r), nm[r]));
  return Spectrum(std::move(nm), std::move(values), std::string(name));
}

double Spectrum::operator()(double nm, double outside) const {
  if (nm_.empty()) return 0.0;
  if (!(nm >= nm_.front() && nm <= nm_.back())) return outside;
  if (nm_.size() == 1) return values_.front();
  std::size_t i = 0;
  double t = 0.0;
  if (uniform_) {
    const double u = (nm - first_nm_) / step_nm_;
    i = std::min(static_cast<std::size_t>(u), nm_.size() - 2);
    t = u - static_cast<double>(i);
  } else {
    const auto it = std::upper_bound(nm_.begin(), nm_.end(), nm);
    if (it == nm_.end()) return values_.back();
    i = static_cast<std::size_t>(it - nm_.begin()) - 1;
    t = (nm - nm_[i]) / (nm_[i + 1] - nm_[i]);
  }
  return (1.0 - t) * values_[i] + t * values_[i + 1];
}

std::optional<double> Spectrum::at(double nm) const {
  if (nm_.empty() || !(nm >= nm_.front() && nm <= nm_.back())) return std::nullopt;
  return (*this)(nm);
}

Spectrum Spectrum::scaled(double factor) const {
  Spectrum s = *this;
  for (double& v : s.values_) v *= factor;
  return s;
}

double Spectrum::min_nm() const {
  return nm_.empty() ? 0.0 : nm_.front();
}
double Spectrum::max_nm() const {
  return nm_.empty() ? 0.0 : nm_.back();
}

}  // namespace skylight
