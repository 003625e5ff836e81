// libFuzzer target: the SH polynomial-table JSON loader (sh/polynomial.h, table_from_json). An
// accepted table must be consistent (coefficient count, finite values, ordered ranges) and
// survive export -> load unchanged.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "skylight/sh/polynomial.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const auto t = sh::table_from_json(text, "fuzz.json");
    fuzz::require(t.bands >= 1 && t.degree_theta >= 0 && t.degree_tau >= 0, "bad sizes");
    fuzz::require(t.tau_pieces >= 1 && t.tau_pieces <= sh::kMaxTauPieces, "tau pieces");
    const std::size_t expect = static_cast<std::size_t>(t.tau_pieces) *
                               static_cast<std::size_t>(t.bands * (t.bands + 1) / 2) * 3 *
                               static_cast<std::size_t>(t.terms());
    fuzz::require(t.coefficients.size() == expect, "coefficient count");
    for (const float c : t.coefficients) fuzz::require_finite(c, "coefficient");
    for (const double v : {t.theta_min, t.theta_max, t.tau_min, t.tau_max})
      fuzz::require_finite(v, "range");
    fuzz::require(t.theta_min <= t.theta_max && t.tau_min <= t.tau_max, "range order");
    const auto again = sh::table_from_json(sh::table_to_json(t), "again");
    fuzz::require(again.coefficients == t.coefficients, "export -> load changed coefficients");
    fuzz::require(again.theta_axis == t.theta_axis && again.tau_pieces == t.tau_pieces &&
                      again.ground_albedo == t.ground_albedo,
                  "export -> load changed the axis, pieces or ground");
  });
  return 0;
}
