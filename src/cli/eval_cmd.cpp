// `skylight eval`: a model evaluated for directions read as CSV (zenith_deg,azimuth_deg), written
// as CSV on standard output (rgb, xyz, luminance or spectral radiance).
#include <fmt/format.h>

#include <cmath>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/directions.h"
#include "skylight/io/file.h"

namespace skylight::cli {
namespace {

struct EvalFlags {
  ModelOptions model;
  std::string input;
  std::string quantity = "rgb";
  std::vector<double> wavelengths;
};

int run_eval(const EvalFlags& f) {
  const bool spectral = f.quantity == "spectral";
  if (spectral && f.wavelengths.empty())
    throw InvalidArgument("--quantity spectral needs --wavelengths NM[,NM...]");
  if (!spectral && !f.wavelengths.empty())
    throw InvalidArgument("--wavelengths is only used with --quantity spectral");
  const auto model = f.model.make();
  warn_domain(*model, spectral);
  if (spectral && !f.model.info().spectral)
    throw InvalidArgument(
        fmt::format("--quantity spectral: model '{}' has no spectral output", model->name()));

  const bool from_stdin = f.input.empty() || f.input == "-";
  const std::string source = from_stdin ? "<stdin>" : f.input;
  const std::string text = from_stdin ? read_stdin() : io::read_text_file(f.input);
  const auto rows = io::parse_directions_csv(text, source);
  std::string out(io::kDirectionsHeader);
  if (f.quantity == "rgb")
    out += ",r,g,b";
  else if (f.quantity == "xyz")
    out += ",x,y,z";
  else if (f.quantity == "luminance")
    out += ",luminance";
  else
    for (double nm : f.wavelengths) out += fmt::format(",L{}", nm);
  out += "\n";

  // No output may hold NaN or Inf: a value that overflows is an error naming the row.
  auto value = [&](std::size_t line_no, double v) {
    if (!std::isfinite(v))
      throw InvalidArgument(fmt::format(
          "{} line {}: model '{}' gives a non-finite value (overflow) in this direction", source,
          line_no, model->name()));
    return v;
  };
  const bool sky = !f.model.sun_only(), sun = f.model.include_sun() || f.model.sun_only();
  for (const auto& row : rows) {
    const std::size_t line_no = row.line;
    const Vec3 v = direction_from_angles(row.zenith, row.azimuth);
    out += row.text;
    if (spectral) {
      for (double nm : f.wavelengths) {
        double L = 0.0;
        if (sky) {
          const auto s = model->spectral_radiance(v, nm);
          if (!s)
            throw InvalidArgument(fmt::format(
                "--wavelengths: {} nm is outside the range of model '{}'", nm, model->name()));
          L += *s;
        }
        if (sun) {
          const auto s = model->sun_spectral_radiance(v, nm);
          if (!s)
            throw InvalidArgument(
                fmt::format("--wavelengths: {} nm is outside the sun's range of model '{}'", nm,
                            model->name()));
          L += *s;
        }
        out += fmt::format(",{}", value(line_no, L));
      }
    } else {
      Xyz c;
      if (sky) c = model->tristimulus(v);
      if (sun) {
        const Xyz s = model->sun_tristimulus(v);
        c = {c.X + s.X, c.Y + s.Y, c.Z + s.Z};
      }
      if (f.quantity == "xyz") {
        out +=
            fmt::format(",{},{},{}", value(line_no, c.X), value(line_no, c.Y), value(line_no, c.Z));
      } else if (f.quantity == "luminance") {
        out += fmt::format(",{}", value(line_no, c.Y));
      } else {
        const Rgb rgb = (sky && !sun) ? model->rgb(v) : xyz_to_linear_srgb(c);
        out += fmt::format(",{},{},{}", value(line_no, rgb.r), value(line_no, rgb.g),
                           value(line_no, rgb.b));
      }
    }
    out += "\n";
  }
  // Written only once everything parsed: a bad row produces no partial output.
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_eval_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<EvalFlags>();
  auto* cmd = app.add_subcommand(
      "eval", "evaluate a model for directions read as CSV (zenith_deg,azimuth_deg)");
  f->model.add(*cmd);
  cmd->add_option("--input", f->input, "input CSV file; default: standard input");
  cmd->add_option("--quantity", f->quantity,
                  "rgb (linear sRGB), xyz (Y in cd/m^2), luminance (cd/m^2), spectral (W m^-2 "
                  "sr^-1 nm^-1); default rgb")
      ->check(CLI::IsMember({"rgb", "xyz", "luminance", "spectral"}));
  add_numbers(*cmd,
              {"wavelengths", "nm", ParameterKind::numbers, 1.0, 10000.0, 0, Absent{"none"},
               "wavelengths for --quantity spectral, e.g. 450,550,650"},
              f->wavelengths);
  commands.push_back({cmd, [f] { return run_eval(*f); }});
}

}  // namespace skylight::cli
