// `nn train|validate|export|animate|study|planet` (docs/NN.md, docs/PIETRAS.md): a sky network
// on a registered model or on HDR photos, or a Pietras network on nishita; their validation, GLSL
// export, animations, the hidden-layer study and the planet of the GPU module. The work is
// fit/network_training.h's, nn/'s and models/pietras.h's.
#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <numeric>
#include <sstream>

#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/estimate/sky_sequence.h"
#include "skylight/fit/measured_training.h"
#include "skylight/fit/network_training.h"
#include "skylight/io/file.h"
#include "skylight/io/kider.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/nn/glsl.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/gpu_backend.h"
#include "skylight/operations/operations.h"
#include "skylight/render/animation.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#include "skylight/version.h"

namespace skylight::operations::detail {
namespace {

using Kind = fit::NetworkTrainingRequest::Kind;

std::string utc_now_iso8601() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string software() {
  return std::string("skylight ") + kVersion;
}

// ---- train --------------------------------------------------------------------------------------

struct ImageRow {
  int line = 0;
  double sun_zenith_deg = 0, sun_azimuth_deg = 0;
  std::string sun_from{}, file{};
  long long sky_pixels = 0, samples = 0;
};

struct FoldRow {
  int fold = 0;
  std::string held_out_lines{};
  long long test_examples = 0;
  double training_rmse = 0, rmse = 0, relative_median = 0, relative_p95 = 0;
};

struct MeasuredRow {
  std::string capture{};
  double turbidity = 0, luminance_rms_shape = 0, luminance_rms_abs = 0, preetham_rms_shape = 0;
};

// What every kind of training reports; a kind's own fields are null for the others.
struct TrainResult {
  std::string kind{}, network{}, source{}, trainer{};
  long long iterations = 0;
  std::optional<std::vector<double>> subnetwork_iterations{};
  std::optional<std::string> encoding{}, stop{}, held_out_check{}, region{};
  long long seed = 0, weights = 0;
  double seconds = 0.0;
  std::optional<long long> examples{}, samples{};
  std::optional<double> training_rmse{}, validation_rmse{}, validation_relative_median{},
      validation_relative_p95{}, target_scale{}, final_rmse{}, final_relative_median{},
      final_relative_p95{};
  std::vector<ImageRow> images{};
  std::vector<FoldRow> folds{};
  std::vector<MeasuredRow> captures{};
  std::optional<double> measured_median_shape{}, preetham_median_shape{};
};

// A measured capture left out of `nn train --measured` (train_result's `captures`).
ResultSchema<MeasuredRow> measured_row_record() {
  ResultSchema<MeasuredRow> capture;
  capture.text("capture", "the capture left out", &MeasuredRow::capture)
      .number("turbidity", "1", "its turbidity input (the fitted Preetham turbidity)",
              &MeasuredRow::turbidity, 4)
      .number("luminance_rms_shape", "1",
              "the network trained without it: relative luminance RMS after the best scale",
              &MeasuredRow::luminance_rms_shape, 4)
      .number("luminance_rms_abs", "1", "the same without the scale",
              &MeasuredRow::luminance_rms_abs, 4)
      .number("preetham_rms_shape", "1", "the fitted Preetham sky's shape RMS on the same samples",
              &MeasuredRow::preetham_rms_shape, 4);
  return capture;
}

const ResultSchema<TrainResult>& train_result() {
  using R = TrainResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<ImageRow> image;
    image.integer("line", "1", "the list's line", &ImageRow::line)
        .number("sun_zenith_deg", "deg", "the image's sun", &ImageRow::sun_zenith_deg, 3)
        .number("sun_azimuth_deg", "deg", "from north towards east", &ImageRow::sun_azimuth_deg, 3)
        .text("sun_from", "list, time or image", &ImageRow::sun_from)
        .integer("sky_pixels", "1", "pixels of the sky mask", &ImageRow::sky_pixels)
        .integer("samples", "1", "sky pixels sampled", &ImageRow::samples)
        .text("file", "the image", &ImageRow::file);
    ResultSchema<FoldRow> fold;
    fold.integer("fold", "1", "the fold (1..K)", &FoldRow::fold)
        .text("held_out_lines", "the list's lines held out", &FoldRow::held_out_lines)
        .integer("test_examples", "1", "their examples", &FoldRow::test_examples)
        .number("training_rmse", "1", "RMSE on the others (encoded outputs)",
                &FoldRow::training_rmse, 5)
        .number("rmse", "1", "RMSE on the held-out examples", &FoldRow::rmse, 5)
        .number("relative_median", "1", "their relative error, median", &FoldRow::relative_median,
                4)
        .number("relative_p95", "1", "p95", &FoldRow::relative_p95, 4);
    ResultSchema<R> s;
    s.text("kind", "sky (on a model), images, measured, or pietras (a Pietras network)", &R::kind)
        .text("network", "the architecture, or the Pietras kind", &R::network)
        .text("encoding", "the output encoding (sky networks)", &R::encoding)
        .text("source", "what it learned", &R::source)
        .text("trainer", "the trainer", &R::trainer)
        .integer("seed", "1", "the training's seed", &R::seed)
        .integer("iterations", "1", "iterations (a Pietras network: of all its sub-networks)",
                 &R::iterations)
        .numbers("subnetwork_iterations", "1", "per sub-network (pietras)",
                 &R::subnetwork_iterations)
        .text("stop", "why the training stopped", &R::stop)
        .number("seconds", "s", "the training's time", &R::seconds, 1)
        .integer("weights", "1", "the network's weights", &R::weights)
        .integer("examples", "1", "training examples", &R::examples)
        .integer("samples", "1", "samples of nishita (pietras)", &R::samples)
        .text("region", "what the samples cover (pietras)", &R::region)
        .number("target_scale", "1", "the scale the targets are divided by (images)",
                &R::target_scale)
        .number("training_rmse", "1", "RMSE on the training set (encoded outputs)",
                &R::training_rmse, 5)
        .number("validation_rmse", "1", "RMSE on the paper's validation set", &R::validation_rmse,
                5)
        .number("validation_relative_median", "1", "its relative error, median",
                &R::validation_relative_median, 4)
        .number("validation_relative_p95", "1", "p95", &R::validation_relative_p95, 4)
        .records("images", "each image of the sequence (images)", image, &R::images)
        .records("folds", "the K-fold cross-validation (images, --kfold)", fold, &R::folds)
        .records("captures",
                 "each measured capture left out in turn (measured): the network trained on the "
                 "others against it",
                 measured_row_record(), &R::captures)
        .number("measured_median_shape", "1",
                "the median over the captures left out of luminance_rms_shape (measured)",
                &R::measured_median_shape, 4)
        .number("preetham_median_shape", "1",
                "the fitted Preetham skies' median shape RMS on the same samples (measured)",
                &R::preetham_median_shape, 4)
        .number("final_rmse", "1", "the final network's RMSE on all images (or captures)",
                &R::final_rmse, 5)
        .number("final_relative_median", "1", "its relative error, median",
                &R::final_relative_median, 4)
        .number("final_relative_p95", "1", "p95", &R::final_relative_p95, 4)
        .text("held_out_check",
              "the check on data the training never saw (passed: else nothing "
              "is written)",
              &R::held_out_check);
    return s;
  }();
  return s;
}

std::string train_log(const std::vector<nn::TrainLogEntry>& log) {
  std::ostringstream os;
  nn::write_log_csv(os, log);
  return os.str();
}

TrainResult train_pietras(const Request& r, const fit::NetworkTrainingRequest& req, Result& out) {
  std::optional<nn::PietrasNetwork> initial;
  fit::PietrasTraining t = req.pietras_training(initial, r.output_path("output"));
  const int subnets = static_cast<int>(nn::pietras_layouts(t.kind).size());
  const int iterations = t.options.max_iterations;
  const int total = subnets * iterations;
  // Every iteration (a front end shows what it wants; Python checks Ctrl-C there).
  t.progress = [&](int k, const nn::TrainLogEntry& e) {
    r.progress(std::min(k * iterations + e.iteration, total), total,
               fmt::format("sub-network {}/{} mse {:.3g}", k + 1, subnets, e.mse));
    return true;
  };
  fit::PietrasTrainingResult result = fit::train_pietras(t);
  nn::PietrasNetwork& net = result.network;
  net.provenance.date = utc_now_iso8601();
  net.provenance.software = software();
  r.write_text(out, "output", nn::to_json(net));
  std::vector<double> its(net.provenance.iterations.begin(), net.provenance.iterations.end());
  TrainResult tr{.kind = "pietras",
                 .network = std::string(nn::to_string(t.kind)),
                 .source = std::string(NishitaModel::kName),
                 .trainer = std::string(nn::to_string(t.options.trainer)),
                 .iterations = static_cast<long long>(std::accumulate(its.begin(), its.end(), 0.0)),
                 .subnetwork_iterations = its,
                 .region = net.provenance.region,
                 .seed = req.seed,
                 .weights = static_cast<long long>(net.parameter_count()),
                 .seconds = net.provenance.training_seconds,
                 .samples = static_cast<long long>(net.provenance.samples)};
  if (result.check) tr.held_out_check = result.check->summary();
  return tr;
}

// A sky network trained on data (images, measured skies): written (weights, and the log when
// asked), and the result fields those trainings share. `source`: the provenance's, when given.
TrainResult written_network(const Request& r, Result& out, std::string kind,
                            const nn::TrainedSkyNetwork& trained, std::size_t examples,
                            double target_scale, const nn::ErrorStats& errors,
                            const std::string& source = {}) {
  nn::SkyNetwork network = trained.network;
  if (!source.empty()) network.provenance.source = source;
  network.provenance.date = utc_now_iso8601();
  network.provenance.software = software();
  r.write_text(out, "output", nn::to_json(network));
  if (r.output_wanted("log")) r.write_text(out, "log", train_log(trained.train.log));
  const nn::SkyNetworkProvenance& pv = network.provenance;
  return TrainResult{.kind = std::move(kind),
                     .network = network.net.layout().describe(),
                     .source = pv.source,
                     .trainer = pv.trainer,
                     .iterations = pv.iterations,
                     .encoding = std::string(nn::to_string(network.encoding)),
                     .stop = pv.stop,
                     .seed = static_cast<long long>(pv.seed),
                     .weights = static_cast<long long>(network.net.layout().parameter_count()),
                     .seconds = pv.training_seconds,
                     .examples = static_cast<long long>(examples),
                     .target_scale = target_scale,
                     .final_rmse = errors.rmse,
                     .final_relative_median = errors.relative_median,
                     .final_relative_p95 = errors.relative_p95};
}

TrainResult train_images(const Request& r, const fit::NetworkTrainingRequest& req, Result& out) {
  const auto options = r.bind(fit::ImageTrainingOptions::schema());
  const fit::ImageTrainingResult res = fit::train_on_images(
      options, req.sky_training(), req.samples.value_or(fit::kImageSamples),
      [&](int done, int total, const std::string& step) { r.progress(done, total, step); });
  TrainResult tr =
      written_network(r, out, "images", res.trained, res.examples, res.target_scale, res.errors);
  for (const fit::LoadedImage& li : res.images) {
    const nn::SkyState& s = li.sampled.samples.state;
    tr.images.push_back({li.entry.line, rad_to_deg(s.sun_zenith), rad_to_deg(s.sun_azimuth),
                         li.sun_source, li.entry.file.string(),
                         static_cast<long long>(li.sampled.sky_pixels),
                         static_cast<long long>(li.sampled.samples.views.size())});
  }
  if (res.cross_validation)
    for (std::size_t k = 0; k < res.cross_validation->folds.size(); ++k) {
      const nn::FoldResult& f = res.cross_validation->folds[k];
      std::string lines;
      for (int s : f.held_out)
        lines += fmt::format("{}{}", lines.empty() ? "" : " ", res.images[s].entry.line);
      tr.folds.push_back({static_cast<int>(k + 1), lines, static_cast<long long>(f.test_examples),
                          f.training_rmse, f.errors.rmse, f.errors.relative_median,
                          f.errors.relative_p95});
    }
  tr.held_out_check = res.check ? res.check->summary(res.images)
                                : "held-out captures: none (fewer than 3 images); the error "
                                  "between captures is not measured";
  return tr;
}

TrainResult train_measured(const Request& r, const fit::NetworkTrainingRequest& req, Result& out) {
  const std::string dir = *r.text("measured");
  fit::MeasuredSettings settings;  // the defaults of `skylight measured`
  const fit::MeasuredTrainingResult res = fit::train_on_measured(
      io::read_kider(dir), req.sky_training(), settings,
      [&](int done, int total, const std::string& step) { r.progress(done, total, step); });
  TrainResult tr = written_network(r, out, "measured", res.trained, res.examples, res.target_scale,
                                   res.errors, "measured: " + io::shown_path(dir));
  tr.measured_median_shape = res.median_shape;
  tr.preetham_median_shape = res.median_turbidity_model_shape;
  for (std::size_t k = 0; k < res.folds.size(); ++k)
    tr.captures.push_back({res.folds[k].capture, res.turbidities[k],
                           res.folds[k].luminance_rms_shape, res.folds[k].luminance_rms_abs,
                           res.folds[k].turbidity_model_rms_shape});
  tr.held_out_check = fmt::format(
      "each capture left out in turn: luminance shape RMS median {:.1f} % (bound {:.3g} %; the "
      "fitted Preetham skies {:.1f} %)",
      100.0 * res.median_shape, 100.0 * res.max_shape, 100.0 * res.median_turbidity_model_shape);
  return tr;
}

TrainResult train_sky(const Request& r, const fit::NetworkTrainingRequest& req, Result& out) {
  fit::NeuralTraining t = req.sky_training();
  // Every iteration (a front end shows what it wants; Python checks Ctrl-C there), counted over
  // the starts' short runs and the kept start's run to the end, so that it only grows.
  const int last = std::max(1, t.options.max_iterations);
  const int per_start = std::min(t.start_iterations, last);
  const int total = t.starts > 1 && t.options.initial == nullptr
                        ? t.starts * per_start + (last - per_start)
                        : last;
  int done = 0;
  t.options.progress = [&](const nn::TrainLogEntry& e) {
    done = std::min(done + 1, total);
    r.progress(done, total,
               e.restart > 0 ? fmt::format("start {} mse {:.3g}", e.restart, e.mse)
                             : fmt::format("mse {:.3g}", e.mse));
    return true;
  };
  fit::NeuralTrainingResult res = fit::train_neural_sky(t);
  res.network.provenance.date = utc_now_iso8601();
  res.network.provenance.software = software();
  r.write_text(out, "output", nn::to_json(res.network));
  if (r.output_wanted("log")) r.write_text(out, "log", train_log(res.train.log));
  const auto& pv = res.network.provenance;
  TrainResult tr{.kind = "sky",
                 .network = res.network.net.layout().describe(),
                 .source = pv.source,
                 .trainer = pv.trainer,
                 .iterations = pv.iterations,
                 .encoding = std::string(nn::to_string(res.network.encoding)),
                 .stop = pv.stop,
                 .seed = static_cast<long long>(pv.seed),
                 .weights = static_cast<long long>(res.network.net.layout().parameter_count()),
                 .seconds = pv.training_seconds,
                 .examples = static_cast<long long>(pv.turbidities.size() * pv.sun_count *
                                                    pv.view_zeniths * pv.view_azimuths),
                 .training_rmse = std::sqrt(pv.training_mse)};
  if (res.validation) {
    tr.validation_rmse = res.validation->errors.rmse;
    tr.validation_relative_median = res.validation->errors.relative_median;
    tr.validation_relative_p95 = res.validation->errors.relative_p95;
  }
  if (res.check) tr.held_out_check = res.check->summary();
  return tr;
}

Kind training_kind(const Request& r) {
  return r.given("network")    ? Kind::pietras
         : r.given("images")   ? Kind::images
         : r.given("measured") ? Kind::measured
                               : Kind::sky;
}

OperationInfo train_operation() {
  OperationInfo op{
      .name = "nn train",
      .summary = "train a network on a sky model or on HDR photos",
      .description =
          "a neural sky network trained on a registered model (the paper's protocol) "
          "or on a sequence of HDR sky images, or a Pietras network on nishita; "
          "validated on held-out data (docs/NN.md, docs/PIETRAS.md)",
      .parameters = concat(
          {fit::NetworkTrainingRequest::schema().specs(),
           fit::ImageTrainingOptions::schema().specs(),
           fit::MeasuredTrainingOptions::schema().specs(),
           {output_file("output", "the weights file (JSON)", {}),
            output_file("log",
                        "the training log (CSV: restart,iteration,seconds,mse,validation_mse,step)",
                        {}, "none")}}),
      .result = train_result().fields(),
      .result_type = "nn::SkyNetwork or nn::PietrasNetwork (the weights file)"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "images" || s.name == "init" || s.name == "mask" || s.name == "calibration")
      s.file = FileRole::input;
  // The flags of model-source training have no meaning for images: giving them is an error.
  for (const char* name : {"source", "suns", "view-zeniths", "view-azimuths", "network"})
    op.relations.push_back(excludes("images", name));
  // Measured skies are their own source: the same flags, the images and their options too.
  for (const char* name :
       {"source", "suns", "view-zeniths", "view-azimuths", "network", "images", "kfold", "mask"})
    op.relations.push_back(excludes("measured", name));
  op.relations.push_back(unread_with("log", "network", "a Pietras network keeps no log"));
  op.check = [](Request& r) {
    const auto req = r.bind(fit::NetworkTrainingRequest::schema());
    const Kind kind = training_kind(r);
    for (const std::string& name : fit::NetworkTrainingRequest::unread(r.values(), kind)) {
      r.warn(fmt::format("{} is not read by this training ({}); ignored", spelled(name),
                         kind == Kind::sky        ? "a sky network on a model"
                         : kind == Kind::images   ? spelled("images")
                         : kind == Kind::measured ? spelled("measured")
                                                  : spelled("network")));
      r.drop(name);
    }
    if (kind == Kind::pietras) {
      std::optional<nn::PietrasNetwork> initial;
      (void)req.pietras_training(initial, r.output_path("output"));
      return;
    }
    (void)req.sky_training();
    if (kind == Kind::measured) check_input_folder(r, "measured");
    if (kind != Kind::images) return;
    // Every image of the list exists and every row has its sun, before any image is read.
    fit::check_image_list(r.bind(fit::ImageTrainingOptions::schema()));
  };
  op.run = [](const Request& r, const ProgressSink&) {
    const auto req = r.bind(fit::NetworkTrainingRequest::schema());
    Result out;
    const Kind kind = training_kind(r);
    const TrainResult tr = kind == Kind::pietras    ? train_pietras(r, req, out)
                           : kind == Kind::images   ? train_images(r, req, out)
                           : kind == Kind::measured ? train_measured(r, req, out)
                                                    : train_sky(r, req, out);
    out.record = train_result().record(tr);
    return out;
  };
  return op;
}

// ---- validate -----------------------------------------------------------------------------------

// The validation sets' seed: fixed, and apart from training seeds (1, 2, ...).
constexpr std::uint64_t kValidationSeed = 1000003;

struct PietrasErrorsRecord {
  long long samples = 0, excluded_dark = 0;
  double luminance_relative_median = 0, luminance_relative_p95 = 0, luminance_relative_max = 0;
  double chromaticity_xy_median = 0, chromaticity_xy_p95 = 0, reference_scaled_median = 0;
};
PietrasErrorsRecord errors_record(const fit::PietrasErrors& e) {
  return {static_cast<long long>(e.count),
          static_cast<long long>(e.excluded),
          e.luminance_median,
          e.luminance_p95,
          e.luminance_max,
          e.chromaticity_median,
          e.chromaticity_p95,
          e.scaled_median};
}

struct SunIrradiance {
  double turbidity = 0, sun_zenith_deg = 0, sun_azimuth_deg = 0;
  std::vector<double> reference_rgb{}, network_rgb{};
};

struct ValidateResult {
  std::string weights{}, network{}, source{};
  long long weights_count = 0;
  // A sky network: its errors on the paper's validation set and the irradiance per sun.
  std::optional<std::string> architecture{}, output_encoding{};
  std::optional<double> target_scale{}, rmse{}, relative_median{}, relative_p95{}, relative_mean{},
      relative_max{}, irradiance_reference_mean{}, irradiance_network_mean{},
      irradiance_abs_difference_mean{}, irradiance_rel_difference_mean{},
      irradiance_rel_difference_max{};
  std::optional<long long> examples{}, relative_excluded{};
  std::vector<SunIrradiance> irradiance_per_sun{};
  // A Pietras network: day, twilight and night of nishita.
  std::optional<PietrasErrorsRecord> day{}, twilight{};
  std::optional<long long> night_samples{}, night_reference_dark{}, night_network_not_dark{},
      night_network_not_dark_without_shadow_test{};
  std::optional<std::string> note{};
};

const ResultSchema<PietrasErrorsRecord>& pietras_errors_result() {
  using E = PietrasErrorsRecord;
  static const ResultSchema<E> s = [] {
    ResultSchema<E> s;
    s.integer("samples", "1", "samples of the set", &E::samples)
        .integer("excluded_dark", "1", "where nishita's Y = 0", &E::excluded_dark)
        .number("luminance_relative_median", "1", "|Y_net - Y| / Y, median",
                &E::luminance_relative_median, 4)
        .number("luminance_relative_p95", "1", "p95", &E::luminance_relative_p95, 4)
        .number("luminance_relative_max", "1", "max", &E::luminance_relative_max, 4)
        .number("chromaticity_xy_median", "1", "|dxy| of CIE 1931 xy, median",
                &E::chromaticity_xy_median, 4)
        .number("chromaticity_xy_p95", "1", "p95", &E::chromaticity_xy_p95, 4)
        .number("reference_scaled_median", "1", "nishita in the network's own scale, median",
                &E::reference_scaled_median, 4);
    return s;
  }();
  return s;
}

const ResultSchema<ValidateResult>& validate_result() {
  using R = ValidateResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<SunIrradiance> sun;
    sun.number("turbidity", "1", "the sky state's", &SunIrradiance::turbidity, 2)
        .number("sun_zenith_deg", "deg", "its sun", &SunIrradiance::sun_zenith_deg, 2)
        .number("sun_azimuth_deg", "deg", "", &SunIrradiance::sun_azimuth_deg, 2)
        .numbers("reference_rgb", "", "the source's irradiance (eq. 11)",
                 &SunIrradiance::reference_rgb)
        .numbers("network_rgb", "", "the network's", &SunIrradiance::network_rgb);
    ResultSchema<R> s;
    s.text("weights", "the weights file", &R::weights)
        .text("network", "sky, pietras or log3", &R::network)
        .integer("weights_count", "1", "its weights", &R::weights_count)
        .text("source", "what it learned", &R::source)
        .text("architecture", "layers (a sky network)", &R::architecture)
        .text("output_encoding", "the output encoding (a sky network)", &R::output_encoding)
        .number("target_scale", "1", "the targets' scale (a sky network)", &R::target_scale)
        .integer("examples", "1", "validation examples (a sky network)", &R::examples)
        .number("rmse", "1", "normalised RMSE", &R::rmse, 5)
        .number("relative_median", "1", "relative error, median", &R::relative_median, 4)
        .number("relative_p95", "1", "p95", &R::relative_p95, 4)
        .number("relative_mean", "1", "mean", &R::relative_mean, 4)
        .number("relative_max", "1", "max", &R::relative_max, 4)
        .integer("relative_excluded", "1", "examples without a relative error (dark)",
                 &R::relative_excluded)
        .number("irradiance_reference_mean", "",
                "eq. 11, mean over suns and channels (source "
                "rgb units x sr)",
                &R::irradiance_reference_mean)
        .number("irradiance_network_mean", "", "the network's", &R::irradiance_network_mean)
        .number("irradiance_abs_difference_mean", "", "|difference|, mean",
                &R::irradiance_abs_difference_mean)
        .number("irradiance_rel_difference_mean", "1", "relative, mean",
                &R::irradiance_rel_difference_mean, 4)
        .number("irradiance_rel_difference_max", "1", "relative, max",
                &R::irradiance_rel_difference_max, 4)
        .records("irradiance_per_sun", "per sky state (a sky network)", sun, &R::irradiance_per_sun)
        .nested("day", "sun zenith <= 85 deg (a Pietras network)", pietras_errors_result(), &R::day)
        .nested("twilight", "85-96 deg", pietras_errors_result(), &R::twilight)
        .integer("night_samples", "1", "sun zenith 96-180 deg", &R::night_samples)
        .integer("night_reference_dark", "1", "where nishita is dark", &R::night_reference_dark)
        .integer("night_network_not_dark", "1", "of those, where the network is not",
                 &R::night_network_not_dark)
        .integer("night_network_not_dark_without_shadow_test", "1", "without its shadow test",
                 &R::night_network_not_dark_without_shadow_test)
        .text("note", "why the paper network's error is what it is", &R::note);
    return s;
  }();
  return s;
}

