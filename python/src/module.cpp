// The Python extension `skylight._skylight` (pybind11): a thin adapter over the library's
// operations. Parameter names, units, ranges and defaults come from the schemas
// (operations::models_json(), operations::sky_request); messages name parameters as Python spells
// them (`sun_zenith`, set_parameter_spelling). The pure-Python layer (python/skylight/) adds
// broadcasting, datetime handling and the docstrings generated from the same schemas.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/interleave.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/core/text.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/fit/network_training.h"
#include "skylight/fit/neural_training.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/sky_model.h"
#include "skylight/nn/glsl.h"
#include "skylight/nn/pietras.h"
#include "skylight/nn/sky_network.h"
#include "skylight/operations/operations.h"
#include "skylight/render/sky_render.h"
#include "skylight/report/report.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/irradiance.h"
#include "skylight/sh/polynomial.h"
#include "skylight/sh/projection.h"
#include "skylight/sh/rotation.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"
#include "skylight/version.h"

namespace py = pybind11;
namespace sl = skylight;

namespace {

std::string python_spelling(std::string_view name) {
  std::string s(name);
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

std::string schema_name(const std::string& python_name) {
  std::string s = python_name;
  for (char& c : s)
    if (c == '_') c = '-';
  return s;
}

double number_of(const sl::ParameterSpec& spec, py::handle v) {
  if (py::isinstance<py::bool_>(v) ||
      !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
        py::hasattr(v, "__float__")) ||
      py::isinstance<py::str>(v))
    throw sl::InvalidArgument(
        fmt::format("{} must be a number, got {}", sl::spelled(spec.name),
                    py::str(py::type::of(v).attr("__name__")).cast<std::string>()));
  return py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>();
}

// A Python value as the spec's kind (the schema then checks the range).
sl::ParameterValue to_value(const sl::ParameterSpec& spec, py::handle v) {
  switch (spec.kind) {
    case sl::ParameterKind::flag:
      if (!py::isinstance<py::bool_>(v))
        throw sl::InvalidArgument(fmt::format("{} must be True or False", sl::spelled(spec.name)));
      return v.cast<bool>();
    case sl::ParameterKind::text:
      if (!py::isinstance<py::str>(v))
        throw sl::InvalidArgument(fmt::format("{} must be a str", sl::spelled(spec.name)));
      return v.cast<std::string>();
    case sl::ParameterKind::numbers: {
      std::vector<double> out;
      for (py::handle item : py::iter(v)) out.push_back(number_of(spec, item));
      return out;
    }
    case sl::ParameterKind::integer: {
      const double d = number_of(spec, v);
      if (d != std::floor(d))
        throw sl::InvalidArgument(
            fmt::format("{} must be a whole number, got {}", sl::spelled(spec.name), d));
      return d;
    }
    case sl::ParameterKind::number:
      break;
  }
  return number_of(spec, v);
}

// Keyword arguments as named values of `specs` (an operation's schema); a name it does not
// declare is an error naming it and `what`.
sl::ParameterValues schema_values(const std::vector<sl::ParameterSpec>& specs,
                                  const py::dict& kwargs, const std::string& what) {
  sl::ParameterValues values;
  for (const auto& [key, value] : kwargs) {
    const std::string name = schema_name(key.cast<std::string>());
    const sl::ParameterSpec* spec = nullptr;
    for (const auto& s : specs)
      if (s.name == name) spec = &s;
    if (spec == nullptr) {
      std::vector<std::string> known;
      for (const auto& s : specs) known.push_back(python_spelling(s.name));
      throw sl::InvalidArgument(fmt::format("{} is not a parameter of {}{}",
                                            key.cast<std::string>(), what,
                                            sl::did_you_mean(key.cast<std::string>(), known)));
    }
    if (value.is_none()) continue;
    const sl::ParameterValue v = to_value(*spec, value);
    spec->check(v);
    values.set(name, v);
  }
  return values;
}

// The keyword arguments of a sky: the operation's sun and solar-disc specs and the model's own.
sl::ParameterValues sky_values(const sl::ModelInfo& info, const py::dict& kwargs) {
  std::vector<sl::ParameterSpec> specs;
  for (const auto& s : sl::operations::model_specs())
    if (s.name != "model") specs.push_back(s);
  for (const auto& p : info.parameters) specs.push_back(p);
  return schema_values(specs, kwargs, fmt::format("model '{}'", info.name));
}

sl::Quantity quantity_of(const std::string& q) {
  if (q == "rgb") return sl::Quantity::rgb;
  if (q == "xyz") return sl::Quantity::xyz;
  if (q == "luminance") return sl::Quantity::luminance;
  if (q == "spectral") return sl::Quantity::spectral;
  throw sl::InvalidArgument(
      fmt::format("quantity = '{}' is not one of rgb|xyz|luminance|spectral", q));
}

// Runs fn() with the GIL released and the library's batch helpers on `threads` threads (0: the
// library's count) for this call only.
template <class F>
void with_threads(int threads, F&& fn) {
  py::gil_scoped_release release;
  const sl::ScopedThreadCount count(threads);
  fn();
}

// Runs fn(begin, end) over [0, n) in chunks on `threads` threads, the GIL released.
template <class F>
void parallel_chunks(std::size_t n, int threads, F&& fn) {
  with_threads(threads, [&] {
    sl::parallel_for(n, sl::kBatchChunk, [&](std::size_t b, std::size_t e) { fn(b, e); });
  });
}

// The CPU time [s] fn() takes on the calling thread (one thread: the library's batch helpers
// set to one), the GIL released.
template <class F>
double thread_cpu_seconds(F&& fn) {
  double seconds = 0.0;
  with_threads(1, [&] {
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    fn();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    seconds = static_cast<double>(t1.tv_sec - t0.tv_sec) +
              1e-9 * static_cast<double>(t1.tv_nsec - t0.tv_nsec);
  });
  return seconds;
}

class Sky {
 public:
  Sky(const std::string& model, const py::dict& kwargs)
      : info_(&sl::require_model(model, "model")) {
    const sl::operations::SkyRequest r =
        sl::operations::sky_request(*info_, sky_values(*info_, kwargs));
    model_ = sl::make_sky_model(info_->name, r.parameters);
    mode_ = r.sun_mode;
    sl::check_sun_mode(*model_, mode_);
  }

  std::string name() const { return info_->name; }
  const sl::SkyModel& model() const { return *model_; }
  double sun_zenith_deg() const { return sl::rad_to_deg(model_->sun().zenith); }
  double sun_azimuth_deg() const { return sl::rad_to_deg(model_->sun().azimuth); }
  std::string sun_mode() const { return std::string(sl::to_string(mode_)); }

  py::dict parameters() const {
    py::dict d;
    const sl::ParameterValues values = model_->parameter_values();
    for (const auto& [name, v] : values.all()) {
      const std::string key = python_spelling(name);
      std::visit([&](const auto& x) { d[py::str(key)] = py::cast(x); }, v);
    }
    return d;
  }

