// `skylight models [--json]`: the registry with each model's parameters (from the schema).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/operations/operations.h"

namespace skylight::cli {
namespace {

nlohmann::ordered_json value_json(const ParameterValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* l = std::get_if<std::vector<double>>(&v)) return *l;
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  return std::get<bool>(v);
}

// A parameter as JSON: the schema entry with a typed default ("required" when the model needs
// it; null when absent, with `when_absent` saying what the model does then).
nlohmann::ordered_json spec_json(const ParameterSpec& s) {
  nlohmann::ordered_json j{
      {"name", s.name}, {"unit", s.unit}, {"kind", std::string(to_string(s.kind))}};
  if (s.kind != ParameterKind::text && s.kind != ParameterKind::flag) {
    j["min"] = s.min;
    j["max"] = s.max;
  }
  if (s.kind == ParameterKind::numbers) j["count"] = s.count;
  j["required"] = s.required();
  if (s.required()) {
    j["default"] = "required";
  } else if (const auto* a = std::get_if<Absent>(&s.default_value)) {
    j["default"] = nullptr;
    j["when_absent"] = a->meaning;
  } else {
    j["default"] = value_json(std::get<ParameterValue>(s.default_value));
  }
  j["description"] = s.description;
  if (!s.choices.empty()) j["choices"] = s.choices;
  return j;
}

int run_models(bool json, bool markdown) {
  if (json && markdown) throw InvalidArgument("--json and --markdown exclude each other");
  std::string out;
  if (markdown) {
    for (const auto& m : model_registry()) out += parameter_docs_block(m) + "\n";
  } else if (json) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& m : model_registry()) {
      nlohmann::ordered_json params = nlohmann::ordered_json::array();
      for (const auto& p : all_parameters(m)) params.push_back(spec_json(p));
      list.push_back({{"name", m.name},
                      {"description", m.description},
                      {"output", m.output},
                      {"parameters", params},
                      {"domain", m.domain},
                      {"spectral", m.spectral},
                      {"sun", m.sun},
                      {"luminance_only", m.luminance_only},
                      {"colour", m.colour_note()}});
    }
    out = list.dump(2) + "\n";
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
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& op : operations::registry()) {
      nlohmann::ordered_json params = nlohmann::ordered_json::array();
      for (const auto& p : op.parameters) params.push_back(spec_json(p));
      list.push_back({{"name", op.name},
                      {"description", op.description},
                      {"parameters", params},
                      {"result", op.result}});
    }
    out = list.dump(2) + "\n";
  } else {
    for (const auto& op : operations::registry()) {
      out += fmt::format("{}\n  {}\n  result: {}\n  parameters:\n", op.name, op.description,
                         op.result);
      for (const auto& p : op.parameters)
        out += fmt::format("    --{:<22} [{}] {}, default {}: {}\n", p.name, p.unit, p.range_text(),
                           p.default_text(), p.description);
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
  commands.push_back({cmd, [flags] { return run_models((*flags)[0], (*flags)[1]); }});

  auto op_flags = std::make_shared<std::array<bool, 2>>();
  auto* ops = app.add_subcommand(
      "operations",
      "list the operations with options, their parameters and results\n"
      "Every operation with options (estimate, sh fit, nn train, haze add, ...): its parameters "
      "(unit, range, default) and results; the models' parameters: `skylight models`.");
  ops->add_flag("--json", (*op_flags)[0], "machine-readable JSON");
  ops->add_flag("--markdown", (*op_flags)[1], "the parameter tables of docs/OPERATIONS.md");
  commands.push_back({ops, [op_flags] { return run_operations((*op_flags)[0], (*op_flags)[1]); }});
}

}  // namespace skylight::cli