// Why the paper network's luminance error is what it is (docs/PIETRAS.md, "What limits the
// accuracy"), with the day set's own N / max N: given with its errors, so the number is not read
// without its cause.
std::string paper_network_note(const fit::PietrasErrors& day) {
  const std::string per_milli =
      day.scaled_median > 0.0
          ? fmt::format("{:.1f} %", 100.0 * 0.001 / (nn::kPietrasMScale * day.scaled_median))
          : std::string("unbounded");
  return fmt::format(
      "the paper network's luminance error is its M output's: N = max N (M - 0.05) / 0.9, so an "
      "error dM is a relative error dM / (0.9 N / max N) of N; N / max N has median {:.3f} on the "
      "day set (max N: the file's max_value, the brightest training samples' N or their 99.9th "
      "percentile), so dM = 0.001 is {} there. "
      "On Earth no trainer tried brought M's MSE below 6e-5 (an independent experiment's 2 % day "
      "median is not reproduced); the log3 network learns log-luminance instead (docs/PIETRAS.md)",
      day.scaled_median, per_milli);
}

ValidateResult validate_pietras(const std::string& weights, const std::string& text, int samples) {
  const nn::PietrasNetwork net = nn::pietras_from_json(text, weights);
  const fit::PietrasValidation v =
      fit::validate_pietras(net, static_cast<std::size_t>(samples), kValidationSeed);
  ValidateResult vr{.weights = weights,
                    .network = std::string(nn::to_string(net.kind)),
                    .source = net.provenance.source,
                    .weights_count = static_cast<long long>(net.parameter_count()),
                    .day = errors_record(v.day),
                    .twilight = errors_record(v.twilight),
                    .night_samples = static_cast<long long>(v.night_count),
                    .night_reference_dark = static_cast<long long>(v.night_reference_dark),
                    .night_network_not_dark = static_cast<long long>(v.night_nonzero),
                    .night_network_not_dark_without_shadow_test =
                        static_cast<long long>(v.night_ungated_nonzero)};
  if (net.kind == nn::PietrasKind::pietras) vr.note = paper_network_note(v.day);
  return vr;
}