  py::list domain() const {
    py::list out;
    for (const auto& issue : model_->domain().issues) {
      py::dict d;
      d["parameter"] = issue.parameter;
      d["validity"] = std::string(sl::to_string(issue.validity));
      d["message"] = issue.message;
      d["spectral_only"] = issue.spectral_only;
      out.append(d);
    }
    return out;
  }

  // The sky drawn into an image (render::render_sky, `skylight render`'s CPU path): (H, W, 3)
  // float32 of linear sRGB or XYZ, and the mask of pixels without a direction.
  std::pair<py::array_t<float>, py::array_t<bool>> render(const py::dict& image_kwargs,
                                                          const std::string& quantity,
                                                          int threads) const {
    if (quantity != "rgb" && quantity != "xyz")
      throw sl::InvalidArgument(fmt::format("quantity = '{}': an image is rgb or xyz", quantity));
    const sl::ImageSchemaOptions kind{};
    const auto schema = sl::image_schema(kind);
    sl::ImageOptions image = kind.defaults();
    schema.bind(schema_values(schema.specs(), image_kwargs, "render"), image, "render");
    sl::render::RenderSettings settings;
    static_cast<sl::Camera&>(settings) = image.camera();
    settings.sun = mode_;
    sl::render::SkyImage img;
    with_threads(threads, [&] { img = sl::render::render_sky(*model_, settings); });
    const sl::io::ImageF& src = quantity == "rgb" ? img.rgb : img.xyz;
    for (const float v : src.data)
      if (!std::isfinite(v))
        throw sl::InvalidArgument(fmt::format(
            "model '{}' gives non-finite pixels: its parameters overflow", info_->name));
    const auto h = static_cast<std::size_t>(src.height), w = static_cast<std::size_t>(src.width);
    py::array_t<float> out({h, w, std::size_t{3}});
    std::copy(src.data.begin(), src.data.end(), out.mutable_data());
    py::array_t<bool> mask({h, w});
    bool* m = mask.mutable_data();
    for (std::size_t i = 0; i < h * w; ++i) m[i] = img.mask[i] != 0;
    return {out, mask};
  }

  std::vector<std::string> columns(const std::string& quantity,
                                   const std::vector<double>& wavelengths) const {
    return sl::quantity_columns(options(quantity, wavelengths));
  }

  // (N, 3) unit-or-not direction vectors -> (N, C) values (sl::evaluate_rows).
  py::array_t<double> evaluate_directions(
      py::array_t<double, py::array::c_style | py::array::forcecast> v, const std::string& quantity,
      const std::vector<double>& wavelengths, bool exact, int threads, py::object out) const {
    if (v.ndim() != 2 || v.shape(1) != 3)
      throw sl::InvalidArgument("directions must have shape (..., 3)");
    const std::span<const double> rows(v.data(), static_cast<std::size_t>(v.size()));
    return evaluate(rows.size() / 3, quantity, wavelengths, threads, out,
                    [&](const sl::EvaluationOptions& o, std::span<double> dst) {
                      sl::evaluate_rows(*model_, rows, o, dst, exact);
                    });
  }

  // float32 x, y, z of shape (N,) -> (3, N) float32 X, Y, Z (sl::evaluate_soa): the batch path
  // on the caller's arrays, no conversion.
  py::array_t<float> evaluate_soa(const py::array& x, const py::array& y, const py::array& z,
                                  int threads, py::object out_arg) const {
    const auto flat = [](const py::array& a, const char* name) {
      if (!py::isinstance<py::array_t<float>>(a) || !(a.flags() & py::array::c_style) ||
          a.ndim() != 1)
        throw sl::InvalidArgument(fmt::format(
            "{} must be a 1-D C-contiguous float32 array (evaluate_directions takes others)",
            name));
      return std::span<const float>(static_cast<const float*>(a.data()),
                                    static_cast<std::size_t>(a.size()));
    };
    const std::span<const float> sx = flat(x, "x"), sy = flat(y, "y"), sz = flat(z, "z");
    const std::size_t n = sx.size();
    py::array_t<float> out;
    if (out_arg.is_none()) {
      out = py::array_t<float>({std::size_t{3}, n});
    } else {
      if (!py::isinstance<py::array_t<float>>(out_arg))
        throw sl::InvalidArgument("out must be a float32 numpy array");
      out = py::reinterpret_borrow<py::array_t<float>>(out_arg);
      if (!(out.flags() & py::array::c_style) || !out.writeable() || out.ndim() != 2 ||
          out.shape(0) != 3 || static_cast<std::size_t>(out.shape(1)) != n)
        throw sl::InvalidArgument(
            fmt::format("out must be a writable C-contiguous float32 array of shape (3, {})", n));
    }
    float* dst = out.mutable_data();
    with_threads(threads, [&] {
      sl::evaluate_soa(*model_, {sx, sy, sz}, {{dst, n}, {dst + n, n}, {dst + 2 * n, n}});
    });
    return out;
  }

  // Zenith and azimuth angles [deg] (flat arrays of one length) -> (N, C) values
  // (sl::evaluate_angles).
  py::array_t<double> evaluate_angles(
      py::array_t<double, py::array::c_style | py::array::forcecast> zenith_deg,
      py::array_t<double, py::array::c_style | py::array::forcecast> azimuth_deg,
      const std::string& quantity, const std::vector<double>& wavelengths, bool exact, int threads,
      py::object out) const {
    const std::span<const double> z(zenith_deg.data(), static_cast<std::size_t>(zenith_deg.size()));
    const std::span<const double> a(azimuth_deg.data(),
                                    static_cast<std::size_t>(azimuth_deg.size()));
    return evaluate(z.size(), quantity, wavelengths, threads, out,
                    [&](const sl::EvaluationOptions& o, std::span<double> dst) {
                      sl::evaluate_angles(*model_, z, a, o, dst, exact);
                    });
  }

  // The in-process baselines of python/tools/bench_overhead.py: the seconds of CPU time one
  // thread takes for the C++ batch path without the binding. batch_cpu_seconds: tristimulus_batch
  // over float directions already in structure-of-arrays form (x, y, z of shape (n,)) in
  // kBatchChunk chunks, or with `checked` sl::evaluate_soa (the same with its checks), into `out`
  // (3, n); rows_cpu_seconds: sl::evaluate_rows (xyz) over float64 rows (n, 3) into `out` (n, 3).
  // The caller's output arrays: the same memory as the Python call it is compared with.
  double batch_cpu_seconds(py::array_t<float, py::array::c_style> x,
                           py::array_t<float, py::array::c_style> y,
                           py::array_t<float, py::array::c_style> z,
                           py::array_t<float, py::array::c_style> out, bool checked) const {
    const auto n = static_cast<std::size_t>(x.size());
    if (static_cast<std::size_t>(out.size()) != 3 * n)
      throw sl::InvalidArgument("out must hold 3 x n values");
    const float *px = x.data(), *py_ = y.data(), *pz = z.data();
    float* X = out.mutable_data();
    float *Y = X + n, *Z = Y + n;
    if (checked)
      return thread_cpu_seconds([&] {
        sl::evaluate_soa(*model_, {{px, n}, {py_, n}, {pz, n}}, {{X, n}, {Y, n}, {Z, n}});
      });
    return thread_cpu_seconds([&] {
      for (std::size_t b = 0; b < n; b += sl::kBatchChunk) {
        const std::size_t m = std::min(sl::kBatchChunk, n - b);
        model_->tristimulus_batch({{px + b, m}, {py_ + b, m}, {pz + b, m}},
                                  {{X + b, m}, {Y + b, m}, {Z + b, m}});
      }
    });
  }

