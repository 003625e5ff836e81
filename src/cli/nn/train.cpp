// `skylight nn train`: a sky network on a registered model (the paper's protocol), on a sequence
// of HDR sky images (--images, optionally K-fold cross-validated), or a Pietras network on nishita
// (--network); the weights file and the training log are one output transaction.
#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <sstream>

#include "nn.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/fit/network_training.h"
#include "skylight/io/file.h"
#include "skylight/operations/operations.h"
#include "skylight/version.h"

namespace skylight::cli {

std::string percent(double fraction) {
  return fmt::format("{:.2f} %", 100.0 * fraction);
}

std::string utc_now_iso8601() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

namespace {

struct TrainCommand {
  SchemaFlags flags;
  std::string output, log;
};

std::string software() {
  return std::string("skylight ") + SKYLIGHT_VERSION;
}

void write_log(const std::string& path, const std::vector<nn::TrainLogEntry>& log) {
  if (path.empty()) return;
  std::ostringstream os;
  nn::write_log_csv(os, log);
  io::write_text_file(path, os.str());
}

int run_pietras(const TrainCommand& c, const fit::NetworkTrainingRequest& req) {
  std::optional<nn::PietrasNetwork> initial;
  fit::PietrasTraining t = req.pietras_training(initial, c.output);
  const int subnets = static_cast<int>(nn::pietras_layouts(t.kind).size());
  const int iterations = t.options.max_iterations;
  const int total = subnets * iterations;
  Progress progress("nn train");
  double last = -1.0;
  int last_net = -1;
  t.progress = [&](int k, const nn::TrainLogEntry& e) {
    if (k != last_net || e.seconds - last >= 1.0) {
      last = e.seconds;
      last_net = k;
      progress(std::min(k * iterations + e.iteration, total), total,
               fmt::format("sub-network {}/{} mse {:.3g}", k + 1, subnets, e.mse));
    }
    return true;
  };
  fit::PietrasTrainingResult result = fit::train_pietras(t);
  nn::PietrasNetwork& net = result.network;
  net.provenance.date = utc_now_iso8601();
  net.provenance.software = software();
  io::write_text_file(c.output, nn::to_json(net));
  std::string its;
  for (int i : net.provenance.iterations) its += (its.empty() ? "" : ", ") + std::to_string(i);
  write_stdout(fmt::format(
      "nn train: {} network ({} weights) on {}, {} samples, trainer {}, seed {}: iterations "
      "{}, {:.1f} s, region {}\n{}\n",
      nn::to_string(t.kind), net.parameter_count(), NishitaModel::kName, net.provenance.samples,
      nn::to_string(t.options.trainer), req.seed, its, net.provenance.training_seconds,
      net.provenance.region, result.check->summary()));
  announce_after_commit(fmt::format("wrote {}", io::shown_path(c.output)));
  return kExitOk;
}

std::string cross_validation_text(const nn::CrossValidation& cv, int kfold,
                                  const std::vector<fit::LoadedImage>& images) {
  std::string out = fmt::format(
      "{}-fold cross-validation (held out: images s with s mod {} = fold)\n", kfold, kfold);
  out += "fold  held_out_lines  test_examples  training_rmse  rmse     rel_median  rel_p95\n";
  for (std::size_t k = 0; k < cv.folds.size(); ++k) {
    const nn::FoldResult& fr = cv.folds[k];
    std::string lines;
    for (int s : fr.held_out)
      lines += fmt::format("{}{}", lines.empty() ? "" : " ", images[s].entry.line);
    out += fmt::format("{:4}  {:>14}  {:13}  {:13.5f}  {:.5f}  {:9.2f}%  {:6.2f}%\n", k + 1, lines,
                       fr.test_examples, fr.training_rmse, fr.errors.rmse,
                       100.0 * fr.errors.relative_median, 100.0 * fr.errors.relative_p95);
  }
  out += fmt::format("mean  RMSE {:.5f}, relative error median {:.2f} %, p95 {:.2f} %\n",
                     cv.mean_rmse, 100.0 * cv.mean_relative_median, 100.0 * cv.mean_relative_p95);
  return out;
}

int run_images(const TrainCommand& c, const fit::NetworkTrainingRequest& req) {
  const auto options = c.flags.bind(fit::ImageTrainingOptions::schema(),
                                    fit::ImageTrainingOptions{}, "nn train --images");
  warn_unread_layout(options.image, c.flags.values());
  Progress progress("nn train --images");
  const fit::ImageTrainingResult r = fit::train_on_images(
      options, req.sky_training(), req.samples.value_or(fit::kImageSamples),
      [&](int done, int total, const std::string& step) { progress(done, total, step); });
  nn::SkyNetwork network = r.trained.network;
  network.provenance.date = utc_now_iso8601();
  network.provenance.software = software();
  io::write_text_file(c.output, nn::to_json(network));
  write_log(c.log, r.trained.train.log);
  std::string out = fmt::format("nn train --images: {} images, {} examples, target scale {:.6g}\n",
                                r.images.size(), r.examples, r.target_scale);
  out += "line  sun_zenith_deg  sun_azimuth_deg  sun_from  sky_pixels  samples  file\n";
  for (const fit::LoadedImage& li : r.images) {
    const nn::SkyState& s = li.sampled.samples.state;
    out +=
        fmt::format("{:4}  {:14.3f}  {:15.3f}  {:8}  {:10}  {:7}  {}\n", li.entry.line,
                    rad_to_deg(s.sun_zenith), rad_to_deg(s.sun_azimuth), li.sun_source,
                    li.sampled.sky_pixels, li.sampled.samples.views.size(), li.entry.file.string());
  }
  if (r.cross_validation)
    out += cross_validation_text(*r.cross_validation, options.kfold, r.images);
  out += r.check ? r.check->summary(r.images) + "\n"
                 : "held-out captures: none (fewer than 3 images); the error between captures is "
                   "not measured\n";
  const nn::SkyNetworkProvenance& pv = network.provenance;
  out += fmt::format(
      "final: {} {}, trainer {}, seed {}: {} iterations ({}), {:.1f} s, RMSE on the training "
      "images {:.5f}, relative error median {:.2f} %, p95 {:.2f} %\n",
      network.net.layout().describe(), nn::to_string(network.encoding), pv.trainer, pv.seed,
      pv.iterations, pv.stop, pv.training_seconds, r.errors.rmse, 100.0 * r.errors.relative_median,
      100.0 * r.errors.relative_p95);
  write_stdout(out);
  announce_after_commit(fmt::format("wrote {}", io::shown_path(c.output)));
  return kExitOk;
}

int run_sky(const TrainCommand& c, const fit::NetworkTrainingRequest& req) {
  fit::NeuralTraining t = req.sky_training();
  Progress progress("nn train");
  double last_report = -1.0;
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
  r.network.provenance.software = software();
  io::write_text_file(c.output, nn::to_json(r.network));
  write_log(c.log, r.train.log);
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
  if (r.check) out += r.check->summary() + "\n";
  write_stdout(out);
  announce_after_commit(fmt::format("wrote {}", io::shown_path(c.output)));
  return kExitOk;
}

int run_train(const TrainCommand& c) {
  using Kind = fit::NetworkTrainingRequest::Kind;
  const auto req = c.flags.bind(fit::NetworkTrainingRequest::schema(),
                                fit::NetworkTrainingRequest{}, "nn train");
  const Kind kind = req.network               ? Kind::pietras
                    : c.flags.given("images") ? Kind::images
                                              : Kind::sky;
  for (const std::string& name : fit::NetworkTrainingRequest::unread(c.flags.values(), kind))
    warn(fmt::format("{} is not read by this training ({}); ignored", flag_spelling(name),
                     kind == Kind::sky      ? "a sky network on a model"
                     : kind == Kind::images ? "--images"
                                            : "--network"));
  if (kind == Kind::pietras) return run_pietras(c, req);
  if (kind == Kind::images) return run_images(c, req);
  return run_sky(c, req);
}

}  // namespace

void add_nn_train_command(CLI::App& nn, Commands& commands) {
  auto c = std::make_shared<TrainCommand>();
  auto* train = nn.add_subcommand(
      "train",
      "train a network on a sky model or on HDR photos\n"
      "Train a network on a registered sky model (defaults: the paper's protocol) or on a sequence "
      "of HDR photos (--images); validated on held-out data (docs/NN.md).");
  c->flags.add(*train, operations::find("nn train").parameters);
  // The flags of model-source training have no meaning for images: giving them is an error.
  for (const char* name : {"source", "suns", "view-zeniths", "view-azimuths", "network"})
    c->flags.option("images")->excludes(c->flags.option(name));
  train->add_option("-o,--output", c->output, "weights file to write (JSON)")->required();
  train->add_option("--log", c->log,
                    "training log to write (CSV: restart,iteration,seconds,mse,validation_mse,"
                    "step)");
  commands.push_back({train, [c] { return run_train(*c); }});
}

}  // namespace skylight::cli