ValidateResult validate_sky(const std::string& weights, const std::string& text,
                            const fit::ValidationOptions& o) {
  const nn::SkyNetwork sky = nn::sky_network_from_json(text, weights);
  if (sky.provenance.source == "images")
    throw InvalidArgument(
        fmt::format("{}: trained on images, not on a sky model: nn validate "
                    "needs a model source (use nn train --images --kfold)",
                    excerpt(weights)));
  const fit::NeuralValidation v =
      fit::validate_neural_sky(sky, o.suns, o.view_zeniths, o.view_azimuths);
  const nn::ErrorStats& e = v.errors;
  const nn::IrradianceStats& ir = v.irradiance;
  const double scale = sky.target_scale;
  ValidateResult vr{.weights = weights,
                    .network = "sky",
                    .source = sky.provenance.source,
                    .weights_count = static_cast<long long>(sky.net.layout().parameter_count()),
                    .architecture = sky.net.layout().describe(),
                    .output_encoding = std::string(nn::to_string(sky.encoding)),
                    .target_scale = scale,
                    .rmse = e.rmse,
                    .relative_median = e.relative_median,
                    .relative_p95 = e.relative_p95,
                    .relative_mean = e.relative_mean,
                    .relative_max = e.relative_max,
                    .irradiance_reference_mean = scale * ir.reference_mean,
                    .irradiance_network_mean = scale * ir.network_mean,
                    .irradiance_abs_difference_mean = scale * ir.abs_difference_mean,
                    .irradiance_rel_difference_mean = ir.rel_difference_mean,
                    .irradiance_rel_difference_max = ir.rel_difference_max,
                    .examples = static_cast<long long>(v.dataset.size()),
                    .relative_excluded = static_cast<long long>(e.relative_excluded)};
  for (std::size_t s = 0; s < v.dataset.states.size(); ++s) {
    const nn::SkyState& st = v.dataset.states[s];
    std::vector<double> ref, net;
    for (int c = 0; c < 3; ++c) {
      ref.push_back(scale * ir.reference[s][static_cast<std::size_t>(c)]);
      net.push_back(scale * ir.network[s][static_cast<std::size_t>(c)]);
    }
    vr.irradiance_per_sun.push_back(
        {st.turbidity, rad_to_deg(st.sun_zenith), rad_to_deg(st.sun_azimuth), ref, net});
  }
  return vr;
}

