// `skylight nn train --images LIST.csv`: a neural sky model learnt from a sequence of HDR sky
// images (Satilmis et al. 2016 §III-D; docs/NN.md): per image the sun (from the list, from a time
// and --lat/--lon through the SPA, or found in the image), the sky mask (automatic rules, the
// list's or --mask's mask image), sky pixels sampled as examples; optionally K-fold
// cross-validation over the images (--kfold) before the final network is trained on all of them.
#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <sstream>

#include "common.h"
#include "nn_parts.h"
#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/estimate/photo.h"
#include "skylight/estimate/sky_sequence.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/nn/image_dataset.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"
#include "skylight/version.h"

namespace skylight::cli {

struct ImageTrainFlags {
  std::string list, mask;
  std::string projection = "equirect";
  FisheyeFlags fisheye;
  std::optional<double> lat_deg, lon_deg;
  int kfold = 0;
  double min_elevation_deg = 0.0, sun_exclusion_deg = 5.0, saturation = 0.999;
};

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

bool images_given(const ImageTrainFlags& f) {
  return !f.list.empty();
}

std::shared_ptr<ImageTrainFlags> add_image_train_flags(CLI::App& train) {
  auto f = std::make_shared<ImageTrainFlags>();
  auto* images =
      train.add_option("--images", f->list,
                       "train on HDR sky images instead of --source: a CSV list with a header of "
                       "file[,sun_zenith_deg,sun_azimuth_deg][,time][,mask] (docs/NN.md)");
  train.add_option("--projection", f->projection, "the images' projection: equirect|fisheye")
      ->check(CLI::IsMember({"fisheye", "equirect"}))
      ->capture_default_str();
  f->fisheye.add(train, "180", "fisheye images: field of view across the image circle");
  train.add_option("--mask", f->mask,
                   "sky mask for every image without its own (.png, .pfm, .exr, .hdr): nonzero = "
                   "sky");
  ParameterSpec lat = sun::spa_parameter_spec("lat"), lon = sun::spa_parameter_spec("lon");
  lat.default_value = Absent{"needed by rows with a time"};
  lon.default_value = Absent{"needed by rows with a time"};
  add_number(train, lat, f->lat_deg);
  add_number(train, lon, f->lon_deg);
  add_integer(train,
              {"kfold", "1", ParameterKind::integer, 0, 100000, 1, ParameterValue(0.0),
               "K-fold cross-validation over the images first (K = the number of images: leave "
               "one image out; 0: none)"},
              f->kfold);
  add_number(train,
             {"min-elevation", "deg", ParameterKind::number, 0.0, 89.0, 1, ParameterValue(0.0),
              "sky pixels above this elevation only"},
             f->min_elevation_deg);
  add_number(train,
             {"sun-exclusion", "deg", ParameterKind::number, 0.0, 90.0, 1, ParameterValue(5.0),
              "pixels within this angle of the sun are not sky (disc, aureole, flare)"},
             f->sun_exclusion_deg);
  add_number(train,
             {"saturation", "1", ParameterKind::number, 1e-6, 1.0, 1, ParameterValue(0.999),
              "pixels with a channel >= this fraction of the image's largest value are not sky "
              "(a clipped sun)"},
             f->saturation);
  // The flags of model-source training have no meaning for images: giving them is an error.
  for (const char* name : {"--source", "--suns", "--view-zeniths", "--view-azimuths", "--network"})
    if (CLI::Option* other = train.get_option_no_throw(name)) images->excludes(other);
  return f;
}

namespace {

// The list's name in messages: long enough for a path.
constexpr std::size_t kListNameChars = 240;

struct LoadedImage {
  estimate::SequenceEntry entry;
  estimate::SampledImage sampled;
  std::string sun_source;  // "list", "time", "image"
};

std::optional<SunPosition> entry_sun(const ImageTrainFlags& f, const estimate::SequenceEntry& e,
                                     std::string& source) {
  if (e.sun_zenith_deg) {
    source = "list";
    return sun_from_degrees(*e.sun_zenith_deg, *e.sun_azimuth_deg);
  }
  if (!e.time.empty()) {
    source = "time";
    if (!f.lat_deg || !f.lon_deg)
      throw InvalidArgument(fmt::format("{}:{}: a time needs --lat and --lon",
                                        excerpt(f.list, kListNameChars), e.line));
    sun::SpaInput in;
    try {
      in.time = sun::parse_iso8601(e.time);
    } catch (const InvalidArgument& x) {
      throw InvalidArgument(
          fmt::format("{}:{}: {}", excerpt(f.list, kListNameChars), e.line, x.what()));
    }
    in.latitude = deg_to_rad(*f.lat_deg);
    in.longitude = deg_to_rad(*f.lon_deg);
    const sun::SpaResult r = sun::solar_position(in);
    return sun_from_degrees(rad_to_deg(r.zenith), rad_to_deg(r.azimuth));
  }
  source = "image";
  return std::nullopt;
}

}  // namespace

int run_train_images(const ImageTrainFlags& f, const fit::NeuralTraining& t,
                     const std::string& output, const std::string& log, int samples_per_image) {
  const std::filesystem::path list_path(f.list);
  const std::vector<char> text = io::read_file(list_path);
  const std::vector<estimate::SequenceEntry> entries =
      estimate::parse_sequence_list(std::string_view(text.data(), text.size()),
                                    excerpt(f.list, kListNameChars), list_path.parent_path());
  std::optional<io::ImageF> common_mask;
  if (!f.mask.empty()) common_mask = estimate::load_mask(f.mask);
  estimate::SequenceSampling sampling;
  sampling.mask.min_elevation = deg_to_rad(f.min_elevation_deg);
  sampling.mask.sun_exclusion = deg_to_rad(f.sun_exclusion_deg);
  sampling.mask.saturation_fraction = f.saturation;
  sampling.samples_per_image = samples_per_image;

  Progress progress("nn train --images");
  std::vector<LoadedImage> loaded;
  std::vector<nn::ImageSamples> samples;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const estimate::SequenceEntry& e = entries[k];
    progress(static_cast<int>(k), static_cast<int>(entries.size()), e.file.filename().string());
    LoadedImage li;
    li.entry = e;
    const std::optional<SunPosition> sun = entry_sun(f, e, li.sun_source);
    const io::ImageF image = io::read_image(e.file);
    const Camera camera = image_camera(*parse_projection(f.projection), f.fisheye.layout(),
                                       image.width, image.height);
    std::optional<io::ImageF> own_mask;
    if (!e.mask.empty()) own_mask = estimate::load_mask(e.mask);
    const io::ImageF* mask = own_mask ? &*own_mask : common_mask ? &*common_mask : nullptr;
    sampling.seed = t.options.seed + k;
    try {
      li.sampled = estimate::sample_sky_image(image, camera, sun, sampling, mask);
    } catch (const InvalidArgument& x) {
      throw InvalidArgument(fmt::format("{}:{}: {}: {}", excerpt(f.list, kListNameChars), e.line,
                                        excerpt(e.file.string()), x.what()));
    }
    samples.push_back(li.sampled.samples);
    loaded.push_back(std::move(li));
  }
  progress(static_cast<int>(entries.size()), static_cast<int>(entries.size()), "images read");
  const double target_scale = t.target_scale ? *t.target_scale : nn::image_target_scale(samples);
  const nn::Dataset ds = nn::image_dataset(samples, t.inputs, target_scale);