  double rows_cpu_seconds(py::array_t<double, py::array::c_style> v,
                          py::array_t<double, py::array::c_style> out) const {
    const std::span<const double> rows(v.data(), static_cast<std::size_t>(v.size()));
    const std::span<double> dst(out.mutable_data(), static_cast<std::size_t>(out.size()));
    sl::EvaluationOptions o;
    o.quantity = sl::Quantity::xyz;
    return thread_cpu_seconds([&] { sl::evaluate_rows(*model_, rows, o, dst); });
  }

 private:
  sl::EvaluationOptions options(const std::string& quantity,
                                const std::vector<double>& wavelengths) const {
    sl::EvaluationOptions o;
    o.quantity = quantity_of(quantity);
    o.wavelengths_nm = wavelengths;
    o.sun = mode_;
    sl::validate(o);
    sl::validate(o, *model_);
    return o;
  }

  // n directions evaluated by run(options, out) with the GIL released on `threads` threads.
  // `out`: None, or a C-contiguous float64 array of n * columns values to write into.
  template <class Run>
  py::array_t<double> evaluate(std::size_t n, const std::string& quantity,
                               const std::vector<double>& wavelengths, int threads,
                               py::object out_arg, Run run) const {
    const sl::EvaluationOptions o = options(quantity, wavelengths);
    const std::size_t cols = sl::quantity_columns(o).size();
    py::array_t<double> out;
    if (out_arg.is_none()) {
      out = py::array_t<double>({n, cols});
    } else {
      if (!py::isinstance<py::array_t<double>>(out_arg))
        throw sl::InvalidArgument("out must be a float64 numpy array");
      out = py::reinterpret_borrow<py::array_t<double>>(out_arg);
      if (!(out.flags() & py::array::c_style) || !out.writeable() ||
          static_cast<std::size_t>(out.size()) != n * cols)
        throw sl::InvalidArgument(fmt::format(
            "out must be a writable C-contiguous float64 array of {} x {} values", n, cols));
    }
    const std::span<double> dst(out.mutable_data(), n * cols);
    with_threads(threads, [&] { run(o, dst); });
    return out;
  }

  const sl::ModelInfo* info_;
  std::unique_ptr<sl::SkyModel> model_;
  sl::SunMode mode_ = sl::SunMode::sky;
};

// Civil date-time (UTC) of nanoseconds since 1970-01-01T00:00:00Z (H. Hinnant's days-to-civil).
sl::sun::DateTime civil_utc(std::int64_t ns) {
  constexpr std::int64_t kDay = 86'400'000'000'000;
  std::int64_t days = ns / kDay, rem = ns % kDay;
  if (rem < 0) {
    rem += kDay;
    --days;
  }
  const std::int64_t zd = days + 719468;
  const std::int64_t era = (zd >= 0 ? zd : zd - 146096) / 146097;
  const std::int64_t doe = zd - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  sl::sun::DateTime t;
  t.day = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  t.month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  t.year = static_cast<int>(yoe + era * 400 + (t.month <= 2 ? 1 : 0));
  const std::int64_t s = rem / 1'000'000'000;
  t.hour = static_cast<int>(s / 3600);
  t.minute = static_cast<int>((s / 60) % 60);
  t.second = static_cast<double>(s % 60) + static_cast<double>(rem % 1'000'000'000) * 1e-9;
  return t;
}

// The SPA's options (lat, lon, elevation, pressure, ...) as keyword arguments of `what`.
sl::sun::SpaInput spa_input_of(const py::dict& kwargs, const char* what) {
  sl::ParameterValues values;
  for (const auto& [key, value] : kwargs) {
    const std::string name = schema_name(key.cast<std::string>());
    const auto& specs = sl::sun::spa_parameter_specs();
    if (std::none_of(specs.begin(), specs.end(),
                     [&](const sl::ParameterSpec& s) { return s.name == name; }))
      throw sl::InvalidArgument(
          fmt::format("{} is not a parameter of {}", key.cast<std::string>(), what));
    const sl::ParameterSpec& spec = sl::sun::spa_parameter_spec(name);
    if (value.is_none()) continue;
    const sl::ParameterValue v = to_value(spec, value);
    spec.check(v);
    values.set(name, v);
  }
  sl::sun::SpaInput base;
  sl::sun::spa_input_schema().bind(values, base, what);
  return base;
}

// The SPA for each time (ns since the epoch, UTC): (N, 2) zenith and azimuth [deg].
py::array_t<double> sun_position(
    py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> ns,
    const py::dict& kwargs) {
  const sl::sun::SpaInput base = spa_input_of(kwargs, "sun_position");
  const auto n = static_cast<std::size_t>(ns.size());
  py::array_t<double> out({n, std::size_t{2}});
  double* dst = out.mutable_data();
  const std::int64_t* t = ns.data();
  std::vector<sl::sun::DateTime> times(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = civil_utc(t[i]);
    sl::sun::validate(times[i], fmt::format("times[{}]", i));
  }
  parallel_chunks(n, 0, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      sl::sun::SpaInput in = base;
      in.time = times[i];
      const sl::sun::SpaResult r = sl::sun::solar_position(in);
      dst[2 * i] = sl::rad_to_deg(r.zenith);
      dst[2 * i + 1] = sl::rad_to_deg(r.azimuth);
    }
  });
  return out;
}

// io: images as numpy arrays (io/image.h). Float formats as (H, W, C) float32, PNG as (H, W, 3)
// uint8; the metadata of an EXR as a dict.
py::tuple read_image(const std::string& path) {
  const auto format = sl::io::format_from_path(path);
  if (format == sl::io::ImageFormat::png) {
    sl::io::Image8 img;
    {
      py::gil_scoped_release release;
      img = sl::io::read_png(path);
    }
    py::array_t<std::uint8_t> out({static_cast<std::size_t>(img.height),
                                   static_cast<std::size_t>(img.width), std::size_t{3}});
    std::copy(img.data.begin(), img.data.end(), out.mutable_data());
    return py::make_tuple(out, py::dict());
  }
  sl::io::ImageF img;
  sl::io::Metadata meta;
  {
    py::gil_scoped_release release;
    img = sl::io::read_image(path);
    if (format == sl::io::ImageFormat::exr) meta = sl::io::read_exr_metadata(path);
  }
  py::array_t<float> out({static_cast<std::size_t>(img.height), static_cast<std::size_t>(img.width),
                          static_cast<std::size_t>(img.channels)});
  std::copy(img.data.begin(), img.data.end(), out.mutable_data());
  py::dict d;
  for (const auto& [k, v] : meta) d[py::str(k)] = v;
  return py::make_tuple(out, d);
}

