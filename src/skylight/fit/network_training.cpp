#include "skylight/fit/network_training.h"
#include "skylight/io/camera_calibration.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/io/file.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/preetham.h"
#include "skylight/render/sky_render.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::fit {
namespace {

using Request = NetworkTrainingRequest;

// The nishita parameters of a Pietras network's planet (observer, sun and albedo are not the
// network's).
constexpr const char* kPlanetParameters[] = {
    "ground-radius", "top-radius", "rayleigh-scale-height", "mie-scale-height",
    "mie-g",         "ozone",      "solar-irradiance"};

ParameterSpec count_spec(const char* name, const char* help) {
  return {.name = name,
          .unit = "1",
          .kind = ParameterKind::integer,
          .min = 0,
          .max = 1000,
          .default_value = ParameterValue(0.0),
          .description = help};
}

std::vector<std::pair<std::string, nn::Trainer>> trainer_names() {
  std::vector<std::pair<std::string, nn::Trainer>> out;
  for (nn::Trainer t : {nn::Trainer::levenberg_marquardt, nn::Trainer::backprop, nn::Trainer::adam,
                        nn::Trainer::lbfgs})
    out.emplace_back(std::string(nn::to_string(t)), t);
  return out;
}

void add_training_specs(ParameterSchema<Request>& s) {
  const Request d;
  s.text(&Request::source, {.name = "source",
                            .kind = ParameterKind::text,
                            .default_value = ParameterValue(std::string(PreethamModel::kName)),
                            .description = "sky model to learn (any of `skylight models`)"})
      .integer(&Request::seed,
               {.name = "seed",
                .unit = "1",
                .kind = ParameterKind::integer,
                .min = 0,
                .max = 2147483647,
                .default_value = ParameterValue(static_cast<double>(d.seed)),
                .description = "seed of the initial weights (training is deterministic for a "
                               "seed)"})
      .integer(&Request::hidden, {.name = "hidden",
                                  .unit = "1",
                                  .kind = ParameterKind::integer,
                                  .min = 1,
                                  .max = 256,
                                  .default_value = ParameterValue(static_cast<double>(d.hidden)),
                                  .description = "neurons of the hidden layer"})
      .custom(
          {.name = "trainer",
           .kind = ParameterKind::text,
           .default_value = Absent{fmt::format("{}, with --network {}", nn::to_string(kSkyTrainer),
                                               nn::to_string(kPietrasTrainer))},
           .description = "lm (Levenberg-Marquardt), backprop (the paper's), adam, lbfgs",
           .choices =
               [] {
                 std::vector<std::string> c;
                 for (const auto& [n, t] : trainer_names()) c.push_back(n);
                 return c;
               }()},
          [](Request& r, const ParameterValue& v) {
            r.trainer = nn::parse_trainer(std::get<std::string>(v));
          },
          [](const Request& r) -> std::optional<ParameterValue> {
            if (!r.trainer) return std::nullopt;
            return std::string(nn::to_string(*r.trainer));
          })
      .custom(
          {.name = "inputs",
           .kind = ParameterKind::text,
           .default_value = ParameterValue(nn::to_string(nn::satilmis_inputs())),
           .description =
               "the network's inputs, comma-separated (the paper's V_NN by default; also "
               "log_chord, sqrt_view_z, aureole, cos_sun_zenith, sun_elevation_cbrt, turbidity)"},
          [](Request& r, const ParameterValue& v) {
            r.inputs = nn::parse_inputs(std::get<std::string>(v));
          },
          [](const Request& r) -> std::optional<ParameterValue> { return nn::to_string(r.inputs); })
      .choice(
          &Request::encoding,
          {.name = "encoding",
           .kind = ParameterKind::text,
           .default_value = ParameterValue(std::string("satilmis")),
           .description =
               "output encoding: satilmis (the paper's L_s, eq. 7), log, root4, root8 (the last "
               "three with an identity output layer)"},
          {{"satilmis", nn::OutputEncoding::satilmis},
           {"log", nn::OutputEncoding::log},
           {"root4", nn::OutputEncoding::root4},
           {"root8", nn::OutputEncoding::root8}})
      .optional_number(
          &Request::time_limit_s,
          {.name = "time-limit",
           .unit = "s",
           .min = 0.01,
           .max = 1e6,
           .default_value = Absent{fmt::format(
               "{} s, with --network {} s per sub-network on average (pietras: M {:.0f} s, R, G, "
               "B {:.0f} s each)",
               kSkyTimeLimitS, kPietrasTimeLimitS,
               kPietrasTimeLimitS * pietras_time_shares(nn::PietrasKind::pietras)[3],
               kPietrasTimeLimitS * pietras_time_shares(nn::PietrasKind::pietras)[0])},
           .description = "stop training after this much CPU time (all threads; not wall time, "
                          "so a result does not depend on the machine's load)"})
      .optional_integer(
          &Request::iterations,
          {.name = "iterations",
           .unit = "1",
           .kind = ParameterKind::integer,
           .min = 1,
           .max = 100000000,
           .default_value = Absent{fmt::format("{}, with --network {} per sub-network",
                                               kSkyIterations, kPietrasIterations)},
           .description = "at most this many iterations (LM, L-BFGS) or epochs (backprop, adam)"})
      .integer(&Request::starts,
               {.name = "starts",
                .unit = "1",
                .kind = ParameterKind::integer,
                .min = 1,
                .max = 1000,
                .default_value = ParameterValue(static_cast<double>(d.starts)),
                .description = "independent starts, each trained --start-iterations and judged "
                               "on held-out skies (--images: held-out captures); the best is "
                               "trained on (sky networks)"})
      .integer(&Request::start_iterations,
               {.name = "start-iterations",
                .unit = "1",
                .kind = ParameterKind::integer,
                .min = 1,
                .max = 100000,
                .default_value = ParameterValue(static_cast<double>(d.start_iterations)),
                .description = "iterations of each start before they are compared"})
      .optional_number(
          &Request::max_error_percent,
          {.name = "max-error",
           .unit = "%",
           .min = 0.01,
           .max = 1e6,
           .default_value = Absent{fmt::format(
               "the source's (its registry entry; e.g. preetham 12 %, hosek 30 %); --images "
               "{:g} %; --network: the region's ({} {:g} %, {} {:g} %)",
               100.0 * kImageMaxRelativeP95, pietras_region_policy(PietrasRegion::full).name,
               100.0 * pietras_region_policy(PietrasRegion::full).max_luminance_p95,
               pietras_region_policy(PietrasRegion::sky_dome).name,
               100.0 * pietras_region_policy(PietrasRegion::sky_dome).max_luminance_p95)},
           .description = fmt::format(
               "bound on the 95th percentile of the relative radiance error on the held-out "
               "check skies (T every 0.1; --images: the held-out captures; --network: the "
               "luminance error on {} held-out day samples); beyond it training fails and "
               "nothing is written",
               kPietrasCheckSamples)})
      .optional_number(
          &Request::target_scale,
          {.name = "target-scale",
           .unit = "1",
           .min = 1e-30,
           .max = 1e30,
           .default_value =
               Absent{"the source's (its registry entry; e.g. hosek 683, preetham 1000)"},
           .description = "the network learns the source's rgb() / target-scale"})
      .integer(&Request::suns, count_spec("suns",
                                          "sun zenith angles per turbidity (0: the protocol's 20 "
                                          "for training, 7 for validation)"))
      .integer(&Request::view_zeniths,
               count_spec("view-zeniths", "view zenith strata per sky (0: the protocol's 10)"))
      .integer(&Request::view_azimuths,
               count_spec("view-azimuths", "view azimuth strata per sky (0: the protocol's 20)"));
}

void add_pietras_specs(ParameterSchema<Request>& s) {
  s.custom(
       {.name = "network",
        .kind = ParameterKind::text,
        .default_value = Absent{"a sky network (Satilmis)"},
        .description =
            "pietras (Pietras's 4 x 4-8-4-1 per-vertex network) or log3 (3 x 4-16-16-1, log "
            "luminance and chromaticity): learn --source nishita (docs/PIETRAS.md)",
        .choices = {"pietras", "log3"}},
       [](Request& r, const ParameterValue& v) {
         r.network = nn::parse_pietras_kind(std::get<std::string>(v));
       },
       [](const Request& r) -> std::optional<ParameterValue> {
         if (!r.network) return std::nullopt;
         return std::string(nn::to_string(*r.network));
       })
      .choice(&Request::region,
              {.name = "region",
               .kind = ParameterKind::text,
               .default_value = ParameterValue(std::string("full")),
               .description = "--network: the samples' region: full (any view, altitude to the "
                              "top, any sun: the planet from orbit) or sky-dome (upward views "
                              "0-20 km, sun zenith 0-100 deg: skies seen from the ground)"},
              {{std::string(pietras_region_policy(PietrasRegion::full).name), PietrasRegion::full},
               {std::string(pietras_region_policy(PietrasRegion::sky_dome).name),
                PietrasRegion::sky_dome}})
      .text(
          &Request::init,
          {.name = "init",
           .kind = ParameterKind::text,
           .default_value = Absent{"random initial weights"},
           .description =
               "--network: continue training from this weights file (its network kind, planet and "
               "max value; iterations and seconds add up in the provenance)"})
      .optional_integer(
          &Request::samples,
          {.name = "samples",
           .unit = "1",
           .kind = ParameterKind::integer,
           .min = 16,
           .max = 100000000,
           .default_value = Absent{fmt::format("{} with --network, {} per image with --images",
                                               kPietrasSamples, kImageSamples)},
           .description = "--network: random samples of nishita to train on; --images: sky pixels "
                          "sampled per image (all when the mask has fewer)"});
  for (const char* name : kPlanetParameters) {
    ParameterSpec spec = *NishitaParameters::schema().find(name);
    spec.description = "--network: nishita's " + spec.description + " (recorded in the file)";
    s.custom(
        spec, [n = std::string(name)](Request& r, const ParameterValue& v) { r.planet.set(n, v); },
        [n = std::string(name)](const Request& r) -> std::optional<ParameterValue> {
          if (const ParameterValue* v = r.planet.find(n)) return *v;
          return std::nullopt;
        });
  }
}

}  // namespace