  std::string out = fmt::format("nn train --images: {} images, {} examples, target scale {:.6g}\n",
                                loaded.size(), ds.size(), target_scale);
  out += "line  sun_zenith_deg  sun_azimuth_deg  sun_from  sky_pixels  samples  file\n";
  for (const LoadedImage& li : loaded) {
    const nn::SkyState& s = li.sampled.samples.state;
    out +=
        fmt::format("{:4}  {:14.3f}  {:15.3f}  {:8}  {:10}  {:7}  {}\n", li.entry.line,
                    rad_to_deg(s.sun_zenith), rad_to_deg(s.sun_azimuth), li.sun_source,
                    li.sampled.sky_pixels, li.sampled.samples.views.size(), li.entry.file.string());
  }

  nn::NetworkSetup setup;
  setup.hidden = t.hidden;
  setup.encoding = t.encoding;
  setup.options = t.options;
  setup.options.progress = nullptr;
  if (f.kfold > 0) {
    const nn::CrossValidation cv = nn::cross_validate(ds, f.kfold, setup, [&](int k, int n) {
      progress(k, n + 1, fmt::format("fold {} of {}", k + 1, n));
    });
    out += fmt::format("{}-fold cross-validation (held out: images s with s mod {} = fold)\n",
                       f.kfold, f.kfold);
    out += "fold  held_out_lines  test_examples  training_rmse  rmse     rel_median  rel_p95\n";
    for (std::size_t k = 0; k < cv.folds.size(); ++k) {
      const nn::FoldResult& fr = cv.folds[k];
      std::string lines;
      for (int s : fr.held_out)
        lines += fmt::format("{}{}", lines.empty() ? "" : " ", loaded[s].entry.line);
      out += fmt::format("{:4}  {:>14}  {:13}  {:13.5f}  {:.5f}  {:9.2f}%  {:6.2f}%\n", k + 1,
                         lines, fr.test_examples, fr.training_rmse, fr.errors.rmse,
                         100.0 * fr.errors.relative_median, 100.0 * fr.errors.relative_p95);
    }
    out += fmt::format("mean  RMSE {:.5f}, relative error median {:.2f} %, p95 {:.2f} %\n",
                       cv.mean_rmse, 100.0 * cv.mean_relative_median, 100.0 * cv.mean_relative_p95);
  }
  progress(f.kfold, f.kfold + 1, "final network on all images");
  nn::TrainedSkyNetwork r = nn::train_sky_network(ds, setup);
  r.network.provenance.date = utc_now_iso8601();
  r.network.provenance.software = std::string("skylight ") + SKYLIGHT_VERSION;
  io::write_text_file(output, nn::to_json(r.network));
  if (!log.empty()) {
    std::ostringstream os;
    nn::write_log_csv(os, r.train.log);
    io::write_text_file(log, os.str());
  }
  const nn::ErrorStats e = nn::evaluate_errors(r.network, ds);
  out += fmt::format(
      "final: {} {}, trainer {}, seed {}: {} iterations ({}), {:.1f} s, RMSE on the training "
      "images "
      "{:.5f}, relative error median {:.2f} %, p95 {:.2f} %\nwrote {}\n",
      r.network.net.layout().describe(), nn::to_string(r.network.encoding),
      r.network.provenance.trainer, r.network.provenance.seed, r.network.provenance.iterations,
      r.network.provenance.stop, r.network.provenance.training_seconds, e.rmse,
      100.0 * e.relative_median, 100.0 * e.relative_p95, output);
  write_stdout(out);
  return kExitOk;
}

}  // namespace skylight::cli