void write_image(const std::string& path, py::array image, const py::dict& metadata) {
  sl::io::Metadata meta;
  for (const auto& [k, v] : metadata) meta.emplace_back(py::str(k), py::str(v));
  const auto format = sl::io::format_from_path(path);
  if (image.ndim() != 2 && image.ndim() != 3)
    throw sl::InvalidArgument(
        fmt::format("an image has shape (H, W) or (H, W, C), got {} axes", image.ndim()));
  const auto h = static_cast<int>(image.shape(0)), w = static_cast<int>(image.shape(1));
  const int c = image.ndim() == 3 ? static_cast<int>(image.shape(2)) : 1;
  if (format == sl::io::ImageFormat::png) {
    if (!py::isinstance<py::array_t<std::uint8_t>>(image) || c != 3)
      throw sl::InvalidArgument(fmt::format(
          "'{}': a PNG holds (H, W, 3) uint8 pixels (tone-map float images first)", path));
    const auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>(image);
    sl::io::Image8 img(w, h);
    std::copy(a.data(), a.data() + a.size(), img.data.begin());
    py::gil_scoped_release release;
    sl::io::write_png(path, img, meta);
    return;
  }
  if (c != 1 && c != 3)
    throw sl::InvalidArgument(fmt::format("an image has 1 or 3 channels, got {}", c));
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>(image);
  sl::io::ImageF img(w, h, c);
  std::copy(a.data(), a.data() + a.size(), img.data.begin());
  for (const float v : img.data)
    if (!std::isfinite(v))
      throw sl::InvalidArgument(fmt::format("'{}': the image holds NaN or Inf", path));
  py::gil_scoped_release release;
  sl::io::write_image(path, img, meta);
}

// sh: coefficients as (bands^2, 3) float64 arrays (sh/projection.h's order: index(l, m)).
sl::sh::Coefficients coefficients_of(
    py::array_t<double, py::array::c_style | py::array::forcecast> a) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw sl::InvalidArgument("SH coefficients must have shape (bands^2, 3)");
  const auto n = static_cast<int>(a.shape(0));
  const int bands = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
  if (bands * bands != n || bands < 1)
    throw sl::InvalidArgument(fmt::format("SH coefficients must have bands^2 rows, got {}", n));
  sl::sh::check_bands(bands);
  sl::sh::Coefficients c;
  c.bands = bands;
  c.c.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      c.c[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = a.at(i, k);
  return c;
}

py::array_t<double> array_of(const sl::sh::Coefficients& c) {
  py::array_t<double> out({c.c.size(), std::size_t{3}});
  double* d = out.mutable_data();
  for (std::size_t i = 0; i < c.c.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) d[3 * i + k] = c.c[i][k];
  return out;
}

sl::sh::Channels channels_of(const std::string& name) {
  if (name == "rgb") return sl::sh::Channels::linear_srgb;
  if (name == "xyz") return sl::sh::Channels::xyz;
  throw sl::InvalidArgument(fmt::format("channels = '{}' is not rgb or xyz", name));
}

py::tuple sh_project(const Sky& sky, int bands, const std::string& channels,
                     std::optional<double> ground_albedo, double tolerance) {
  sl::sh::check_bands(bands);
  sl::sh::ProjectionOptions o;
  o.ground_albedo = ground_albedo;
  o.tolerance = tolerance;
  if (ground_albedo && !(*ground_albedo >= 0.0 && *ground_albedo <= 1.0))
    throw sl::InvalidArgument(fmt::format("ground_albedo = {} is outside [0, 1]", *ground_albedo));
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw sl::InvalidArgument(fmt::format("tolerance = {} is outside (0, 1)", tolerance));
  sl::sh::Projection p;
  {
    py::gil_scoped_release release;
    p = sl::fit::project_model(sky.model(), channels_of(channels), bands, o);
  }
  return py::make_tuple(array_of(p.coefficients), p.converged, p.nodes);
}

// Sunrise, transit and sunset (SPA App. A.2, sun::sun_events) on the local calendar date of each
// time (ns since the epoch, UTC) at a UTC offset [min]: (N, 3) int64 ns since the epoch (UTC) of
// the events, INT64_MIN (numpy's NaT) where none occurs on that date, and (N,) day kinds
// (0 normal, 1 polar day, 2 polar night).
py::tuple sun_events(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> ns,
                     int utc_offset_minutes, const py::dict& kwargs) {
  if (utc_offset_minutes < -1080 || utc_offset_minutes > 1080)
    throw sl::InvalidArgument(
        fmt::format("utc_offset = {} min is outside [-18:00, +18:00]", utc_offset_minutes));
  const sl::sun::SpaInput base = spa_input_of(kwargs, "sun_events");
  const auto n = static_cast<std::size_t>(ns.size());
  py::array_t<std::int64_t> events({n, std::size_t{3}});
  py::array_t<std::int8_t> kinds(n);
  std::int64_t* ev = events.mutable_data();
  std::int8_t* kd = kinds.mutable_data();
  const std::int64_t* t = ns.data();
  std::vector<sl::sun::DateTime> times(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = civil_utc(t[i] + static_cast<std::int64_t>(utc_offset_minutes) * 60'000'000'000);
    times[i].utc_offset_minutes = utc_offset_minutes;
    sl::sun::validate(times[i], fmt::format("times[{}]", i));
  }
  constexpr double kUnixEpochJd = 2440587.5;
  constexpr double kNsPerDay = 86'400e9;
  parallel_chunks(n, 0, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      sl::sun::SpaInput in = base;
      in.time = times[i];
      const sl::sun::SunEvents se = sl::sun::sun_events(in);
      const std::optional<sl::sun::SunEvent>* each[3] = {&se.sunrise, &se.transit, &se.sunset};
      for (int k = 0; k < 3; ++k)
        ev[3 * i + k] = *each[k] ? static_cast<std::int64_t>(
                                       std::llround(((*each[k])->jd - kUnixEpochJd) * kNsPerDay))
                                 : std::numeric_limits<std::int64_t>::min();
      kd[i] = se.kind == sl::sun::DayKind::normal      ? 0
              : se.kind == sl::sun::DayKind::polar_day ? 1
                                                       : 2;
    }
  });
  return py::make_tuple(events, kinds);
}

// Per direction (N, 3) -> (N, 3): the reconstruction (sh::reconstruct) or the irradiance for a
// surface normal (sh::irradiance).
py::array_t<double> sh_per_direction(
    py::array_t<double, py::array::c_style | py::array::forcecast> coeffs,
    py::array_t<double, py::array::c_style | py::array::forcecast> v, bool irradiance) {
  const sl::sh::Coefficients c = coefficients_of(coeffs);
  if (v.ndim() != 2 || v.shape(1) != 3)
    throw sl::InvalidArgument("directions must have shape (..., 3)");
  const auto n = static_cast<std::size_t>(v.shape(0));
  const double* p = v.data();
  py::array_t<double> out({n, std::size_t{3}});
  double* d = out.mutable_data();
  const sl::sh::Coefficients e = irradiance ? sl::sh::irradiance_coefficients(c) : c;
  parallel_chunks(n, 0, [&](std::size_t b, std::size_t end) {
    for (std::size_t i = b; i < end; ++i) {
      const sl::sh::Triple t = sl::sh::reconstruct(e, sl::row_direction(p, i));
      for (std::size_t k = 0; k < 3; ++k) d[3 * i + k] = t[k];
    }
  });
  return out;
}

