// `skylight nn`: neural sky models (Satilmis et al. 2016; docs/NN.md). `nn train` fits a network
// to any registered sky model with the paper's protocol as defaults and writes the weights file;
// `nn validate` measures a weights file on the paper's validation set of its source (normalised
// RMSE, relative radiance error, irradiance of eq. 11 per sun position: Tables 1 and 2).
// `nn export --glsl` writes a network as a GLSL function with its weights baked in (nn/glsl.h,
// docs/GPU.md). Evaluating a network is `eval`/`render --model nn --weights FILE`.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <sstream>

#include "common.h"
#include "nn_parts.h"
#include "nn_pietras.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/fit/neural_training.h"
#include "skylight/fit/pietras_training.h"
#include "skylight/io/file.h"
#include "skylight/models/neural_sky.h"
#include "skylight/nn/glsl.h"
#include "skylight/version.h"

namespace skylight::cli {
namespace {

// Defaults of nn train --samples: Pietras trains on 800 000 random samples (§VI, results); 2000
// sky pixels per image keep a 12-image sequence at 24 000 examples (docs/NN.md).
constexpr int kPietrasSamples = 800000, kImageSamples = 2000;
// Trainer defaults of the sky networks (docs/NN.md); --network takes fit/pietras_training.h's
// (L-BFGS, kPietrasIterations, kPietrasTimeLimitS per sub-network).
constexpr const char* kSkyTrainer = "lm";
constexpr int kSkyIterations = 500;
constexpr double kSkyTimeLimitS = 60.0;

struct TrainFlags {
  std::string source = "preetham";
  int seed = 1;
  int hidden = 12;
  std::string trainer;  // empty: kSkyTrainer, with --network fit::kPietrasTrainer
  std::string inputs = nn::to_string(nn::satilmis_inputs());
  std::string encoding = "satilmis";
  std::optional<double>
      time_limit_s;    // absent: kSkyTimeLimitS, with --network fit::kPietrasTimeLimitS
  int iterations = 0;  // 0: kSkyIterations, with --network fit::kPietrasIterations
  std::optional<double> target_scale;
  int suns = 0, view_zeniths = 0, view_azimuths = 0;
  std::string output, log;
  std::string network;  // pietras, log3 (nn_pietras.h); empty: the Satilmis sky network
  int samples = 0;      // 0: the default of the mode (kPietrasSamples, kImageSamples)
  std::map<std::string, std::optional<double>> planet;  // --network: nishita's planet
  std::string init;  // --network: a weights file to continue from
};

struct ValidateFlags {
  std::string weights;
  bool json = false;
  int suns = 0, view_zeniths = 0, view_azimuths = 0;
  int samples = 20000;  // per validation set of a Pietras file
};

struct ExportFlags {
  std::string weights;  // empty: the embedded network
  std::string glsl;
};

// Sampling overrides for quick runs (tests); 0 = the paper protocol.
void add_sampling_flags(CLI::App& cmd, int& suns, int& zeniths, int& azimuths) {
  add_integer(cmd,
              {"suns", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "sun zenith angles per turbidity (0: the protocol's 20 for training, 7 for "
               "validation)"},
              suns);
  add_integer(cmd,
              {"view-zeniths", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "view zenith strata per sky (0: the protocol's 10)"},
              zeniths);
  add_integer(cmd,
              {"view-azimuths", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "view azimuth strata per sky (0: the protocol's 20)"},
              azimuths);
}

int run_train(const TrainFlags& f, const ImageTrainFlags& images) {
  if (!f.network.empty()) {
    return run_pietras_train(
        {f.network, f.source,
         f.trainer.empty() ? std::string(nn::to_string(fit::kPietrasTrainer)) : f.trainer,
         f.samples > 0 ? f.samples : kPietrasSamples, f.seed,
         f.iterations > 0 ? f.iterations : fit::kPietrasIterations,
         f.time_limit_s.value_or(fit::kPietrasTimeLimitS), f.output, f.planet, f.init},
        utc_now_iso8601(), std::string("skylight ") + SKYLIGHT_VERSION);
  }
  if (planet_given(f.planet))
    throw InvalidArgument("the planet flags (--ground-radius, ...) need --network pietras|log3");
  if (!f.init.empty()) throw InvalidArgument("--init needs --network pietras|log3");
  const auto trainer = nn::parse_trainer(f.trainer.empty() ? kSkyTrainer : f.trainer);
  if (!trainer) {
    throw InvalidArgument(
        fmt::format("--trainer: '{}' is not lm, backprop, adam or lbfgs", excerpt(f.trainer)));
  }
  const auto encoding = nn::parse_output_encoding(f.encoding);
  if (!encoding) {
    throw InvalidArgument(
        fmt::format("--encoding: '{}' is not satilmis, log, root4 or root8", excerpt(f.encoding)));
  }
  fit::NeuralTraining t;
  t.source = f.source;
  t.inputs = nn::parse_inputs(f.inputs);
  t.encoding = *encoding;
  t.hidden = {f.hidden};
  t.target_scale = f.target_scale;
  t.sun_count = f.suns;
  t.view_zeniths = f.view_zeniths;
  t.view_azimuths = f.view_azimuths;
  t.options.trainer = *trainer;
  t.options.seed = static_cast<std::uint64_t>(f.seed);
  t.options.time_limit_s = f.time_limit_s.value_or(kSkyTimeLimitS);
  t.options.max_iterations = f.iterations > 0 ? f.iterations : kSkyIterations;
  Progress progress("nn train");
  double last_report = -1.0;
  if (images_given(images))
    return run_train_images(images, t, f.output, f.log, f.samples > 0 ? f.samples : kImageSamples);
  t.options.progress = [&](const nn::TrainLogEntry& e) {
    // At most one progress line a second (the trainers log every iteration).
    const int total = t.options.max_iterations;
    if (e.seconds - last_report >= 1.0 || e.iteration == total) {
      last_report = e.seconds;
      progress(std::min(e.iteration, total), total, fmt::format("mse {:.3g}", e.mse));
    }
    return true;
  };
  fit::NeuralTrainingResult r = fit::train_neural_sky(t);
  r.network.provenance.date = utc_now_iso8601();
  r.network.provenance.software = std::string("skylight ") + SKYLIGHT_VERSION;
  io::write_text_file(f.output, nn::to_json(r.network));
  if (!f.log.empty()) {
    std::ostringstream os;
    nn::write_log_csv(os, r.train.log);
    io::write_text_file(f.log, os.str());
  }
  const auto& pv = r.network.provenance;
  std::string out = fmt::format(
      "nn train: {} {} on {} ({} examples), trainer {}, seed {}: {} iterations ({}), {:.1f} s, "
      "training RMSE {:.5f} (encoded outputs)\n",
      r.network.net.layout().describe(), nn::to_string(r.network.encoding), pv.source,
      pv.turbidities.size() * pv.sun_count * pv.view_zeniths * pv.view_azimuths, pv.trainer,
      pv.seed, pv.iterations, pv.stop, pv.training_seconds, std::sqrt(pv.training_mse));
  if (r.validation) {
    const nn::ErrorStats& e = r.validation->errors;
    out += fmt::format("validation: RMSE {:.5f}, relative error median {}, p95 {}\n", e.rmse,
                       percent(e.relative_median), percent(e.relative_p95));
  }
  out += fmt::format("wrote {}\n", f.output);
  write_stdout(out);
  return kExitOk;
}

int run_validate(const ValidateFlags& f) {
  // Read once: a Pietras file or a sky network (load_sky_network_file's checks, on this text).
  const std::string text = io::read_text_file(f.weights);
  if (nn::is_pietras_json(text)) return run_pietras_validate(f.weights, text, f.json, f.samples);
  const nn::SkyNetwork sky = nn::sky_network_from_json(text, f.weights);
  if (sky.provenance.source == "images")
    throw InvalidArgument(
        fmt::format("{}: trained on images, not on a sky model: nn validate "
                    "needs a model source (use nn train --images --kfold)",
                    excerpt(f.weights)));
  const fit::NeuralValidation v =
      fit::validate_neural_sky(sky, f.suns, f.view_zeniths, f.view_azimuths);
  const nn::ErrorStats& e = v.errors;
  const nn::IrradianceStats& ir = v.irradiance;
  const double scale = sky.target_scale;
  if (f.json) {
    nlohmann::ordered_json j;
    j["weights"] = f.weights;
    j["source"] = sky.provenance.source;
    j["architecture"] = sky.net.layout().describe();
    j["output_encoding"] = nn::to_string(sky.encoding);
    j["target_scale"] = scale;
    j["examples"] = v.dataset.size();
    j["rmse"] = e.rmse;
    j["relative_median"] = e.relative_median;
    j["relative_p95"] = e.relative_p95;
    j["relative_mean"] = e.relative_mean;
    j["relative_max"] = e.relative_max;
    j["relative_excluded"] = e.relative_excluded;
    j["irradiance_units"] = "the source's rgb() units x sr (cos-weighted hemisphere integral)";
    j["irradiance_reference_mean"] = scale * ir.reference_mean;
    j["irradiance_network_mean"] = scale * ir.network_mean;
    j["irradiance_abs_difference_mean"] = scale * ir.abs_difference_mean;
    j["irradiance_rel_difference_mean"] = ir.rel_difference_mean;
    j["irradiance_rel_difference_max"] = ir.rel_difference_max;
    nlohmann::ordered_json per = nlohmann::ordered_json::array();
    for (std::size_t s = 0; s < v.dataset.states.size(); ++s) {
      const nn::SkyState& st = v.dataset.states[s];
      nlohmann::ordered_json row;
      row["turbidity"] = st.turbidity;
      row["sun_zenith_deg"] = rad_to_deg(st.sun_zenith);
      row["sun_azimuth_deg"] = rad_to_deg(st.sun_azimuth);
      row["reference_rgb"] = {scale * ir.reference[s][0], scale * ir.reference[s][1],
                              scale * ir.reference[s][2]};
      row["network_rgb"] = {scale * ir.network[s][0], scale * ir.network[s][1],
                            scale * ir.network[s][2]};
      per.push_back(row);
    }
    j["irradiance_per_sun"] = per;
    write_stdout(j.dump(2) + "\n");
    return kExitOk;
  }
  std::string out =
      fmt::format("nn validate: {} ({} {}, source {}, target scale {}), {} validation examples\n",
                  f.weights, sky.net.layout().describe(), nn::to_string(sky.encoding),
                  sky.provenance.source, scale, v.dataset.size());
  out += fmt::format("normalised RMSE            {:.5f}\n", e.rmse);
  out += fmt::format("relative error median      {}\n", percent(e.relative_median));
  out += fmt::format("relative error p95         {}\n", percent(e.relative_p95));
  out += fmt::format("relative error mean / max  {} / {}\n", percent(e.relative_mean),
                     percent(e.relative_max));
  out += fmt::format(
      "irradiance (eq. 11, mean over suns and channels, source rgb units x sr): reference {:.4g}, "
      "network {:.4g}, |difference| {:.4g} ({} mean, {} max)\n",
      scale * ir.reference_mean, scale * ir.network_mean, scale * ir.abs_difference_mean,
      percent(ir.rel_difference_mean), percent(ir.rel_difference_max));
  out += "turbidity  sun_zenith_deg  sun_azimuth_deg  reference_G  network_G  difference\n";
  for (std::size_t s = 0; s < v.dataset.states.size(); ++s) {
    const nn::SkyState& st = v.dataset.states[s];
    out += fmt::format("{:9.2f}  {:14.2f}  {:15.2f}  {:11.5g}  {:9.5g}  {:10.3g}\n", st.turbidity,
                       rad_to_deg(st.sun_zenith), rad_to_deg(st.sun_azimuth),
                       scale * ir.reference[s][1], scale * ir.network[s][1],
                       scale * (ir.network[s][1] - ir.reference[s][1]));
  }
  write_stdout(out);
  return kExitOk;
}

int run_export(const ExportFlags& f) {
  if (f.weights.empty()) {
    io::write_text_file(f.glsl, nn::glsl_sky_network_file(embedded_sky_network()));
    return kExitOk;
  }
  // Read once: a Pietras file or a sky network.
  const std::string text = io::read_text_file(f.weights);
  io::write_text_file(f.glsl,
                      nn::is_pietras_json(text)
                          ? nn::glsl_pietras_network_file(nn::pietras_from_json(text, f.weights))
                          : nn::glsl_sky_network_file(nn::sky_network_from_json(text, f.weights)));
  return kExitOk;
}

}  // namespace

void add_nn_command(CLI::App& app, Commands& commands) {
  auto* nn_cmd = app.add_subcommand(
      "nn",
      "neural sky models (Satilmis et al. 2016): train on a sky model, validate, export as GLSL");
  nn_cmd->require_subcommand(1);

  auto tf = std::make_shared<TrainFlags>();
  auto* train = nn_cmd->add_subcommand(
      "train", "train a network on a registered sky model (defaults: the paper's protocol)");
  train->add_option("--source", tf->source, "sky model to learn (preetham, hosek, cie, ...)")
      ->capture_default_str();
  add_integer(*train,
              {"seed", "1", ParameterKind::integer, 0, 2147483647, 1,
               ParameterValue(static_cast<double>(tf->seed)),
               "seed of the initial weights (training is deterministic for a seed)"},
              tf->seed);
  add_integer(*train,
              {"hidden", "1", ParameterKind::integer, 1, 256, 1,
               ParameterValue(static_cast<double>(tf->hidden)), "neurons of the hidden layer"},
              tf->hidden);
  train->add_option("--trainer", tf->trainer,
                    fmt::format("lm (Levenberg-Marquardt), backprop (the paper's), adam, lbfgs; "
                                "default {}, with --network {}",
                                kSkyTrainer, nn::to_string(fit::kPietrasTrainer)));
  train
      ->add_option("--inputs", tf->inputs,
                   "the network's inputs, comma-separated (the paper's V_NN by default; also "
                   "log_chord, sqrt_view_z, aureole, cos_sun_zenith, sun_elevation_cbrt, "
                   "turbidity)")
      ->capture_default_str();
  train
      ->add_option("--encoding", tf->encoding,
                   "output encoding: satilmis (the paper's L_s, eq. 7), log, root4, root8 (the "
                   "last three with an identity output layer)")
      ->capture_default_str();
  add_number(*train,
             {"time-limit", "s", ParameterKind::number, 0.01, 1e6, 1,
              Absent{fmt::format("{} s, with --network {} s per sub-network", kSkyTimeLimitS,
                                 fit::kPietrasTimeLimitS)},
              "stop training after this wall time"},
             tf->time_limit_s);
  add_integer(*train,
              {"iterations", "1", ParameterKind::integer, 1, 100000000, 1,
               Absent{fmt::format("{}, with --network {} per sub-network", kSkyIterations,
                                  fit::kPietrasIterations)},
               "at most this many iterations (LM, L-BFGS) or epochs (backprop, adam)"},
              tf->iterations);
  add_number(*train,
             {"target-scale", "1", ParameterKind::number, 1e-30, 1e30, 1,
              Absent{"preetham 1000, hosek 683, other models 1000"},
              "the network learns the source's rgb() / target-scale"},
             tf->target_scale);
  add_sampling_flags(*train, tf->suns, tf->view_zeniths, tf->view_azimuths);
  train->add_option("--network", tf->network,
                    "pietras (Pietras's 4 x 4-8-4-1 per-vertex network) or log3 (3 x 4-16-16-1, "
                    "log luminance and chromaticity): learn --source nishita (docs/PIETRAS.md)");
  train->add_option("--init", tf->init,
                    "--network: continue training from this weights file (its network kind, "
                    "planet and max value; iterations and seconds add up in the provenance)");
  add_integer(*train,
              {"samples", "1", ParameterKind::integer, 16, 100000000, 1,
               Absent{fmt::format("{} with --network, {} per image with --images", kPietrasSamples,
                                  kImageSamples)},
               "--network: random samples of nishita to train on; --images: sky pixels sampled "
               "per image (all when the mask has fewer)"},
              tf->samples);
  add_planet_flags(*train, tf->planet);
  train->add_option("-o,--output", tf->output, "weights file to write (JSON)")->required();
  train->add_option("--log", tf->log,
                    "training log to write (CSV: restart,iteration,seconds,mse,validation_mse,"
                    "step)");
  auto images = add_image_train_flags(*train);
  commands.push_back({train, [tf, images] { return run_train(*tf, *images); }});

  auto vf = std::make_shared<ValidateFlags>();
  auto* validate = nn_cmd->add_subcommand(
      "validate", "errors of a weights file on the paper's validation set of its source");
  validate->add_option("--weights", vf->weights, "weights file (JSON)")->required();
  validate->add_flag("--json", vf->json, "JSON on standard output");
  add_sampling_flags(*validate, vf->suns, vf->view_zeniths, vf->view_azimuths);
  add_integer(*validate,
              {"samples", "1", ParameterKind::integer, 1, 100000000, 1,
               ParameterValue(static_cast<double>(vf->samples)),
               "Pietras files: random samples per validation set (day, twilight, night)"},
              vf->samples);
  commands.push_back({validate, [vf] { return run_validate(*vf); }});

  auto ef = std::make_shared<ExportFlags>();
  auto* exp = nn_cmd->add_subcommand(
      "export", "write a network as a GLSL function with its weights baked in (docs/GPU.md)");
  exp->add_option("--weights", ef->weights, "weights file (JSON); default: the embedded network");
  exp->add_option("--glsl", ef->glsl,
                  "GLSL file to write: vec3 skylight_sky(vec3 view, vec3 sun, float turbidity); "
                  "for a Pietras file vec3 skylight_pietras_at(float altitude, vec3 view, vec3 "
                  "sun)")
      ->required();
  commands.push_back({exp, [ef] { return run_export(*ef); }});
  add_nn_animate_command(*nn_cmd, commands);
  add_nn_study_command(*nn_cmd, commands);
  add_nn_planet_command(*nn_cmd, commands);
}

}  // namespace skylight::cli