const ParameterSchema<Request>& Request::schema() {
  static const ParameterSchema<Request> s = [] {
    ParameterSchema<Request> s;
    add_training_specs(s);
    add_pietras_specs(s);
    return s;
  }();
  return s;
}

std::string Request::source_model() const {
  return source.empty() ? std::string(PreethamModel::kName) : source;
}

std::vector<std::string> Request::unread(const ParameterValues& given, Kind kind) {
  std::vector<std::string> out;
  const auto check = [&](const char* name, bool read) {
    if (!read && given.has(name)) out.emplace_back(name);
  };
  for (const char* name : {"starts", "start-iterations"}) check(name, kind != Kind::pietras);
  check("samples", kind == Kind::images || kind == Kind::pietras);
  check("region", kind == Kind::pietras);
  return out;
}

NeuralTraining Request::sky_training() const {
  if (!planet.empty())
    throw InvalidArgument(fmt::format("the planet flags ({}, ...) need {} pietras|log3",
                                      spelled("ground-radius"), spelled("network")));
  if (!init.empty())
    throw InvalidArgument(
        fmt::format("{} needs {} pietras|log3", spelled("init"), spelled("network")));
  NeuralTraining t;
  t.source = source_model();
  t.inputs = inputs;
  t.encoding = encoding;
  t.hidden = {hidden};
  t.target_scale = target_scale;
  t.sun_count = suns;
  t.view_zeniths = view_zeniths;
  t.view_azimuths = view_azimuths;
  t.options.trainer = trainer.value_or(kSkyTrainer);
  t.options.seed = static_cast<std::uint64_t>(seed);
  t.options.time_limit_s = time_limit_s.value_or(kSkyTimeLimitS);
  t.options.max_iterations = iterations.value_or(kSkyIterations);
  t.starts = starts;
  t.start_iterations = start_iterations;
  if (max_error_percent) t.max_relative_p95 = *max_error_percent / 100.0;
  return t;
}

