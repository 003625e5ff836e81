// libFuzzer target: the neural sky weights loader (nn/sky_network.h, sky_network_from_json). An
// accepted network must be consistent (parameter count, one input per first-layer neuron, a
// positive finite target scale, finite weights) and survive save -> load unchanged. (Radiance
// from arbitrary finite weights may overflow; the commands refuse non-finite output.)
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "skylight/nn/sky_network.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const nn::SkyNetwork sky = nn::sky_network_from_json(text, "fuzz.json");
    const auto& layout = sky.net.layout();
    fuzz::require(static_cast<int>(sky.inputs.size()) == layout.inputs(), "input count");
    fuzz::require(sky.net.parameters().size() == layout.parameter_count(), "parameter count");
    fuzz::require(sky.target_scale > 0.0, "target scale");
    fuzz::require_finite(sky.target_scale, "target scale");
    for (const double p : sky.net.parameters()) fuzz::require_finite(p, "parameter");
    const auto again = nn::sky_network_from_json(nn::to_json(sky), "again");
    fuzz::require(std::ranges::equal(again.net.parameters(), sky.net.parameters()),
                  "save -> load changed weights");
  });
  return 0;
}
