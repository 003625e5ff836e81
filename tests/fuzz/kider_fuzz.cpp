// libFuzzer target: the Kider et al. 2014 reader's parsers (io/kider.h). The first byte picks the
// parser: a radiance file, a pyranometer file, a radiance file name, or the subset's radiance CSV
// (with a pyranometer CSV after the first form feed). Every accepted input is in range and finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/io/kider.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  fuzz::expect_parsed_or_refused([&] {
    switch (data[0] % 4) {
      case 0: {
        const io::KiderSpectrum s = io::parse_kider_radiance(text, "fuzz.asd.rad.txt");
        fuzz::require(s.wavelengths_nm.size() >= 2 && s.radiance.size() == s.wavelengths_nm.size(),
                      "spectrum sizes");
        for (std::size_t i = 0; i < s.radiance.size(); ++i) {
          fuzz::require_finite(s.radiance[i], "radiance");
          fuzz::require(s.wavelengths_nm[i] > 0.0, "wavelength <= 0");
          if (i > 0) fuzz::require(s.wavelengths_nm[i] > s.wavelengths_nm[i - 1], "not ascending");
        }
        fuzz::require_finite(io::luminance_380_780(s.wavelengths_nm, s.radiance), "luminance");
        break;
      }
      case 1:
        for (const auto& r : io::parse_pyranometer(text, "fuzz.txt")) {
          fuzz::require_finite(r.global_horizontal_w_m2, "irradiance");
          fuzz::require(r.global_horizontal_w_m2 >= 0.0, "negative irradiance");
        }
        break;
      case 2:
        if (const auto f = io::parse_kider_file_name(text)) {
          fuzz::require(f->index >= 0 && f->index < io::kKiderSampleCount, "index range");
          fuzz::require(f->file_azimuth_deg >= 0.0 && f->file_azimuth_deg < 360.0, "azimuth range");
          fuzz::require(f->elevation_deg >= 0.0 && f->elevation_deg <= 90.0, "elevation range");
        }
        break;
      default: {
        const std::size_t split = text.find('\f');
        const auto captures = io::parse_kider_subset(
            text.substr(0, split), split == std::string_view::npos ? "" : text.substr(split + 1),
            "fuzz");
        fuzz::require(!captures.empty(), "no captures accepted");
        for (const auto& c : captures) {
          fuzz::require(c.samples.size() == io::kKiderSampleCount, "a capture without 81 samples");
          for (const auto& s : c.samples) {
            fuzz::require(s.luminance > 0.0, "luminance <= 0");
            fuzz::require_finite(s.luminance, "luminance");
            fuzz::require(s.radiance.size() == c.wavelengths_nm.size(), "spectrum size");
            fuzz::require(s.zenith >= 0.0 && s.zenith <= 1.5708, "zenith range");
          }
        }
      }
    }
  });
  return 0;
}