PietrasTraining Request::pietras_training(std::optional<nn::PietrasNetwork>& initial,
                                          const std::string& output) const {
  SKYLIGHT_CHECK(network.has_value(), "pietras_training: a Pietras network");
  const std::string kind(nn::to_string(*network));
  if (source_model() != NishitaModel::kName)
    throw InvalidArgument(fmt::format("{} {}: {} must be {}, not '{}'", spelled("network"), kind,
                                      spelled("source"), NishitaModel::kName,
                                      excerpt(source_model())));
  PietrasTraining t;
  t.kind = *network;
  if (!init.empty()) {
    // Checked before minutes of training (the command's transaction would refuse it after).
    std::error_code ec;
    if (init == output || std::filesystem::equivalent(init, output, ec))
      throw InvalidArgument(fmt::format("{} '{}' is also the {} file; write to another file",
                                        spelled("output"), io::shown_path(output),
                                        spelled("init")));
    if (!planet.empty())
      throw InvalidArgument(fmt::format("{}: the planet is the file's; drop {} etc.",
                                        spelled("init"), spelled("ground-radius")));
    initial = nn::pietras_from_json(io::read_text_file(init), init);
    if (initial->kind != *network)
      throw InvalidArgument(fmt::format("{} {}: a {} network, not {} {}", spelled("init"),
                                        excerpt(init), nn::to_string(initial->kind),
                                        spelled("network"), kind));
    t.atmosphere = nishita_parameters_of(*initial);
    t.initial = &*initial;
  } else {
    NishitaParameters::schema().bind(
        planet, t.atmosphere,
        fmt::format("nn train {} {}", spelled("source"), NishitaModel::kName));
  }
  if (!(t.atmosphere.top_radius() > t.atmosphere.ground_radius_m))
    throw InvalidArgument(fmt::format("{} {} m is not above {} {} m", spelled("top-radius"),
                                      t.atmosphere.top_radius(), spelled("ground-radius"),
                                      t.atmosphere.ground_radius_m));
  t.samples = static_cast<std::size_t>(samples.value_or(kPietrasSamples));
  t.region = region;
  t.options.trainer = trainer.value_or(kPietrasTrainer);
  t.options.seed = static_cast<std::uint64_t>(seed);
  t.options.max_iterations = iterations.value_or(kPietrasIterations);
  t.options.time_limit_s = time_limit_s.value_or(kPietrasTimeLimitS);
  if (max_error_percent) t.max_luminance_p95 = *max_error_percent / 100.0;
  return t;
}