OperationInfo validate_operation() {
  OperationInfo op{
      .name = "nn validate",
      .summary = "errors of a weights file on the paper's validation set of its source",
      .description =
          "the errors of a weights file on the validation sets of its source (a sky "
          "network: the paper's protocol, Tables 1-2; a Pietras network: day, twilight "
          "and night of nishita)",
      .parameters = concat({{input_file("weights", "the weights file (JSON)", {})},
                            fit::ValidationOptions::schema().specs()}),
      .result = validate_result().fields(),
      .result_type = "fit::NeuralValidation or fit::PietrasValidation"};
  op.run = [](const Request& r, const ProgressSink&) {
    const auto o = r.bind(fit::ValidationOptions::schema());
    const std::string weights = r.text("weights").value_or("the weights");
    // Read once: a Pietras file or a sky network (load_sky_network_file's checks, on this text).
    const std::string text = r.text_file("weights");
    Result out;
    out.record = validate_result().record(nn::is_pietras_json(text)
                                              ? validate_pietras(weights, text, o.samples)
                                              : validate_sky(weights, text, o));
    return out;
  };
  return op;
}

// ---- export -------------------------------------------------------------------------------------

struct ExportResult {
  std::string network{}, weights{};
  long long weights_count = 0;
};

const ResultSchema<ExportResult>& export_result() {
  using R = ExportResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("network", "sky, pietras or log3", &R::network)
        .text("weights", "the weights file, or embedded", &R::weights)
        .integer("weights_count", "1", "the weights baked into the GLSL", &R::weights_count);
    return s;
  }();
  return s;
}

