#include "nn_pietras.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "common.h"
#include "nn_parts.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/fit/pietras_training.h"
#include "skylight/io/file.h"

namespace skylight::cli {
namespace {

// The validation sets' seed: fixed, and apart from training seeds (1, 2, ...).
constexpr std::uint64_t kValidationSeed = 1000003;

nlohmann::ordered_json errors_json(const fit::PietrasErrors& e) {
  nlohmann::ordered_json j;
  j["samples"] = e.count;
  j["excluded_dark"] = e.excluded;
  j["luminance_relative_median"] = e.luminance_median;
  j["luminance_relative_p95"] = e.luminance_p95;
  j["luminance_relative_max"] = e.luminance_max;
  j["chromaticity_xy_median"] = e.chromaticity_median;
  j["chromaticity_xy_p95"] = e.chromaticity_p95;
  j["reference_scaled_median"] = e.scaled_median;
  return j;
}

std::string errors_line(const char* name, const fit::PietrasErrors& e) {
  return fmt::format(
      "{:<9} {:>7} samples: luminance error median {}, p95 {}, max {}; chromaticity |dxy| median "
      "{:.4f}, p95 {:.4f}\n",
      name, e.count - e.excluded, percent(e.luminance_median), percent(e.luminance_p95),
      percent(e.luminance_max), e.chromaticity_median, e.chromaticity_p95);
}

// The nishita parameters of add_planet_flags (observer, sun and albedo are not the network's).
constexpr const char* kPlanetParameters[] = {
    "ground-radius", "top-radius", "rayleigh-scale-height", "mie-scale-height",
    "mie-g",         "ozone",      "solar-irradiance"};

}  // namespace

void add_planet_flags(CLI::App& train, std::map<std::string, std::optional<double>>& values) {
  for (const char* name : kPlanetParameters) {
    ParameterSpec spec = *NishitaParameters::schema().find(name);
    spec.description = "--network: nishita's " + spec.description + " (recorded in the file)";
    add_number(train, spec, values[name]);
  }
}

bool planet_given(const std::map<std::string, std::optional<double>>& values) {
  return std::any_of(values.begin(), values.end(),
                     [](const auto& v) { return v.second.has_value(); });
}

int run_pietras_train(const PietrasTrainArgs& a, const std::string& date,
                      const std::string& software) {
  const auto kind = nn::parse_pietras_kind(a.network);
  if (!kind)
    throw InvalidArgument(
        fmt::format("--network: '{}' is not pietras or log3", excerpt(a.network)));
  if (a.source != NishitaModel::kName)
    throw InvalidArgument(fmt::format("--network {}: --source must be nishita, not '{}'", a.network,
                                      excerpt(a.source)));
  const auto trainer = nn::parse_trainer(a.trainer);
  if (!trainer)
    throw InvalidArgument(
        fmt::format("--trainer: '{}' is not lm, backprop, adam or lbfgs", excerpt(a.trainer)));
  fit::PietrasTraining t;
  t.kind = *kind;
  std::optional<nn::PietrasNetwork> initial;
  if (!a.init.empty()) {
    std::error_code ec;
    if (a.init == a.output || std::filesystem::equivalent(a.init, a.output, ec))
      throw InvalidArgument(
          fmt::format("-o '{}' is also the --init file; write to another file", excerpt(a.output)));
    if (planet_given(a.planet))
      throw InvalidArgument("--init: the planet is the file's; drop --ground-radius etc.");
    initial = nn::pietras_from_json(io::read_text_file(a.init), a.init);
    if (initial->kind != *kind)
      throw InvalidArgument(fmt::format("--init {}: a {} network, not --network {}",
                                        excerpt(a.init), nn::to_string(initial->kind), a.network));
    t.atmosphere = nishita_parameters_of(*initial);
    t.initial = &*initial;
  } else {
    ParameterValues planet;
    for (const auto& [name, value] : a.planet)
      if (value) planet.set(name, *value);
    NishitaParameters::schema().bind(planet, t.atmosphere, "nn train --source nishita");
  }
  if (!(t.atmosphere.top_radius() > t.atmosphere.ground_radius_m))
    throw InvalidArgument(fmt::format("--top-radius {} m is not above --ground-radius {} m",
                                      t.atmosphere.top_radius(), t.atmosphere.ground_radius_m));
  t.samples = static_cast<std::size_t>(a.samples);
  t.options.trainer = *trainer;
  t.options.seed = static_cast<std::uint64_t>(a.seed);
  t.options.max_iterations = a.iterations;
  t.options.time_limit_s = a.time_limit_s;
  const int subnets = static_cast<int>(nn::pietras_layouts(*kind).size());
  const int total = subnets * a.iterations;
  Progress progress("nn train");
  double last = -1.0;
  int last_net = -1;
  t.progress = [&](int k, const nn::TrainLogEntry& e) {
    if (k != last_net || e.seconds - last >= 1.0) {
      last = e.seconds;
      last_net = k;
      progress(std::min(k * a.iterations + e.iteration, total), total,
               fmt::format("sub-network {}/{} mse {:.3g}", k + 1, subnets, e.mse));
    }
    return true;
  };
  nn::PietrasNetwork net = fit::train_pietras(t);
  net.provenance.date = date;
  net.provenance.software = software;
  io::write_text_file(a.output, nn::to_json(net));
  std::string its;
  for (int i : net.provenance.iterations) its += (its.empty() ? "" : ", ") + std::to_string(i);
  write_stdout(fmt::format(
      "nn train: {} network ({} weights) on nishita, {} samples, trainer {}, seed {}: iterations "
      "{}, {:.1f} s\nwrote {}\n",
      a.network, net.parameter_count(), net.provenance.samples, a.trainer, a.seed, its,
      net.provenance.training_seconds, a.output));
  return kExitOk;
}

// Why the paper network's luminance error is what it is (docs/PIETRAS.md, "What limits the
// accuracy"), with the day set's own N / max N: printed with its errors, so the number is not read
// without its cause.
std::string paper_network_note(const fit::PietrasErrors& day) {
  const std::string per_milli =
      day.scaled_median > 0.0
          ? fmt::format("{:.1f} %", 100.0 * 0.001 / (nn::kPietrasMScale * day.scaled_median))
          : std::string("unbounded");
  return fmt::format(
      "the paper network's luminance error is its M output's: N = max N (M - 0.05) / 0.9, so an "
      "error dM is a relative error dM / (0.9 N / max N) of N; N / max N has median {:.3f} on the "
      "day set (max N: the brightest of the training samples), so dM = 0.001 is {} there. "
      "On Earth no trainer tried brought M's MSE below 6e-5 (an independent experiment's 2 % day "
      "median is not reproduced); the log3 network learns log-luminance instead (docs/PIETRAS.md)",
      day.scaled_median, per_milli);
}

int run_pietras_validate(const std::string& weights, const std::string& text, bool json,
                         int samples) {
  const nn::PietrasNetwork net = nn::pietras_from_json(text, weights);
  const fit::PietrasValidation v =
      fit::validate_pietras(net, static_cast<std::size_t>(samples), kValidationSeed);
  if (json) {
    nlohmann::ordered_json j;
    j["weights"] = weights;
    j["network"] = nn::to_string(net.kind);
    j["weights_count"] = net.parameter_count();
    j["source"] = net.provenance.source;
    j["luminance_error"] = "|Y_net - Y| / Y over samples with Y > 0 (Y = nishita's luminance)";
    j["chromaticity_error"] = "Euclidean distance of CIE 1931 (x, y)";
    j["day"] = errors_json(v.day);
    j["twilight"] = errors_json(v.twilight);
    j["night_samples"] = v.night_count;
    j["night_reference_dark"] = v.night_reference_dark;
    j["night_network_not_dark"] = v.night_nonzero;
    j["night_network_not_dark_without_shadow_test"] = v.night_ungated_nonzero;
    if (net.kind == nn::PietrasKind::pietras) j["note"] = paper_network_note(v.day);
    write_stdout(j.dump(2) + "\n");
    return kExitOk;
  }
  std::string out = fmt::format(
      "nn validate: {} ({} network, {} weights, source {}); altitudes 0-20 km, upward views\n",
      weights, nn::to_string(net.kind), net.parameter_count(), net.provenance.source);
  out += errors_line("day", v.day);
  out += errors_line("twilight", v.twilight);
  out += fmt::format(
      "night     {:>7} samples (sun zenith 96-180 deg): nishita dark in {}, the network not dark "
      "in {} of those ({} without the shadow test)\n",
      v.night_count, v.night_reference_dark, v.night_nonzero, v.night_ungated_nonzero);
  out += "(day: sun zenith <= 85 deg; twilight: 85-96 deg; chromaticity: |dxy| in CIE 1931 xy)\n";
  if (net.kind == nn::PietrasKind::pietras) out += "note: " + paper_network_note(v.day) + "\n";
  write_stdout(out);
  return kExitOk;
}

}  // namespace skylight::cli