py::array_t<double> sh_rotate(py::array_t<double, py::array::c_style | py::array::forcecast> coeffs,
                              py::array_t<double, py::array::c_style | py::array::forcecast> r) {
  const sl::sh::Coefficients c = coefficients_of(coeffs);
  if (r.ndim() != 2 || r.shape(0) != 3 || r.shape(1) != 3)
    throw sl::InvalidArgument("a rotation is a 3 x 3 matrix");
  sl::sh::RotationMatrix m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = r.at(i, j);
  // Orthogonal with det +1, to 1e-9 (sh::rotate assumes it).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dot = 0.0;
      for (int k = 0; k < 3; ++k)
        dot += m[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)] *
               m[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-9)
        throw sl::InvalidArgument("the rotation matrix is not orthogonal (R^T R != I to 1e-9)");
    }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (!(det > 0.0)) throw sl::InvalidArgument("the rotation matrix has det -1 (a reflection)");
  return array_of(sl::sh::rotate(c, m));
}

py::array_t<double> sh_rotate_about_zenith(
    py::array_t<double, py::array::c_style | py::array::forcecast> coeffs, double degrees) {
  if (!std::isfinite(degrees)) throw sl::InvalidArgument("the angle must be finite");
  return array_of(sl::sh::rotate_about_zenith(coefficients_of(coeffs), sl::deg_to_rad(degrees)));
}

// The report (report/report.h) into `output_dir`, its options from the schema; the files written.
std::vector<std::string> write_report(const std::string& output_dir, const py::dict& kwargs) {
  const auto& schema = sl::report::ReportOptions::schema();
  sl::report::ReportOptions o;
  schema.bind(schema_values(schema.specs(), kwargs, "report"), o, "report");
  o.output_dir = output_dir;
  sl::report::ReportSummary summary;
  {
    py::gil_scoped_release release;
    summary = sl::report::write_report(o);  // its own transaction: all files or none
  }
  return summary.files;
}

// nn train of a sky network on a registered model (fit/neural_training.h), written to `output`
// (atomically); the request's options from the schema. Ctrl-C stops between iterations: the
// progress callback checks Python's signals with the GIL taken, and KeyboardInterrupt is raised
// (nothing written). Returns the summary as a dict.
// The callbacks of a training: Ctrl-C (checked under the GIL) stops it between iterations,
// `progress(iteration, mse)` (if given) is called after each.
struct TrainingProgress {
  const py::object* progress;
  bool interrupted = false;
  bool operator()(int iteration, double mse) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      return false;
    }
    if (!progress->is_none()) (*progress)(iteration, mse);
    return true;
  }
  // Between steps without a return value (reading images): Ctrl-C ends the work by exception.
  struct Stop {};
  void step() {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      throw Stop{};
    }
  }
  // Runs the training with the GIL released; KeyboardInterrupt when it was interrupted.
  template <class F>
  void run(F&& fn) {
    try {
      py::gil_scoped_release release;
      fn();
    } catch (const Stop&) {
    }
    if (interrupted) throw py::error_already_set();
  }
};

py::dict nn_train_sky(const std::string& output, const sl::fit::NetworkTrainingRequest& req,
                      TrainingProgress& tp) {
  sl::fit::NeuralTraining t = req.sky_training();
  t.options.progress = [&](const sl::nn::TrainLogEntry& e) { return tp(e.iteration, e.mse); };
  sl::fit::NeuralTrainingResult r;
  tp.run([&] { r = sl::fit::train_neural_sky(t); });
  r.network.provenance.software = fmt::format("skylight {} (Python)", sl::kVersion);
  sl::io::write_text_file(output, sl::nn::to_json(r.network));
  py::dict d;
  const auto& pv = r.network.provenance;
  d["layout"] = r.network.net.layout().describe();
  d["source"] = pv.source;
  d["trainer"] = pv.trainer;
  d["seed"] = pv.seed;
  d["iterations"] = pv.iterations;
  d["stop"] = pv.stop;
  d["training_rmse"] = std::sqrt(pv.training_mse);
  if (r.validation) {
    d["validation_rmse"] = r.validation->errors.rmse;
    d["validation_relative_median"] = r.validation->errors.relative_median;
    d["validation_relative_p95"] = r.validation->errors.relative_p95;
  }
  if (r.check) d["check"] = r.check->summary();
  return d;
}

// `nn train --images LIST`: a sky network on a sequence of HDR sky images.
py::dict nn_train_images(const std::string& output, const sl::fit::NetworkTrainingRequest& req,
                         const sl::ParameterValues& values, TrainingProgress& tp) {
  sl::fit::ImageTrainingOptions options;
  sl::fit::ImageTrainingOptions::schema().bind(
      values.only(sl::fit::ImageTrainingOptions::schema().specs()), options, "nn.train");
  sl::fit::NeuralTraining t = req.sky_training();
  t.options.progress = [&](const sl::nn::TrainLogEntry& e) { return tp(e.iteration, e.mse); };
  sl::fit::ImageTrainingResult r;
  tp.run([&] {
    r = sl::fit::train_on_images(options, t, req.samples.value_or(sl::fit::kImageSamples),
                                 [&](int, int, const std::string&) { tp.step(); });
  });
  sl::nn::SkyNetwork network = r.trained.network;
  network.provenance.software = fmt::format("skylight {} (Python)", sl::kVersion);
  sl::io::write_text_file(output, sl::nn::to_json(network));
  py::dict d;
  py::list images;
  for (const sl::fit::LoadedImage& li : r.images) {
    py::dict i;
    i["line"] = li.entry.line;
    i["file"] = li.entry.file.string();
    i["sun_zenith_deg"] = sl::rad_to_deg(li.sampled.samples.state.sun_zenith);
    i["sun_azimuth_deg"] = sl::rad_to_deg(li.sampled.samples.state.sun_azimuth);
    i["sun_from"] = li.sun_source;
    i["sky_pixels"] = li.sampled.sky_pixels;
    i["samples"] = li.sampled.samples.views.size();
    images.append(i);
  }
  d["images"] = images;
  d["examples"] = r.examples;
  d["target_scale"] = r.target_scale;
  if (r.cross_validation) {
    py::list folds;
    for (const sl::nn::FoldResult& f : r.cross_validation->folds) {
      py::dict fd;
      py::list lines;
      for (int k : f.held_out) lines.append(r.images[static_cast<std::size_t>(k)].entry.line);
      fd["held_out_lines"] = lines;
      fd["test_examples"] = f.test_examples;
      fd["training_rmse"] = f.training_rmse;
      fd["rmse"] = f.errors.rmse;
      fd["relative_median"] = f.errors.relative_median;
      fd["relative_p95"] = f.errors.relative_p95;
      folds.append(fd);
    }
    d["cross_validation"] = folds;
    d["cross_validation_mean_rmse"] = r.cross_validation->mean_rmse;
  }
  d["check"] = r.check ? py::cast(r.check->summary(r.images)) : py::object(py::none());
  const auto& pv = network.provenance;
  d["layout"] = network.net.layout().describe();
  d["trainer"] = pv.trainer;
  d["seed"] = pv.seed;
  d["iterations"] = pv.iterations;
  d["stop"] = pv.stop;
  d["rmse"] = r.errors.rmse;
  d["relative_median"] = r.errors.relative_median;
  d["relative_p95"] = r.errors.relative_p95;
  return d;
}