// ---- image sequences ----------------------------------------------------------------------------

namespace {

// The list's name in messages: long enough for a path.
constexpr std::size_t kListNameChars = 240;

ImageSchemaOptions sequence_images() {
  return estimate::photo_image_options(Projection::equirect, "projection",
                                       "the images' projection");
}

std::optional<SunPosition> entry_sun(const ImageTrainingOptions& o,
                                     const estimate::SequenceEntry& e, std::string& source) {
  if (e.sun_zenith_deg) {
    source = "list";
    return sun_from_degrees(*e.sun_zenith_deg, *e.sun_azimuth_deg);
  }
  if (!e.time.empty()) {
    source = "time";
    if (!o.lat_deg || !o.lon_deg)
      throw InvalidArgument(fmt::format("{}:{}: a time needs {} and {}",
                                        excerpt(o.list, kListNameChars), e.line, spelled("lat"),
                                        spelled("lon")));
    sun::SpaInput in;
    try {
      in.time = sun::parse_iso8601(e.time);
    } catch (const InvalidArgument& x) {
      throw InvalidArgument(
          fmt::format("{}:{}: {}", excerpt(o.list, kListNameChars), e.line, x.what()));
    }
    in.latitude = deg_to_rad(*o.lat_deg);
    in.longitude = deg_to_rad(*o.lon_deg);
    const sun::SpaResult r = sun::solar_position(in);
    return sun_from_degrees(rad_to_deg(r.zenith), rad_to_deg(r.azimuth));
  }
  source = "image";
  return std::nullopt;
}

}  // namespace

const ParameterSchema<ImageTrainingOptions>& ImageTrainingOptions::schema() {
  static const ParameterSchema<ImageTrainingOptions> s = [] {
    using O = ImageTrainingOptions;
    ParameterSchema<O> s;
    s.text(
         &O::list,
         {.name = "images",
          .kind = ParameterKind::text,
          .default_value = Absent{"--source"},
          .description = "train on HDR sky images instead of --source: a CSV list with a header of "
                         "file[,sun_zenith_deg,sun_azimuth_deg][,time][,mask] (docs/NN.md)"})
        .nested(&O::image, image_schema(sequence_images()))
        .text(&O::mask,
              {.name = "mask",
               .kind = ParameterKind::text,
               .default_value = Absent{"the automatic rules"},
               .description = "sky mask for every image without its own (.png, .pfm, .exr, .hdr): "
                              "nonzero = sky"})
        .optional_number(&O::lat_deg, sun::spa_parameter_spec("lat", "needed by rows with a time"))
        .optional_number(&O::lon_deg, sun::spa_parameter_spec("lon", "needed by rows with a time"))
        .integer(&O::kfold,
                 {.name = "kfold",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 0,
                  .max = 100000,
                  .default_value = ParameterValue(0.0),
                  .description = "K-fold cross-validation over the images first (K = the number of "
                                 "images: leave one image out; 0: none)"})
        .nested(&O::mask_settings, estimate::MaskSettings::schema());
    return s;
  }();
  return s;
}