OperationInfo export_operation() {
  OperationInfo op{
      .name = "nn export",
      .summary = "write a network as a GLSL function",
      .description =
          "a network as GLSL with its weights baked in (docs/GPU.md): vec3 "
          "skylight_sky(vec3 view, vec3 sun, float turbidity); for a Pietras file vec3 "
          "skylight_pietras_at(float altitude, vec3 view, vec3 sun)",
      .parameters = {input_file("weights", "the weights file (JSON)", {}, "the embedded network"),
                     output_file("glsl", "the GLSL file written")},
      .result = export_result().fields(),
      .result_type = "text: GLSL"};
  op.run = [](const Request& r, const ProgressSink&) {
    Result out;
    ExportResult e{.network = "sky", .weights = "embedded"};
    if (!r.has_input("weights")) {
      const nn::SkyNetwork& sky = embedded_sky_network();
      e.weights_count = static_cast<long long>(sky.net.layout().parameter_count());
      r.write_text(out, "glsl", nn::glsl_sky_network_file(sky));
    } else {
      // Read once: a Pietras file or a sky network.
      e.weights = r.text("weights").value_or("the weights");
      const std::string text = r.text_file("weights");
      if (nn::is_pietras_json(text)) {
        const nn::PietrasNetwork net = nn::pietras_from_json(text, e.weights);
        e.network = nn::to_string(net.kind);
        e.weights_count = static_cast<long long>(net.parameter_count());
        r.write_text(out, "glsl", nn::glsl_pietras_network_file(net));
      } else {
        const nn::SkyNetwork sky = nn::sky_network_from_json(text, e.weights);
        e.weights_count = static_cast<long long>(sky.net.layout().parameter_count());
        r.write_text(out, "glsl", nn::glsl_sky_network_file(sky));
      }
    }
    out.record = export_result().record(e);
    return out;
  };
  return op;
}

