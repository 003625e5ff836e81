// `skylight models [--json]`: the registry with each model's parameters (from the schema).
#include <fmt/format.h>

#include <array>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/operations/operations.h"

namespace skylight::cli {
namespace {

int run_models(bool json, bool markdown) {
  if (json && markdown) throw InvalidArgument("--json and --markdown exclude each other");
  std::string out;
  if (markdown) {
    for (const auto& m : model_registry()) out += parameter_docs_block(m) + "\n";
  } else if (json) {
    out = operations::models_json() + "\n";
  } else {
    for (const auto& m : model_registry()) {
      out += fmt::format("{}\n  {}\n  output: {}\n  colour: {}\n  domain: {}\n  parameters:\n",
                         m.name, m.description, m.output, m.colour_note(), m.domain);
      for (const auto& p : all_parameters(m))
        out += fmt::format("    --{:<22} [{}] {}, default {}: {}\n", p.name, p.unit, p.range_text(),
                           p.default_text(), p.description);
    }
  }
  write_stdout(out);
  return kExitOk;
}

int run_operations(bool json, bool markdown) {
  if (json && markdown) throw InvalidArgument("--json and --markdown exclude each other");
  std::string out;
  if (markdown) {
    for (const auto& op : operations::registry()) out += operations::markdown(op) + "\n";
  } else if (json) {
    out = operations::operations_json() + "\n";
  } else {
    for (const auto& op : operations::registry()) {
      out += fmt::format("{}\n  {}\n  result: {}\n  parameters:\n", op.name, op.description,
                         op.result_type);
      for (const auto& p : op.parameters)
        out += fmt::format("    --{:<22} [{}] {}, default {}: {}\n", p.name, p.unit, p.range_text(),
                           p.default_text(), p.description);
      for (const auto& r : op.relations)
        out += fmt::format("    relation: --{} {} --{}{}\n", r.a, operations::to_string(r.kind),
                           r.b, r.unread ? " (unread otherwise)" : "");
      out += "  result fields:";
      for (const auto& f : op.result) out += " " + f.name;
      out += "\n";
    }
  }
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_models_command(CLI::App& app, Commands& commands) {
  auto flags = std::make_shared<std::array<bool, 2>>();
  auto* cmd = app.add_subcommand(
      "models", "list the models, their parameters (unit, range, default) and domains");
  cmd->add_flag("--json", (*flags)[0], "machine-readable JSON");
  cmd->add_flag("--markdown", (*flags)[1],
                "the parameter tables of docs/MODELS.md (generated from the schema)");
  commands.push_back({cmd, [flags](const auto&) { return run_models((*flags)[0], (*flags)[1]); }});

  auto op_flags = std::make_shared<std::array<bool, 2>>();
  auto* ops = app.add_subcommand(
      "operations",
      "list the operations with options, their parameters and results\n"
      "Every operation with options (estimate, sh fit, nn train, haze add, ...): its parameters "
      "(unit, range, default) and results; the models' parameters: `skylight models`.");
  ops->add_flag("--json", (*op_flags)[0], "machine-readable JSON");
  ops->add_flag("--markdown", (*op_flags)[1], "the parameter tables of docs/OPERATIONS.md");
  commands.push_back(
      {ops, [op_flags](const auto&) { return run_operations((*op_flags)[0], (*op_flags)[1]); }});
}

}  // namespace skylight::cli