namespace {

// The check network of CaptureCheck: trained without the held-out captures, the starts judged on
// their even examples, measured on their odd ones; FitFailed beyond the bound.
nn::TrainedSkyNetwork train_check_network(const nn::Dataset& ds, nn::NetworkSetup setup,
                                          const NeuralTraining& t, ImageTrainingResult& r) {
  CaptureCheck c;
  c.max_relative_p95 = t.max_relative_p95.value_or(kImageMaxRelativeP95);
  std::vector<bool> held(r.images.size(), false);
  for (std::size_t k = 1; k + 1 < r.images.size(); k += 2) {
    held[k] = true;
    c.held_out.push_back(k);
  }
  c.training_captures = r.images.size() - c.held_out.size();
  std::vector<bool> kept(held.size());
  for (std::size_t k = 0; k < held.size(); ++k) kept[k] = !held[k];
  const nn::Dataset held_out = nn::subset_by_state(ds, held);
  const nn::Dataset selection = nn::every_nth_example(held_out, 2, 0);
  const nn::Dataset measured = nn::every_nth_example(held_out, 2, 1);
  if (measured.size() == 0)
    throw InvalidArgument(
        "nn train --images: the held-out captures have too few sky samples to check the network");
  const std::vector<double> selection_targets = selection.targets(setup.encoding);
  const nn::Examples selection_ex{selection.inputs, selection_targets, selection.size()};
  setup.options.validation = &selection_ex;
  setup.options.keep_best_validation = true;
  setup.options.restarts = t.starts;
  setup.options.restart_iterations = t.start_iterations;
  nn::TrainedSkyNetwork net = nn::train_sky_network(nn::subset_by_state(ds, kept), setup);
  c.errors = nn::evaluate_errors(net.network, measured);
  r.check = c;
  if (!c.passed())
    throw FitFailed(fmt::format(
        "nn train --images: the captures are too sparse: {}; add captures between them, or "
        "accept the network with --max-error",
        c.summary(r.images)));
  return net;
}

}  // namespace

std::string CaptureCheck::summary(const std::vector<LoadedImage>& images) const {
  std::string lines;
  for (std::size_t k : held_out)
    lines += fmt::format("{}{}", lines.empty() ? "" : " ", images[k].entry.line);
  return fmt::format(
      "held-out captures (lines {}; the network trained on the other {}): relative error median "
      "{:.2f} %, p95 {:.2f} % (bound {:.3g} %)",
      lines, training_captures, 100.0 * errors.relative_median, 100.0 * errors.relative_p95,
      100.0 * max_relative_p95);
}

namespace {

std::vector<estimate::SequenceEntry> read_list(const ImageTrainingOptions& o) {
  const std::filesystem::path list_path(o.list);
  const std::vector<char> text = io::read_file(list_path);
  return estimate::parse_sequence_list(std::string_view(text.data(), text.size()),
                                       excerpt(o.list, kListNameChars), list_path.parent_path());
}

}  // namespace

void check_image_list(const ImageTrainingOptions& o) {
  for (const estimate::SequenceEntry& e : read_list(o)) {
    std::string source;
    (void)entry_sun(o, e, source);
    for (const std::filesystem::path* f : {&e.file, &e.mask}) {
      std::error_code ec;
      if (!f->empty() && !std::filesystem::is_regular_file(*f, ec))
        throw InvalidArgument(fmt::format("{}:{}: no such file '{}'",
                                          excerpt(o.list, kListNameChars), e.line,
                                          io::shown_path(*f)));
    }
  }
}

nn::NetworkSetup data_network_setup(const NeuralTraining& t) {
  nn::NetworkSetup setup;
  setup.hidden = t.hidden;
  setup.encoding = t.encoding;
  setup.options = t.options;
  setup.options.progress = nullptr;
  return setup;
}