// ---- animate ------------------------------------------------------------------------------------

// The network options of `nn animate`: a sky network's turbidity, a Pietras network's altitude.
std::vector<ParameterSpec> animate_network_specs() {
  ParameterSpec turbidity = *NeuralSkyParameters::schema().find("turbidity");
  turbidity.default_value = Absent{"3; sky networks only"};
  ParameterSpec altitude = *PietrasParameters::schema().find("observer-altitude");
  altitude.default_value = Absent{"0; Pietras networks only"};
  altitude.description = "observer above the ground, a Pietras network's density input";
  return {turbidity, altitude};
}

struct FrameRow {
  int frame = 0;
  double sun_zenith_deg = 0, sun_azimuth_deg = 0;
  std::string file{};
};
struct AnimateResult {
  std::vector<FrameRow> frames{};
  long long dark_frames = 0;
};

const ResultSchema<AnimateResult>& animate_result() {
  static const ResultSchema<AnimateResult> s = [] {
    ResultSchema<FrameRow> f;
    f.integer("frame", "1", "the frame", &FrameRow::frame)
        .number("sun_zenith_deg", "deg", "its sun", &FrameRow::sun_zenith_deg, 3)
        .number("sun_azimuth_deg", "deg", "", &FrameRow::sun_azimuth_deg, 3)
        .text("file", "the frame's file (null: kept in memory)", &FrameRow::file);
    ResultSchema<AnimateResult> s;
    s.records("frames", "one per frame", f, &AnimateResult::frames)
        .integer("dark_frames", "1",
                 "frames of a sky network with the sun below the horizon (drawn black)",
                 &AnimateResult::dark_frames);
    return s;
  }();
  return s;
}