// `nn train --network pietras|log3`: a Pietras network on nishita.
py::dict nn_train_pietras(const std::string& output, const sl::fit::NetworkTrainingRequest& req,
                          TrainingProgress& tp) {
  std::optional<sl::nn::PietrasNetwork> initial;
  sl::fit::PietrasTraining t = req.pietras_training(initial, output);
  const int iterations = t.options.max_iterations;
  t.progress = [&](int k, const sl::nn::TrainLogEntry& e) {
    return tp(k * iterations + e.iteration, e.mse);
  };
  sl::fit::PietrasTrainingResult result;
  tp.run([&] { result = sl::fit::train_pietras(t); });
  sl::nn::PietrasNetwork& net = result.network;
  net.provenance.software = fmt::format("skylight {} (Python)", sl::kVersion);
  sl::io::write_text_file(output, sl::nn::to_json(net));
  py::dict d;
  d["network"] = std::string(sl::nn::to_string(t.kind));
  d["weights"] = net.parameter_count();
  d["samples"] = net.provenance.samples;
  d["iterations"] = net.provenance.iterations;
  d["region"] = net.provenance.region;
  d["trainer"] = std::string(sl::nn::to_string(t.options.trainer));
  d["seed"] = req.seed;
  if (result.check) d["check"] = result.check->summary();
  return d;
}

// `skylight nn train`: a sky network on a model (source=), on HDR sky images (images=, a list
// file) or a Pietras network on nishita (network=); the weights file written atomically, nothing
// when the training fails its held-out check or is interrupted.
py::dict nn_train(const std::string& output, const py::dict& kwargs, py::object progress) {
  using Kind = sl::fit::NetworkTrainingRequest::Kind;
  const auto& schema = sl::fit::NetworkTrainingRequest::schema();
  std::vector<sl::ParameterSpec> specs = schema.specs();
  for (const auto& s : sl::fit::ImageTrainingOptions::schema().specs()) specs.push_back(s);
  const sl::ParameterValues values = schema_values(specs, kwargs, "nn.train");
  sl::fit::NetworkTrainingRequest req;
  schema.bind(values.only(schema.specs()), req, "nn.train");
  const Kind kind = req.network ? Kind::pietras : values.has("images") ? Kind::images : Kind::sky;
  if (kind == Kind::images)
    for (const char* name : {"source", "suns", "view-zeniths", "view-azimuths", "network"})
      if (values.has(name))
        throw sl::InvalidArgument(
            fmt::format("{} is not an option of training on images", python_spelling(name)));
  for (const std::string& name : sl::fit::NetworkTrainingRequest::unread(values, kind))
    PyErr_WarnEx(PyExc_UserWarning,
                 fmt::format("{} is not read by this training ({}); ignored", python_spelling(name),
                             kind == Kind::sky      ? "a sky network on a model"
                             : kind == Kind::images ? "images"
                                                    : "network")
                     .c_str(),
                 1);
  TrainingProgress tp{&progress};
  py::dict d = kind == Kind::pietras  ? nn_train_pietras(output, req, tp)
               : kind == Kind::images ? nn_train_images(output, req, values, tp)
                                      : nn_train_sky(output, req, tp);
  d["output"] = output;
  return d;
}

// `skylight nn export --glsl`: the GLSL compilation unit of a weights file (a sky network or a
// Pietras network), or of the embedded network when `path` is empty.
std::string nn_glsl(const std::string& path) {
  if (path.empty()) return sl::nn::glsl_sky_network_file(sl::embedded_sky_network());
  const std::string text = sl::io::read_text_file(path);
  return sl::nn::is_pietras_json(text)
             ? sl::nn::glsl_pietras_network_file(sl::nn::pietras_from_json(text, path))
             : sl::nn::glsl_sky_network_file(sl::nn::sky_network_from_json(text, path));
}

// A float (H, W, C) array as an image (C = 1 or 3).
sl::io::ImageF image_of(py::array_t<float, py::array::c_style | py::array::forcecast> a,
                        const char* what) {
  if (a.ndim() != 3 || (a.shape(2) != 1 && a.shape(2) != 3))
    throw sl::InvalidArgument(fmt::format("{} must have shape (H, W, 3) or (H, W, 1)", what));
  sl::io::ImageF img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)),
                     static_cast<int>(a.shape(2)));
  std::copy(a.data(), a.data() + a.size(), img.data.begin());
  for (const float v : img.data)
    if (!std::isfinite(v)) throw sl::InvalidArgument(fmt::format("{} holds NaN or Inf", what));
  return img;
}

// `skylight estimate` on an image array (the photo's layout, the sun given, from a time or found,
// the mask and fit settings from the estimate operation's schema): the fit as a dict.
py::dict estimate_fit(py::array_t<float, py::array::c_style | py::array::forcecast> photo,
                      py::object mask, const py::dict& kwargs) {
  const sl::OperationInfo& op = sl::operations::find("estimate");
  // Every option of the operation, the capture's EXIF file (exif, utc_offset) included; the
  // photo and the mask are the arrays.
  const sl::ParameterValues given = schema_values(op.parameters, kwargs, "estimate");
  const sl::io::ImageF image = image_of(photo, "the photo");
  std::optional<sl::io::ImageF> user_mask;
  if (!mask.is_none())
    user_mask = image_of(mask.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(),
                         "the mask");
  sl::estimate::CaptureOptions co;
  sl::estimate::CaptureOptions::schema().bind(
      given.only(sl::estimate::CaptureOptions::schema().specs()), co, "estimate");
  if (co.exif.empty() && !co.utc_offset.empty())
    throw sl::InvalidArgument("utc_offset is read only with exif (the capture's EXIF file)");
  std::optional<sl::estimate::Capture> capture;
  sl::operations::PhotoEstimate pe;
  {
    py::gil_scoped_release release;
    if (!co.exif.empty()) capture = sl::estimate::read_capture(co, image.width);
    pe = sl::operations::estimate_photo(image, given, user_mask ? &*user_mask : nullptr, capture);
  }
  const std::string& model = pe.model;
  const sl::fit::LuminanceFit& fit = pe.fit;
  const sl::estimate::PhotoSamples& ps = pe.samples;
  py::dict d;
  d["model"] = model;
  for (const auto& p : fit.parameters) {
    d[py::str(python_spelling(p.name))] = p.value;
    d[py::str(python_spelling(p.name) + "_sigma")] = p.sigma;
  }
  d["inlier_fraction"] = fit.inlier_fraction;
  d["residual"] = fit.residual;
  d["inliers"] = fit.inliers;
  d["method"] = fit.method;
  d["luminance_scale"] = std::exp(fit.log_scale);
  d["sun_zenith_deg"] = sl::rad_to_deg(ps.sun.zenith);
  d["sun_azimuth_deg"] = sl::rad_to_deg(ps.sun.azimuth);
  d["sun_source"] = pe.sun_source;
  d["samples"] = ps.samples.size();
  d["sky_pixels"] = ps.sky_pixels;
  if (capture) {
    // As `skylight estimate --json` reports it.
    const sl::io::ExifInfo& e = capture->exif;
    const auto or_none = [](const auto& v) -> py::object {
      return v ? py::cast(*v) : py::object(py::none());
    };
    py::dict x;
    x["file"] = co.exif;
    x["camera"] = fmt::format("{}{}{}", e.make, e.make.empty() ? "" : " ", e.model);
    x["date_time"] = or_none(e.date_time);
    x["utc_offset"] = or_none(e.utc_offset);
    x["focal_length_mm"] = or_none(e.focal_length_mm);
    x["focal_length_px"] = or_none(capture->focal_length_px);
    x["latitude_deg"] = or_none(e.latitude_deg);
    x["longitude_deg"] = or_none(e.longitude_deg);
    d["exif"] = x;
  }
  return d;
}

