// `skylight eval`: a model evaluated for directions read as CSV (zenith_deg,azimuth_deg), written
// as CSV on standard output (rgb, xyz, luminance or spectral radiance).
#include <fmt/format.h>

#include <cmath>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/directions.h"
#include "skylight/io/file.h"
#include "skylight/models/evaluation.h"
#include "skylight/operations/operations.h"

namespace skylight::cli {
namespace {

struct EvalCommand {
  ModelOptions model;
  SchemaFlags flags;  // --quantity, --wavelengths, --reference (models/evaluation.h)
  std::string input;
};

int run_eval(const EvalCommand& f) {
  EvaluationOptions options = f.flags.bind(EvaluationOptions::schema(), {}, "eval");
  validate(options);
  options.sun = f.model.sun_mode();
  const auto model = f.model.make();
  warn_domain(*model, options.quantity == Quantity::spectral);
  validate(options, *model);
  const ReferenceOptions ref = f.flags.bind(ReferenceOptions::schema(), {}, "eval");
  if (!ref.reference)
    for (const char* name : {"paths", "seed"})
      if (f.flags.given(name))
        warn(fmt::format("--{} is read only with --reference; ignored", name));
  const ModelInfo& info = require_model(std::string(model->name()), "model");

  const bool from_stdin = f.input.empty() || f.input == "-";
  const std::string source = from_stdin ? "<stdin>" : f.input;
  const std::string text = from_stdin ? read_stdin() : io::read_text_file(f.input);
  const auto rows = io::parse_directions_csv(text, source);
  std::string out(io::kDirectionsHeader);
  for (const std::string& c : quantity_columns(options)) out += "," + c;
  if (ref.reference)
    for (const std::string& c : quantity_columns(options)) out += "," + c + "_se";
  out += "\n";
  for (const auto& row : rows) {
    out += row.text;
    const Vec3 view = direction_from_angles(row.zenith, row.azimuth);
    std::vector<double> values;
    if (ref.reference) {
      const ReferenceValue r = evaluate_reference(info, *model, view, options, ref.request);
      values = r.value;
      values.insert(values.end(), r.standard_error.begin(), r.standard_error.end());
    } else {
      values = evaluate(*model, view, options);
    }
    for (double v : values) {
      // No output may hold NaN or Inf: a value that overflows is an error naming the row.
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format(
            "{} line {}: model '{}' gives a non-finite value (overflow) in this direction", source,
            row.line, model->name()));
      out += fmt::format(",{}", v);
    }
    out += "\n";
  }
  // Written only once everything parsed: a bad row produces no partial output.
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_eval_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<EvalCommand>();
  auto* cmd = app.add_subcommand(
      "eval", "evaluate a model for directions read as CSV (zenith_deg,azimuth_deg)");
  f->model.add(*cmd);
  cmd->add_option("--input", f->input, "input CSV file; default: standard input");
  f->flags.add(*cmd, operations::without_model_specs(operations::find("eval")));
  commands.push_back({cmd, [f] { return run_eval(*f); }});
}

}  // namespace skylight::cli
