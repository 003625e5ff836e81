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

#include "../../src/cli/gpu_backend.h"
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
#include "skylight/io/kider.h"
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
      if (py::isinstance<py::str>(v) || !py::isinstance<py::iterable>(v))
        throw sl::InvalidArgument(
            fmt::format("{} must be a sequence of numbers, got {}", sl::spelled(spec.name),
                        py::str(py::type::of(v).attr("__name__")).cast<std::string>()));
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

// ---- operations ---------------------------------------------------------------------------------
// Every operation of the library (operations/operation.h), generically: keyword arguments bound
// by the operation's specs (the chosen model's for render and eval), arrays for its image inputs
// and texts for its text inputs in memory, warnings as Python warnings when they arise, progress
// and Ctrl-C between steps, the record as JSON text (the Python layer loads it) and the outputs
// not given a path kept in memory. The same prepare() and execute() as the command line: the same
// verdicts and messages.

// Stops an operation between steps on Ctrl-C (rethrown as KeyboardInterrupt).
struct Interrupted {};

// A Python value as the spec's kind (the schema then checks the range); a path-like's path.
sl::ParameterValue python_value(const sl::ParameterSpec& spec, py::handle v) {
  if (spec.kind == sl::ParameterKind::text && py::hasattr(v, "__fspath__"))
    return py::module_::import("os").attr("fspath")(v).cast<std::string>();
  return to_value(spec, v);
}

// The keyword arguments as named values of `op` (a name no parameter has: an empty text, which
// prepare() refuses naming the nearest parameter).
sl::ParameterValues operation_values(const sl::operations::OperationInfo& op,
                                     const py::dict& kwargs) {
  std::string model;
  if (kwargs.contains("model") && py::isinstance<py::str>(kwargs["model"]))
    model = kwargs["model"].cast<std::string>();
  sl::ParameterValues values;
  for (const auto& [key, value] : kwargs) {
    const std::string name = schema_name(key.cast<std::string>());
    if (value.is_none()) continue;
    const sl::ParameterSpec* spec = sl::operations::parameter_spec(op, model, name);
    values.set(name, spec ? python_value(*spec, value) : sl::ParameterValue(std::string()));
  }
  return values;
}

// Python's warnings.warn(message, SkylightWarning) under the GIL; a filter that turns it into an
// error stops the operation.
PyObject* g_warning_category = nullptr;  // SkylightWarning, made at import

void warn_in_python(const std::string& message) {
  py::gil_scoped_acquire gil;
  if (PyErr_WarnEx(g_warning_category, message.c_str(), 2) != 0) throw py::error_already_set();
}

sl::operations::Frontend python_frontend(const py::dict& inputs, const py::object* progress) {
  sl::operations::Frontend fe;
  fe.warn = warn_in_python;
  fe.keep_outputs = true;
  fe.interrupted = [] {
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;
  };
  fe.progress = [progress](int done, int total, std::string_view step) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
    if (!progress->is_none()) (*progress)(done, total, std::string(step));
  };
  for (const auto& [key, value] : inputs) {
    const std::string name = schema_name(key.cast<std::string>());
    if (py::isinstance<py::str>(value))
      fe.texts[name] = value.cast<std::string>();
    else
      fe.images[name] =
          image_of(value.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(),
                   fmt::format("{}", key.cast<std::string>()).c_str());
  }
  return fe;
}

py::object text_object(const std::string& text) {
  // UTF-8 text as str; other bytes (a .npy matrix) as bytes.
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), nullptr);
  if (s) return py::reinterpret_steal<py::object>(s);
  PyErr_Clear();
  return py::bytes(text);
}

py::array_t<float> image_array(const sl::io::ImageF& img) {
  py::array_t<float> out({static_cast<std::size_t>(img.height), static_cast<std::size_t>(img.width),
                          static_cast<std::size_t>(img.channels)});
  std::copy(img.data.begin(), img.data.end(), out.mutable_data());
  return out;
}