ImageTrainingResult train_on_images(
    const ImageTrainingOptions& o, const NeuralTraining& t, int samples_per_image,
    const std::function<void(int, int, const std::string&)>& progress) {
  const auto report = [&](int done, int total, const std::string& step) {
    if (progress) progress(done, total, step);
  };
  const std::vector<estimate::SequenceEntry> entries = read_list(o);
  std::optional<io::ImageF> common_mask;
  if (!o.mask.empty()) common_mask = estimate::load_mask(o.mask);
  estimate::SequenceSampling sampling;
  sampling.mask = o.mask_settings;
  sampling.samples_per_image = samples_per_image;
  ImageTrainingResult r;
  std::vector<nn::ImageSamples> samples;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const estimate::SequenceEntry& e = entries[k];
    report(static_cast<int>(k), static_cast<int>(entries.size()), e.file.filename().string());
    LoadedImage li;
    li.entry = e;
    const std::optional<SunPosition> sun = entry_sun(o, e, li.sun_source);
    const io::ImageF image = io::read_image(e.file);
    const Camera camera = io::photo_camera(o.image, image.width, image.height);
    std::optional<io::ImageF> own_mask;
    if (!e.mask.empty()) own_mask = estimate::load_mask(e.mask);
    const io::ImageF* mask = own_mask ? &*own_mask : common_mask ? &*common_mask : nullptr;
    sampling.seed = t.options.seed + k;
    try {
      li.sampled = estimate::sample_sky_image(image, camera, sun, sampling, mask);
    } catch (const InvalidArgument& x) {
      throw InvalidArgument(fmt::format("{}:{}: {}: {}", excerpt(o.list, kListNameChars), e.line,
                                        excerpt(e.file.string()), x.what()));
    }
    samples.push_back(li.sampled.samples);
    r.images.push_back(std::move(li));
  }
  report(static_cast<int>(entries.size()), static_cast<int>(entries.size()), "images read");
  r.target_scale = t.target_scale ? *t.target_scale : nn::image_target_scale(samples);
  const nn::Dataset ds = nn::image_dataset(samples, t.inputs, r.target_scale);
  r.examples = ds.size();
  nn::NetworkSetup setup = data_network_setup(t);
  const int steps = o.kfold + 2;
  if (o.kfold > 0) {
    r.cross_validation = nn::cross_validate(ds, o.kfold, setup, [&](int k, int n) {
      report(k, steps, fmt::format("fold {} of {}", k + 1, n));
    });
  }
  nn::TrainedSkyNetwork check_network;
  if (t.check && r.images.size() >= 3) {
    report(o.kfold, steps, "check network without the held-out captures");
    check_network = train_check_network(ds, setup, t, r);
    setup.options.initial = &check_network.train.net;
  } else {
    // Nothing between two captures to hold out: the starts are judged on the training error.
    setup.options.restarts = t.starts;
    setup.options.restart_iterations = t.start_iterations;
  }
  report(o.kfold + 1, steps, "final network on all images");
  r.trained = nn::train_sky_network(ds, setup);
  r.errors = nn::evaluate_errors(r.trained.network, ds);
  return r;
}

// ---- validation and the hidden-layer study
// --------------------------------------------------------

const ParameterSchema<ValidationOptions>& ValidationOptions::schema() {
  static const ParameterSchema<ValidationOptions> s = [] {
    using V = ValidationOptions;
    ParameterSchema<V> s;
    s.integer(&V::suns, count_spec("suns",
                                   "sun zenith angles per turbidity (0: the protocol's 20 for "
                                   "training, 7 for validation)"))
        .integer(&V::view_zeniths,
                 count_spec("view-zeniths", "view zenith strata per sky (0: the protocol's 10)"))
        .integer(&V::view_azimuths,
                 count_spec("view-azimuths", "view azimuth strata per sky (0: the protocol's 20)"))
        .integer(&V::samples,
                 {.name = "samples",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 1,
                  .max = 100000000,
                  .default_value = ParameterValue(static_cast<double>(V{}.samples)),
                  .description = "Pietras files: random samples per validation set (day, "
                                 "twilight, night)"});
    return s;
  }();
  return s;
}

