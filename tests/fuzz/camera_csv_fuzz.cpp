// libFuzzer target: the camera sensitivity CSV of `skylight haze --camera-csv`
// (haze/sensitivity.h). An accepted file gives three channels sampled at strictly ascending
// wavelengths covering 380 .. 780 nm, with finite values >= 0 and a positive sum in that range.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/haze/sensitivity.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const haze::CameraSensitivity camera = haze::parse_camera_csv(text, "fuzz.csv");
    for (const Spectrum& q : camera.channel) {
      const auto& nm = q.wavelengths();
      const auto& values = q.values();
      fuzz::require(!nm.empty() && nm.size() == values.size(), "sample count");
      fuzz::require(q.min_nm() <= haze::kVisibleFirstNm && q.max_nm() >= haze::kVisibleLastNm,
                    "does not cover 380 .. 780 nm");
      double sum = 0.0;
      for (std::size_t i = 0; i < nm.size(); ++i) {
        fuzz::require_finite(nm[i], "wavelength");
        fuzz::require_finite(values[i], "sensitivity");
        fuzz::require(values[i] >= 0.0, "negative sensitivity");
        if (i > 0) fuzz::require(nm[i] > nm[i - 1], "wavelengths not ascending");
        if (nm[i] >= haze::kVisibleFirstNm && nm[i] <= haze::kVisibleLastNm) sum += values[i];
      }
      fuzz::require(sum > 0.0, "a channel of zero response accepted");
    }
  });
  return 0;
}