Result run_animate(const Request& r) {
  const auto a = r.bind(render::AnimationOptions::schema());
  a.validate();
  render::RenderSettings s;
  static_cast<Camera&>(s) = a.image.camera();
  const std::optional<double> turbidity = r.number("turbidity");
  const std::optional<double> altitude = r.number("observer-altitude");
  const std::string weights = *r.text("weights");
  // A sky network or a Pietras network, read once.
  const NetworkFile file = read_network_file(weights);
  // The option the file's kind does not read is refused before any frame.
  (void)network_model(file, weights, a.frame_sun(0), turbidity, altitude);
  const std::string pattern = r.output_path("output");
  const bool strip_wanted = r.output_wanted("strip");
  io::ImageF strip(strip_wanted ? s.width * a.frames : 1, strip_wanted ? s.height : 1, 3);
  AnimateResult ar;
  Result out;
  for (int k = 0; k < a.frames; ++k) {
    r.progress(k, a.frames, fmt::format("frame {}", k));
    const auto model = network_model(file, weights, a.frame_sun(k), turbidity, altitude);
    const SunPosition& sun = model->sun();
    const render::SkyImage img = render::render_sky(*model, s);
    for (float v : img.rgb.data)
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format("frame {}: the network gives a non-finite value", k));
    // A sky network was trained for suns above the horizon; a Pietras network covers twilight
    // and night (its shadow test).
    if (!file.pietras && sun.zenith > kPi / 2) ++ar.dark_frames;
    auto md = model_metadata(*model, "sky");
    md.emplace_back("skylight:projection", std::string(to_string(a.image.projection)));
    md.emplace_back("skylight:frame", fmt::format("{} of {}", k, a.frames));
    std::string path;
    if (!pattern.empty()) {
      path = render::frame_path(pattern, k, a.frames);
      render::write_image_or_preview(path, img.rgb, md);
    } else {
      out.images[fmt::format("frame {}", k)] = img.rgb;
    }
    if (strip_wanted)
      for (int row = 0; row < s.height; ++row)
        for (int col = 0; col < s.width; ++col)
          std::copy_n(img.rgb.pixel(col, row), 3, strip.pixel(k * s.width + col, row));
    ar.frames.push_back({k, rad_to_deg(sun.zenith), rad_to_deg(sun.azimuth), path});
  }
  r.progress(a.frames, a.frames, "done");
  if (ar.dark_frames > 0)
    r.warn(
        fmt::format("{} frames have the sun below the horizon (drawn black: the network was "
                    "trained for suns above it)",
                    ar.dark_frames));
  if (strip_wanted)
    r.write_image(out, "strip", strip,
                  {{"Software", "skylight nn animate"},
                   {"Comment", fmt::format("{} frames, left to right, one exposure", a.frames)}});
  if (!pattern.empty())
    out.notices.push_back(fmt::format("wrote {} frames {}", a.frames, io::shown_path(pattern)));
  out.record = animate_result().record(ar);
  return out;
}

OperationInfo animate_operation() {
  OperationInfo op{
      .name = "nn animate",
      .summary = "environment maps of a network's sky with the sun moving",
      .description =
          "an environment-map sequence of a neural sky or a Pietras network with the "
          "sun moving between two positions or times",
      .parameters = concat(
          {{input_file("weights", "weights file (JSON): a sky network or a Pietras network", {})},
           animate_network_specs(),
           render::AnimationOptions::schema().specs(),
           {output_file("output",
                        "frame files: a pattern whose run of '#' becomes the zero-padded frame "
                        "number, .exr (float + metadata), .hdr, .pfm or .png (preview)",
                        kImageFormats),
            output_file("strip", "every frame side by side in this PNG (one exposure for all)",
                        kPngFormat, "none")}}),
      .result = animate_result().fields(),
      .result_type = "one render::SkyImage per frame"};
  op.relations.push_back(excludes("turbidity", "observer-altitude",
                                  "a sky network reads the one, a Pietras network the other"));
  op.check = [](Request& r) {
    const auto a = r.bind(render::AnimationOptions::schema());
    a.validate();
    if (r.given("output")) {
      const std::string pattern = *r.text("output");
      // Every frame's file: named by the pattern, none of them an input or the strip.
      for (int k = 0; k < a.frames; ++k) {
        const std::string path = render::frame_path(pattern, k, a.frames);
        for (const char* other : {"weights", "strip"})
          if (const auto o = r.text(other); o && std::filesystem::path(*o).lexically_normal() ==
                                                     std::filesystem::path(path).lexically_normal())
            throw InvalidArgument(fmt::format("{} frame '{}' is also {}", spelled("output"),
                                              io::shown_path(path), spelled(other)));
      }
    }
  };
  op.run = [](const Request& r, const ProgressSink&) { return run_animate(r); };
  return op;
}

// ---- study --------------------------------------------------------------------------------------

struct StudyRecord {
  int hidden = 0;
  long long weights = 0;
  double rmse = 0, variance = 0, median = 0, p95 = 0, train_s = 0, t_ms = 0, efficiency = 0,
         relative_efficiency = 0;
  std::string stop{};
};
struct StudyResult {
  std::string source{};
  long long seed = 0, repeats = 0;
  double time_limit_s = 0;
  std::vector<StudyRecord> rows{};
  int most_efficient = 0;
};

const ResultSchema<StudyResult>& study_result() {
  static const ResultSchema<StudyResult> s = [] {
    using W = StudyRecord;
    ResultSchema<W> w;
    w.integer("hidden", "1", "hidden-layer width", &W::hidden)
        .integer("weights", "1", "weights", &W::weights)
        .number("val_rmse", "1", "validation RMSE", &W::rmse, 5)
        .number("variance", "1", "rmse^2", &W::variance)
        .number("relative_median", "1", "relative error, median", &W::median, 4)
        .number("relative_p95", "1", "p95", &W::p95, 4)
        .number("train_s", "s", "training time", &W::train_s, 1)
        .text("stop", "why training stopped", &W::stop)
        .number("t_ms", "ms", "batch evaluation of the 1024 x 512 grid on one thread", &W::t_ms, 2)
        .number("efficiency", "1", "eps = 1 / (Var T), eq. 8", &W::efficiency)
        .number("relative_efficiency", "1", "eps / eps_max", &W::relative_efficiency, 3);
    ResultSchema<StudyResult> s;
    s.text("source", "the model trained on", &StudyResult::source)
        .integer("seed", "1", "the trainings' seed", &StudyResult::seed)
        .number("time_limit_s", "s", "CPU time per network", &StudyResult::time_limit_s)
        .integer("repeats", "1", "timings per width (the best kept)", &StudyResult::repeats)
        .records("widths", "per hidden-layer width", w, &StudyResult::rows)
        .integer("most_efficient", "1", "the width of the highest eps",
                 &StudyResult::most_efficient);
    return s;
  }();
  return s;
}