class Sky {
 public:
  // Prepared as render and eval prepare their sky (operations::sky_declaration): the same
  // checks, warnings and messages.
  Sky(const std::string& model, const py::dict& kwargs)
      : info_(&sl::require_model(model, "model")) {
    const sl::operations::OperationInfo& op = sl::operations::sky_declaration();
    py::dict all(kwargs);
    all["model"] = model;
    sl::operations::Frontend fe;
    fe.warn = warn_in_python;
    const sl::operations::Request request =
        sl::operations::prepare(op, operation_values(op, all), std::move(fe));
    model_ = sl::operations::make_sky(request);
    mode_ = request.bind(sl::SolarDisc::schema()).mode;
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

// (record JSON, {output: array or text}) of the operation `name`.
// The captures of Kider et al. 2014 under `path` (None: the shipped subset), io::read_kider: one
// dict per capture, its samples as arrays in index order.
py::list read_kider(const std::optional<std::string>& path) {
  const std::vector<sl::io::KiderCapture> captures =
      path ? sl::io::read_kider(*path) : sl::io::shipped_kider_subset();
  py::list out;
  for (const sl::io::KiderCapture& c : captures) {
    const std::size_t n = c.samples.size(), w = c.wavelengths_nm.size();
    py::array_t<int> index(static_cast<py::ssize_t>(n));
    py::array_t<double> zenith(static_cast<py::ssize_t>(n)), azimuth(static_cast<py::ssize_t>(n)),
        luminance(static_cast<py::ssize_t>(n));
    py::array_t<bool> replaced(static_cast<py::ssize_t>(n));
    py::array_t<double> radiance({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(w)});
    for (std::size_t i = 0; i < n; ++i) {
      const sl::io::KiderSample& s = c.samples[i];
      index.mutable_at(i) = s.index;
      zenith.mutable_at(i) = sl::rad_to_deg(s.zenith);
      azimuth.mutable_at(i) = sl::rad_to_deg(s.azimuth);
      luminance.mutable_at(i) = s.luminance;
      replaced.mutable_at(i) = s.replaced;
      for (std::size_t k = 0; k < w; ++k) radiance.mutable_at(i, k) = s.radiance[k];
    }
    std::vector<double> ghi;
    py::list times;
    for (const auto& r : c.pyranometer) {
      ghi.push_back(r.global_horizontal_w_m2);
      times.append(r.time);
    }
    py::dict d;
    d["name"] = c.name;
    d["local_time"] = c.local_time;
    d["wavelengths_nm"] = py::array_t<double>(static_cast<py::ssize_t>(w), c.wavelengths_nm.data());
    d["index"] = index;
    d["zenith_deg"] = zenith;
    d["azimuth_deg"] = azimuth;
    d["luminance"] = luminance;
    d["radiance"] = radiance;
    d["replaced"] = replaced;
    d["pyranometer_w_m2"] = py::array_t<double>(static_cast<py::ssize_t>(ghi.size()), ghi.data());
    d["pyranometer_time"] = times;
    const auto g = c.global_horizontal_w_m2();
    d["global_horizontal_w_m2"] = g ? py::object(py::float_(*g)) : py::object(py::none());
    out.append(d);
  }
  return out;
}

py::tuple run_operation(const std::string& name, const py::dict& kwargs, const py::dict& inputs,
                        py::object progress) {
  const sl::operations::OperationInfo& op = sl::operations::require_operation(name);
  sl::operations::Frontend fe = python_frontend(inputs, &progress);
  sl::operations::Result result;
  try {
    const sl::operations::Request request =
        sl::operations::prepare(op, operation_values(op, kwargs), std::move(fe));
    py::gil_scoped_release release;
    result = sl::operations::execute(request);
    // `view --serve`: the server until Ctrl-C (Frontend::interrupted, python_frontend).
    if (result.then) result.then();
  } catch (const Interrupted&) {
    throw py::error_already_set();
  }
  if (PyErr_Occurred()) throw py::error_already_set();
  py::dict outputs;
  for (const auto& [key, img] : result.images)
    outputs[py::str(python_spelling(key))] = image_array(img);
  for (const auto& [key, text] : result.texts)
    outputs[py::str(python_spelling(key))] = text_object(text);
  if (result.wrote_standard_output) outputs["output"] = text_object(result.standard_output);
  return py::make_tuple(
      result.record.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace),
      outputs);
}

// An SH polynomial table (Habel et al. 2008 eq. 1; docs/SH.md): fitted (`skylight sh fit`) or
// read from its JSON file, evaluated, written, exported and checked (`sh error`).
class ShTable {
 public:
  explicit ShTable(sl::sh::PolynomialTable t) : table_(std::move(t)) {}

  static ShTable load(const std::string& path) {
    return ShTable(sl::sh::table_from_json(sl::io::read_text_file(path), path));
  }
  // A table of `sh fit`'s JSON (the fit operation's output kept in memory).
  static ShTable from_json(const std::string& text) {
    return ShTable(sl::sh::table_from_json(text, "the table"));
  }
  std::string to_json() const { return sl::sh::table_to_json(table_); }

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
  // The category of the library's warnings (a flag the request does not read, a model outside its
  // domain): the command line's "skylight: warning: ..." lines.
  g_warning_category = PyErr_NewException("pyskylight.SkylightWarning", PyExc_UserWarning, nullptr);
  m.attr("SkylightWarning") = py::reinterpret_borrow<py::object>(g_warning_category);
  // The GL paths of the operations, when this build has the GPU module.
  sl::frontend::install_gpu_backend();
  m.def("models_json", &sl::operations::models_json);
  m.def("operations_json", &sl::operations::operations_json);
  m.def("sun_position", &sun_position, py::arg("ns"), py::arg("kwargs"));
  m.def("read_image", &read_image, py::arg("path"));
  m.def("read_kider", &read_kider, py::arg("path"));
  m.def("sh_project", &sh_project);
  m.def("run_operation", &run_operation, py::arg("name"), py::arg("kwargs"), py::arg("inputs"),
        py::arg("progress"));
  m.def("sun_events", &sun_events);
  m.def("sh_per_direction", &sh_per_direction);
  m.def("sh_rotate", &sh_rotate);
  m.def("sh_rotate_about_zenith", &sh_rotate_about_zenith);
  m.def("sh_ringing_filter", [](py::array_t<double, py::array::c_style | py::array::forcecast> c) {
    return array_of(sl::sh::ringing_filter(coefficients_of(c)));
  });
  m.def("write_image", &write_image, py::arg("path"), py::arg("image"), py::arg("metadata"));
  py::class_<ShTable>(m, "_ShTable")
      .def_static("from_json", &ShTable::from_json)
      .def("to_json", &ShTable::to_json)
      .def_static("load", &ShTable::load)
      .def("coefficients", &ShTable::coefficients)
      .def("save", &ShTable::save)
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