// A haze operation's options (its schema without the GL switch) as named values.
sl::ParameterValues haze_values(const std::string& operation, const py::dict& kwargs) {
  std::vector<sl::ParameterSpec> specs;
  for (const auto& s : sl::operations::find("haze " + operation).parameters)
    if (s.name != "gpu") specs.push_back(s);
  return schema_values(specs, kwargs, "haze." + operation);
}

// A one-channel (H, W[, 1]) array as an image.
sl::io::ImageF scalar_image_of(py::array_t<float, py::array::c_style | py::array::forcecast> a,
                               const char* what) {
  if (a.ndim() == 2) a = a.reshape({a.shape(0), a.shape(1), py::ssize_t{1}});
  sl::io::ImageF img = image_of(a, what);
  if (img.channels != 1) throw sl::InvalidArgument(fmt::format("{} must have one channel", what));
  return img;
}

py::array_t<float> rgb_array_of(const sl::io::ImageF& out) {
  for (const float v : out.data)
    if (!std::isfinite(v))
      throw sl::InvalidArgument("the result holds NaN or Inf (raise min_transmission)");
  py::array_t<float> result(
      {static_cast<std::size_t>(out.height), static_cast<std::size_t>(out.width), std::size_t{3}});
  std::copy(out.data.begin(), out.data.end(), result.mutable_data());
  return result;
}

// `skylight haze add|retarget|remove` on arrays (Morales et al. 2017; haze/request.h): the image
// (H, W, 3), its depth (H, W[, 1]; metres, or normalised with near/far), the operation's options
// from its schema. The result (H, W, 3) float32.
py::array_t<float> haze_apply(const std::string& name,
                              py::array_t<float, py::array::c_style | py::array::forcecast> image,
                              py::array_t<float, py::array::c_style | py::array::forcecast> depth,
                              const py::dict& kwargs) {
  sl::haze::HazeOperation op{};
  if (name == "add")
    op = sl::haze::HazeOperation::add;
  else if (name == "retarget")
    op = sl::haze::HazeOperation::retarget;
  else if (name == "remove")
    op = sl::haze::HazeOperation::remove;
  else
    throw sl::InvalidArgument(fmt::format("no haze operation '{}'", name));
  const sl::ParameterValues given = haze_values(name, kwargs);
  const sl::io::ImageF img = image_of(image, "the image");
  if (img.channels != 3) throw sl::InvalidArgument("the image must have R, G, B");
  const sl::io::ImageF d = scalar_image_of(depth, "the depth");
  const sl::haze::ImageHazeRequest r =
      sl::haze::image_haze_request(op, given, img.width, img.height);
  const sl::io::ImageF depth_m = sl::haze::depth_in_metres(d, {r.options.near_m, r.options.far_m},
                                                           img.width, img.height, "the depth");
  sl::io::ImageF out;
  {
    py::gil_scoped_release release;
    out = sl::haze::apply_haze(img, depth_m, r.camera, r.settings, nullptr);
  }
  return rgb_array_of(out);
}

// `skylight haze composite` on arrays: the background photo (H, W, 3) already showing the haze of
// T, the object (H, W, 3), its depth (H, W[, 1]) and coverage alpha (H, W[, 1]) in [0, 1] (None:
// 1 where the depth is > 0).
py::array_t<float> haze_composite(
    py::array_t<float, py::array::c_style | py::array::forcecast> background,
    py::array_t<float, py::array::c_style | py::array::forcecast> object,
    py::array_t<float, py::array::c_style | py::array::forcecast> depth, py::object alpha,
    const py::dict& kwargs) {
  const sl::ParameterValues given = haze_values("composite", kwargs);
  const sl::io::ImageF bg = image_of(background, "the background");
  const sl::io::ImageF obj = image_of(object, "the object");
  const sl::io::ImageF d = scalar_image_of(depth, "the object's depth");
  const sl::haze::ImageHazeRequest r =
      sl::haze::image_haze_request(sl::haze::HazeOperation::add, given, bg.width, bg.height);
  const sl::io::ImageF depth_m = sl::haze::depth_in_metres(
      d, {r.options.near_m, r.options.far_m}, obj.width, obj.height, "the object's depth");
  const sl::io::ImageF a =
      alpha.is_none()
          ? sl::haze::coverage_from_depth(depth_m)
          : scalar_image_of(
                alpha.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(),
                "the alpha");
  sl::io::ImageF out;
  {
    py::gil_scoped_release release;
    out = sl::haze::composite(bg, obj, a, depth_m, r.camera, r.settings);
  }
  return rgb_array_of(out);
}

// An SH polynomial table (Habel et al. 2008 eq. 1; docs/SH.md): fitted (`skylight sh fit`) or
// read from its JSON file, evaluated, written, exported and checked (`sh error`).
class ShTable {
 public:
  explicit ShTable(sl::sh::PolynomialTable t) : table_(std::move(t)) {}

  // `skylight sh fit`: the operation's options; progress(done, total) after each projection;
  // Ctrl-C stops between projections (KeyboardInterrupt).
  static ShTable fit(const py::dict& kwargs, py::object progress) {
    const auto& schema = sl::fit::ShFitRequest::schema();
    sl::fit::ShFitRequest req;
    schema.bind(schema_values(schema.specs(), kwargs, "sh.fit"), req, "sh.fit");
    sl::fit::ShFitSettings s = sl::fit::sh_fit_settings(req);
    s.polynomial.progress = interruptible(progress);
    sl::sh::PolynomialTable t;
    run_interruptible([&] { t = sl::fit::fit_sh_table(s); });
    return ShTable(std::move(t));
  }

  static ShTable load(const std::string& path) {
    return ShTable(sl::sh::table_from_json(sl::io::read_text_file(path), path));
  }