const ParameterSchema<HiddenLayerStudy>& HiddenLayerStudy::schema() {
  static const ParameterSchema<HiddenLayerStudy> s = [] {
    using H = HiddenLayerStudy;
    const H d;
    ParameterSchema<H> s;
    s.text(&H::source, {.name = "source",
                        .kind = ParameterKind::text,
                        .default_value = ParameterValue(std::string(HosekWilkieModel::kName)),
                        .description = "sky model to learn (the paper's study used Hosek-Wilkie)"})
        .numbers(&H::hidden, {.name = "hidden",
                              .unit = "1",
                              .kind = ParameterKind::numbers,
                              .min = 1.0,
                              .max = 256.0,
                              .count = 0,
                              .default_value = ParameterValue(d.hidden),
                              .description = "hidden-layer widths to compare (integers)"})
        .integer(&H::seed, {.name = "seed",
                            .unit = "1",
                            .kind = ParameterKind::integer,
                            .min = 0,
                            .max = 2147483647,
                            .default_value = ParameterValue(static_cast<double>(d.seed)),
                            .description = "seed of the initial weights"})
        .number(&H::time_limit_s, {.name = "time-limit",
                                   .unit = "s",
                                   .min = 0.01,
                                   .max = 1e6,
                                   .default_value = ParameterValue(d.time_limit_s),
                                   .description = "training CPU time per network (all threads)"})
        .integer(&H::iterations,
                 {.name = "iterations",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 1,
                  .max = 100000000,
                  .default_value = ParameterValue(static_cast<double>(d.iterations)),
                  .description = "at most this many LM iterations per network"})
        .integer(&H::repeats, {.name = "repeats",
                               .unit = "1",
                               .kind = ParameterKind::integer,
                               .min = 1,
                               .max = 1000,
                               .default_value = ParameterValue(static_cast<double>(d.repeats)),
                               .description = "timing repeats (the best counts)"})
        .integer(&H::suns,
                 count_spec("suns", "sun zenith angles per turbidity (0: the protocol's)"))
        .integer(&H::view_zeniths,
                 count_spec("view-zeniths", "view zenith strata per sky (0: the protocol's)"))
        .integer(&H::view_azimuths,
                 count_spec("view-azimuths", "view azimuth strata per sky (0: the protocol's)"));
    return s;
  }();
  return s;
}

std::string HiddenLayerStudy::source_model() const {
  return source.empty() ? std::string(HosekWilkieModel::kName) : source;
}

namespace {

// Best-of-repeats wall time [s] of the batch path over the grid on the calling thread.
double grid_seconds(const nn::SkyNetwork& sky, const render::PixelDirections& d, int repeats) {
  nn::SkyState state;
  state.turbidity = 3.0;
  state.sun_zenith = deg_to_rad(40.0);
  state.sun_azimuth = deg_to_rad(150.0);
  const nn::SkyNetworkBatch batch(sky, state);
  const std::size_t n = d.x.size();
  std::vector<float> r(n), g(n), b(n);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    batch.rgb(d.x.data(), d.y.data(), d.z.data(), r.data(), g.data(), b.data(), n);
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

}  // namespace

std::vector<StudyRow> study_hidden_layers(const HiddenLayerStudy& f,
                                          const std::function<void(int, int, int)>& progress) {
  render::RenderSettings grid;  // 1024 x 512 equirect
  const render::PixelDirections dirs = render::pixel_directions(grid);
  std::vector<StudyRow> rows;
  for (std::size_t k = 0; k < f.hidden.size(); ++k) {
    const int h = static_cast<int>(f.hidden[k]);
    if (progress) progress(static_cast<int>(k), static_cast<int>(f.hidden.size()), h);
    NeuralTraining t;
    t.source = f.source_model();
    t.hidden = {h};
    t.sun_count = f.suns;
    t.view_zeniths = f.view_zeniths;
    t.view_azimuths = f.view_azimuths;
    t.options.seed = static_cast<std::uint64_t>(f.seed);
    t.options.time_limit_s = f.time_limit_s;
    t.options.max_iterations = f.iterations;
    t.check = false;  // the study reports every width's errors, small ones included
    const NeuralTrainingResult r = train_neural_sky(t);
    const nn::ErrorStats& e = r.validation->errors;
    StudyRow row;
    row.hidden = h;
    row.weights = r.network.net.layout().parameter_count();
    row.rmse = e.rmse;
    row.median = e.relative_median;
    row.p95 = e.relative_p95;
    row.train_s = r.train.seconds;
    row.stop = r.train.stop;
    row.grid_s = grid_seconds(r.network, dirs, f.repeats);
    row.efficiency = 1.0 / (e.rmse * e.rmse * row.grid_s);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace skylight::fit