OperationInfo study_operation() {
  OperationInfo op{.name = "nn study",
                   .summary = "error and speed per hidden-layer width",
                   .description =
                       "the hidden-layer study of Satilmis et al. 2016 (Fig. 5, eq. "
                       "8): error, evaluation time and efficiency per hidden-layer "
                       "width",
                   .parameters = fit::HiddenLayerStudy::schema().specs(),
                   .result = study_result().fields(),
                   .result_type = "fit::StudyRow per width"};
  op.run = [](const Request& r, const ProgressSink&) {
    const auto f = r.bind(fit::HiddenLayerStudy::schema());
    const std::vector<fit::StudyRow> rows = fit::study_hidden_layers(
        f, [&](int k, int n, int h) { r.progress(k, n, fmt::format("hidden {}", h)); });
    r.progress(static_cast<int>(f.hidden.size()), static_cast<int>(f.hidden.size()), "done");
    std::size_t best = 0;
    for (std::size_t k = 1; k < rows.size(); ++k)
      if (rows[k].efficiency > rows[best].efficiency) best = k;
    StudyResult sr{f.source_model(), f.seed, f.repeats, f.time_limit_s, {}, rows[best].hidden};
    for (const fit::StudyRow& w : rows)
      sr.rows.push_back({w.hidden, static_cast<long long>(w.weights), w.rmse, w.rmse * w.rmse,
                         w.median, w.p95, w.train_s, 1e3 * w.grid_s, w.efficiency,
                         w.efficiency / rows[best].efficiency, w.stop});
    Result out;
    out.record = study_result().record(sr);
    return out;
  };
  return op;
}

// ---- planet -------------------------------------------------------------------------------------

struct PlanetResult {
  std::string network{}, view{}, renderer{};
  double altitude_m = 0, sun_zenith_deg = 0, mesh_seconds = 0, gl_seconds = 0;
  int subdivisions = 0;
  long long vertices = 0, triangles = 0;
};

const ResultSchema<PlanetResult>& planet_result() {
  using R = PlanetResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("network", "pietras or log3", &R::network)
        .text("view", "orbit or ground", &R::view)
        .number("altitude_m", "m", "the camera above the ground", &R::altitude_m, 0)
        .number("sun_zenith_deg", "deg", "the sun at the point below the camera",
                &R::sun_zenith_deg)
        .integer("subdivisions", "1", "the icosphere's level", &R::subdivisions)
        .integer("vertices", "1", "the mesh's vertices", &R::vertices)
        .integer("triangles", "1", "its triangles", &R::triangles)
        .number("vertex_terms_s", "s", "the vertex terms (CPU)", &R::mesh_seconds, 2)
        .number("gl_s", "s", "GL draw and readback", &R::gl_seconds, 3)
        .text("renderer", "the GL renderer", &R::renderer);
    return s;
  }();
  return s;
}

OperationInfo planet_operation() {
  OperationInfo op{
      .name = "nn planet",
      .summary = "a planet and its atmosphere shaded by a network, from orbit or ground",
      .description =
          "a Pietras network shading an icosphere planet and its atmosphere in a GL "
          "vertex shader, from orbit or from the ground (the GPU module; "
          "docs/PIETRAS.md)",
      .parameters = concat(
          {{input_file("weights", "the Pietras weights file (JSON)", {})},
           PlanetViewOptions::schema().specs(),
           {output_file("output",
                        "output: .exr (float + metadata), .hdr, .pfm or .png (tone-mapped preview)",
                        kImageFormats)}}),
      .result = planet_result().fields(),
      .result_type = "linear sRGB image"};
  op.check = [](Request&) { (void)gpu_backend("nn planet"); };
  op.run = [](const Request& r, const ProgressSink&) {
    const auto f = r.bind(PlanetViewOptions::schema());
    const std::string weights = r.text("weights").value_or("the weights");
    const std::string text = r.text_file("weights");
    if (!nn::is_pietras_json(text))
      throw InvalidArgument(
          fmt::format("{} '{}': not a Pietras weights file (nn train "
                      "--network pietras|log3)",
                      spelled("weights"), excerpt(weights)));
    const nn::PietrasNetwork net = nn::pietras_from_json(text, weights);
    const PlanetFrame frame = gpu_backend("nn planet").planet(net, f);
    const std::string view = f.orbit ? "orbit" : "ground";
    Result out;
    r.write_image(out, "output", frame.rgb,
                  {{"Software", "skylight nn planet"},
                   {"skylight:weights", weights},
                   {"skylight:view", view},
                   {"skylight:altitude_m", fmt::format("{}", frame.altitude_m)},
                   {"skylight:sun_zenith_deg", fmt::format("{}", f.sun_zenith_deg)},
                   {"skylight:sun_azimuth_deg", fmt::format("{}", f.sun_azimuth_deg)},
                   {"skylight:subdivisions", fmt::format("{}", f.subdivisions)},
                   {"Comment", "linear sRGB of the Pietras vertex shader (docs/PIETRAS.md)"}});
    out.record = planet_result().record(
        {std::string(nn::to_string(net.kind)), view, frame.renderer, frame.altitude_m,
         f.sun_zenith_deg, frame.mesh_seconds, frame.gl_seconds, f.subdivisions,
         static_cast<long long>(frame.vertices), static_cast<long long>(frame.triangles)});
    return out;
  };
  return op;
}

}  // namespace

std::vector<OperationInfo> nn_operations() {
  return {train_operation(),   validate_operation(), export_operation(),
          animate_operation(), study_operation(),    planet_operation()};
}

}  // namespace skylight::operations::detail