  // The coefficients (bands^2, 3) at the sun's zenith and azimuth [deg] and tau (None: the
  // middle of the table's range, as the `sh` model takes it), with or without the ringing filter.
  py::array_t<double> coefficients(double sun_zenith_deg, std::optional<double> tau,
                                   double sun_azimuth_deg, int bands, bool ringing_filter) const {
    const double t = tau.value_or(0.5 * (table_.tau_min + table_.tau_max));
    if (bands <= 0 || bands > table_.bands)
      throw sl::InvalidArgument(
          fmt::format("bands = {} is outside [1, {}] (the table's)", bands, table_.bands));
    return array_of(sl::sh::evaluate_table(table_, sl::deg_to_rad(sun_zenith_deg), t,
                                           sl::deg_to_rad(sun_azimuth_deg), bands, ringing_filter));
  }

  void save(const std::string& path) const {
    sl::io::write_text_file(path, sl::sh::table_to_json(table_));
  }
  std::string c_header(const std::string& name, bool monomial) const {
    return sl::sh::table_to_c_header(table_, name, monomial);
  }

  // `skylight sh error --json`'s rows.
  py::list error(const py::dict& kwargs, py::object progress) const {
    const auto& schema = sl::fit::ShErrorOptions::schema();
    sl::fit::ShErrorOptions o;
    schema.bind(schema_values(schema.specs(), kwargs, "sh.Table.error"), o, "sh.Table.error");
    sl::fit::ShTableError e;
    const auto report = interruptible(progress);
    run_interruptible([&] { e = sl::fit::table_error(table_, o, report); });
    const char* names = table_.channels == sl::sh::Channels::xyz ? "XYZ" : "rgb";
    py::list rows;
    for (const sl::fit::ShErrorRow& r : e.rows) {
      py::dict d;
      d["bands"] = r.bands;
      d["channel"] = std::string(1, names[r.channel]);
      d["e_mean_worst_percent"] = 100 * r.e_mean_worst;
      d["e_mean_median_percent"] = 100 * r.e_mean_median;
      d["e_max_worst_percent"] = 100 * r.e_max_worst;
      d["e_max_median_percent"] = 100 * r.e_max_median;
      d["worst_sun_zenith_deg"] = sl::rad_to_deg(r.worst_theta);
      d["worst_tau"] = r.worst_tau;
      rows.append(d);
    }
    return rows;
  }

  py::dict describe() const {
    py::dict d;
    d["model"] = table_.model;
    d["parameter"] = table_.parameter.empty() ? py::object(py::none()) : py::cast(table_.parameter);
    d["channels"] = table_.channels == sl::sh::Channels::xyz ? "xyz" : "linear-srgb";
    d["bands"] = table_.bands;
    d["degrees"] = py::make_tuple(table_.degree_theta, table_.degree_tau);
    d["sun_zenith_range_deg"] =
        py::make_tuple(sl::rad_to_deg(table_.theta_min), sl::rad_to_deg(table_.theta_max));
    d["tau_range"] = py::make_tuple(table_.tau_min, table_.tau_max);
    d["theta_axis"] = table_.theta_axis == sl::sh::ThetaAxis::theta ? "theta" : "elevation-cbrt";
    d["tau_pieces"] = table_.tau_pieces;
    d["ground_albedo"] =
        table_.ground_albedo ? py::cast(*table_.ground_albedo) : py::object(py::none());
    d["coefficient_count"] = table_.coefficients.size();
    return d;
  }

 private:
  // A progress callback that calls `progress(done, total)` (if given) under the GIL and stops the
  // work on Ctrl-C (the work is then rethrown as KeyboardInterrupt by run_interruptible).
  struct Interrupted {};
  // `progress` outlives the work; the callback holds its address only, so that copies of the
  // callback made without the GIL touch no reference count.
  static std::function<void(int, int)> interruptible(const py::object& progress) {
    const py::object* p = &progress;
    return [p](int done, int total) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
      if (!p->is_none()) (*p)(done, total);
    };
  }
  template <class F>
  static void run_interruptible(F&& fn) {
    try {
      py::gil_scoped_release release;
      fn();
    } catch (const Interrupted&) {
      throw py::error_already_set();
    }
  }

  sl::sh::PolynomialTable table_;
};

}  // namespace

PYBIND11_MODULE(_skylight, m) {
  m.doc() = "skylight: daylight sky models (the C++ library's Python binding)";
  sl::set_parameter_spelling(+[](std::string_view name) { return python_spelling(name); });
  static py::exception<sl::InvalidArgument> invalid(m, "InvalidArgument", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sl::InvalidArgument& e) {
      invalid(e.what());
    } catch (const sl::IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  m.attr("__version__") = sl::kVersion;
  m.def("models_json", &sl::operations::models_json);
  m.def("operations_json", &sl::operations::operations_json);
  m.def("sun_position", &sun_position, py::arg("ns"), py::arg("kwargs"));
  m.def("read_image", &read_image, py::arg("path"));
  m.def("sh_project", &sh_project);
  m.def("write_report", &write_report);
  m.def("nn_train", &nn_train);
  m.def("nn_glsl", &nn_glsl);
  m.def("estimate_fit", &estimate_fit);
  m.def("haze_apply", &haze_apply);
  m.def("sun_events", &sun_events);
  m.def("haze_composite", &haze_composite);
  m.def("sh_per_direction", &sh_per_direction);
  m.def("sh_rotate", &sh_rotate);
  m.def("sh_rotate_about_zenith", &sh_rotate_about_zenith);
  m.def("sh_ringing_filter", [](py::array_t<double, py::array::c_style | py::array::forcecast> c) {
    return array_of(sl::sh::ringing_filter(coefficients_of(c)));
  });
  m.def("write_image", &write_image, py::arg("path"), py::arg("image"), py::arg("metadata"));
  py::class_<ShTable>(m, "_ShTable")
      .def_static("fit", &ShTable::fit)
      .def_static("load", &ShTable::load)
      .def("coefficients", &ShTable::coefficients)
      .def("save", &ShTable::save)
      .def("c_header", &ShTable::c_header)
      .def("error", &ShTable::error)
      .def("describe", &ShTable::describe);
  py::class_<Sky>(m, "_Sky")
      .def(py::init<const std::string&, const py::dict&>(), py::arg("model"), py::arg("kwargs"))
      .def_property_readonly("name", &Sky::name)
      .def_property_readonly("sun_zenith", &Sky::sun_zenith_deg)
      .def_property_readonly("sun_azimuth", &Sky::sun_azimuth_deg)
      .def_property_readonly("sun_mode", &Sky::sun_mode)
      .def("parameters", &Sky::parameters)
      .def("domain", &Sky::domain)
      .def("columns", &Sky::columns)
      .def("evaluate_directions", &Sky::evaluate_directions)
      .def("evaluate_angles", &Sky::evaluate_angles)
      .def("evaluate_soa", &Sky::evaluate_soa)
      .def("render", &Sky::render)
      .def("batch_cpu_seconds", &Sky::batch_cpu_seconds)
      .def("rows_cpu_seconds", &Sky::rows_cpu_seconds);
}
