// Every operation of the library as a command, generated from its declaration
// (operations/operation.h): its flags from its parameters (and, for render and eval, one per
// parameter name of every model), --json where it has a record to show; the run is prepare()
// (every usage error before any work), execute() (outputs in one transaction) and the record as
// labelled lines or JSON. No command is written by hand.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <memory>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/operations/operations.h"

namespace skylight::cli {
namespace {

// Help for a parameter several models declare: the first description, then each model's range
// and default.
std::string model_flag_help(const std::vector<std::pair<std::string, ParameterSpec>>& specs) {
  const ParameterSpec& first = specs.front().second;
  std::string h = first.description;
  if (!first.unit.empty() && first.unit != "1") h += fmt::format(" [{}]", first.unit);
  for (const auto& [model, spec] : specs) {
    h += fmt::format("; {}: ", model);
    if (spec.kind == ParameterKind::numbers) h += fmt::format("{} values, each ", spec.count);
    h += fmt::format("{}, default {}", spec.range_text(), spec.default_text());
  }
  return h;
}

struct OperationCommand {
  const operations::OperationInfo* op = nullptr;
  CLI::App* app = nullptr;
  SchemaFlags flags;
  // The models' parameters (model_parameters), as text until the chosen model's spec parses them.
  std::map<std::string, std::optional<std::string>> model_raw;
  bool json = false;
};

// The arguments CLI11 left (allow_extras): unknown flags become values of their names, so that
// prepare() refuses them as every front end's unknown names are refused, with the nearest name.
void add_extras(const OperationCommand& c, const std::vector<std::string>& extras,
                ParameterValues& given) {
  for (std::size_t i = 0; i < extras.size(); ++i) {
    const std::string& t = extras[i];
    const bool option = t.size() > 1 && t[0] == '-' &&
                        !std::isdigit(static_cast<unsigned char>(t[1])) && t[1] != '.';
    if (!option)
      throw InvalidArgument(
          fmt::format("unexpected argument '{}' for '{}'", excerpt(t), c.op->name));
    std::string name = t.substr(t.find_first_not_of('-'));
    std::string value;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name.resize(eq);
    } else if (i + 1 < extras.size() && extras[i + 1].rfind("--", 0) != 0) {
      value = extras[++i];
    }
    given.set(name, value);
  }
}

int run_operation(const OperationCommand& c, const std::vector<std::string>& extras) {
  const operations::OperationInfo& op = *c.op;
  ParameterValues given = c.flags.values();
  add_extras(c, extras, given);
  if (op.model_parameters) {
    const ParameterValue* m = given.find("model");
    const std::string model = m ? std::get<std::string>(*m) : std::string();
    for (const auto& [name, text] : c.model_raw)
      if (text) given.set(name, operations::parameter_spec(op, model, name)->parse(*text));
  }
  Progress progress(op.name);
  operations::Frontend fe{
      .warn = [](const std::string& m) { warn(m); },
      .progress = [&](int done, int total, std::string_view step) { progress(done, total, step); },
      .standard_input = read_stdin};
  const operations::Request request = operations::prepare(op, std::move(given), std::move(fe));
  const operations::Result result = operations::execute(request, [&](const auto& r) {
    // Shown before the outputs commit: a failed write to standard output writes nothing.
    if (r.wrote_standard_output)
      write_stdout(r.standard_output);
    else
      write_stdout(
          c.json ? r.record.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
                       "\n"
                 : operations::text_of(op.result, r.record));
  });
  for (const std::string& notice : result.notices) std::cerr << "skylight: " << notice << "\n";
  if (result.then) {
    std::cerr.flush();
    result.then();
  }
  return kExitOk;
}

// "the solar position ..." as a page: a capital and a full stop.
std::string page(std::string text) {
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  if (!text.empty() && text.back() != '.') text += '.';
  return text;
}

void add_operation(CLI::App& parent, const std::string& leaf, const operations::OperationInfo& op,
                   Commands& commands) {
  auto c = std::make_shared<OperationCommand>();
  c->op = &op;
  c->app = parent.add_subcommand(leaf, op.summary + "\n" + page(op.description));
  c->flags.add(*c->app, op.parameters);
  if (op.model_parameters)
    for (const auto& [name, specs] : model_parameter_names()) {
      if (op.find(name)) continue;
      auto& raw = c->model_raw[name];
      const bool flag = std::all_of(specs.begin(), specs.end(), [](const auto& s) {
        return s.second.kind == ParameterKind::flag;
      });
      if (flag)
        c->app->add_flag_callback(
            "--" + name, [&raw] { raw = "true"; }, model_flag_help(specs));
      else
        c->app
            ->add_option_function<std::string>(
                "--" + name, [&raw](const std::string& s) { raw = s; }, model_flag_help(specs))
            ->type_name(value_label(specs.front().second));
    }
  // An operation whose output goes to standard output (eval's CSV) shows no record there.
  const bool stdout_output =
      std::any_of(op.parameters.begin(), op.parameters.end(),
                  [](const auto& s) { return s.file == FileRole::output && s.standard_stream; });
  if (!op.result.empty() && !stdout_output)
    c->app->add_flag("--json", c->json, "write the result as JSON instead of labelled lines");
  // Unknown flags are the library's to refuse (prepare), as for every front end.
  commands.push_back(
      {c->app, [c](const std::vector<std::string>& extras) { return run_operation(*c, extras); },
       true});
}

}  // namespace

void add_operation_commands(CLI::App& app, Commands& commands) {
  // A family's group where its first operation stands in the registry's order.
  std::map<std::string, CLI::App*, std::less<>> groups;
  const auto group = [&](std::string_view name) {
    if (const auto it = groups.find(name); it != groups.end()) return it->second;
    const auto& fs = operations::families();
    const auto f =
        std::find_if(fs.begin(), fs.end(), [&](const auto& x) { return x.name == name; });
    SKYLIGHT_CHECK(f != fs.end(), "an operation of an undeclared family");
    CLI::App* g = app.add_subcommand(f->name, f->summary + "\n" + f->description);
    g->require_subcommand(1);
    return groups[f->name] = g;
  };
  for (const auto& op : operations::registry()) {
    const auto space = op.name.find(' ');
    if (space == std::string::npos)
      add_operation(app, op.name, op, commands);
    else
      add_operation(*group(std::string_view(op.name).substr(0, space)), op.name.substr(space + 1),
                    op, commands);
  }
}

}  // namespace skylight::cli
