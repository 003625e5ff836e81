#include "common.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <iostream>
#include <utility>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/text.h"
#include "skylight/io/file.h"
#include "skylight/operations/operations.h"
#include "skylight/version.h"

namespace skylight::cli {

// ---- unknown names ------------------------------------------------------------------------------

std::optional<std::string> unknown_name_error(const CLI::App& app, int argc,
                                              const char* const* argv) {
  const CLI::App* current = &app;
  std::string path;  // the subcommands so far, "nn train"
  // Options of the current command and of every command above it (global options fall through).
  const auto find_option = [&](const std::string& name) -> const CLI::Option* {
    for (const CLI::App* a = current; a; a = a->get_parent())
      if (const CLI::Option* o = a->get_option_no_throw(name)) return o;
    return nullptr;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string token = argv[i];
    if (token == "--") break;
    const bool negative_number =
        token.size() > 1 && (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.');
    if (token.size() > 1 && token[0] == '-' && !negative_number) {
      const std::string name = token.substr(0, token.find('='));
      const CLI::Option* option = find_option(name);
      if (!option) {
        std::vector<std::string> names;
        for (const CLI::App* a = current; a; a = a->get_parent())
          for (const CLI::Option* o : a->get_options()) {
            for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
            for (const std::string& s : o->get_snames()) names.push_back("-" + s);
          }
        return fmt::format("unknown option '{}' for '{}'{}", excerpt(name),
                           path.empty() ? "skylight" : path, did_you_mean(name, names));
      }
      // Its value is the next word (unless given as --flag=value).
      if (token.find('=') == std::string::npos && option->get_items_expected_max() > 0) ++i;
      continue;
    }
    std::vector<std::string> subcommands;
    for (const CLI::App* s : current->get_subcommands([](const CLI::App*) { return true; }))
      subcommands.push_back(s->get_name());
    if (subcommands.empty()) continue;  // a positional argument of a leaf command
    if (std::find(subcommands.begin(), subcommands.end(), token) == subcommands.end())
      return fmt::format("unknown subcommand '{}'{}{} (subcommands: {})", excerpt(token),
                         path.empty() ? "" : " for '" + path + "'",
                         did_you_mean(token, subcommands), fmt::join(subcommands, ", "));
    current = current->get_subcommand(token);
    path += (path.empty() ? "" : " ") + token;
  }
  return std::nullopt;
}

// ---- help pages ---------------------------------------------------------------------------------

namespace {

// `text` broken at spaces into lines of at most `width` columns (a longer word stands alone),
// every line after the first indented by `indent` columns; its own line breaks are kept.
std::string wrapped(std::string_view text, std::size_t indent, std::size_t width) {
  const std::size_t room = width > indent + 20 ? width - indent : 20;
  std::string out, line;
  const auto flush = [&] {
    if (!out.empty()) out += "\n" + std::string(indent, ' ');
    out += line;
    line.clear();
  };
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view paragraph = text.substr(start, end - start);
    // Words; a range "2 .. 1000000" stays one.
    std::vector<std::string> words;
    for (std::size_t pos = 0; pos < paragraph.size();) {
      const std::size_t space = std::min(paragraph.find(' ', pos), paragraph.size());
      std::string word(paragraph.substr(pos, space - pos));
      if (!words.empty() && (word == ".." || words.back().ends_with(" ..")))
        words.back() += " " + word;
      else
        words.push_back(std::move(word));
      pos = space + 1;
    }
    for (const std::string& word : words) {
      if (!line.empty() && line.size() + 1 + word.size() > room) flush();
      if (!line.empty()) line += ' ';
      line += word;
    }
    flush();
    start = end + 1;
  }
  return out;
}

}  // namespace

HelpFormatter::HelpFormatter() {
  column_width(30);
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  std::string name = "  " + make_option_name(opt, is_positional) + make_option_opts(opt);
  const std::string desc = make_option_desc(opt);
  if (desc.empty()) return name + "\n";
  name += name.size() >= get_column_width() ? "\n" + std::string(get_column_width(), ' ')
                                            : std::string(get_column_width() - name.size(), ' ');
  return name + wrapped(desc, get_column_width(), kHelpWidth) + "\n";
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
  const std::string& d = sub->get_description();
  std::string name = "  " + sub->get_display_name(true);
  name.resize(std::max(name.size() + 1, get_column_width()), ' ');
  return name + d.substr(0, d.find('\n')) + "\n";
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  // "summary\ndetail": the page shows the detail, which says it all.
  const std::string& d = app->get_description();
  const std::size_t newline = d.find('\n');
  const std::string page = newline == std::string::npos ? d : d.substr(newline + 1);
  return page.empty() ? std::string() : wrapped(page, 0, kHelpWidth) + "\n";
}

// ---- flags from the schema ----------------------------------------------------------------------

namespace {}  // namespace

std::string flag_spelling(std::string_view name) {
  return name == "output" ? "-o" : "--" + std::string(name);
}

CLI::Validator schema_check(const ParameterSpec& spec) {
  // No description: the help text already shows the range as the schema writes it.
  return CLI::Validator(
      [spec](std::string& text) -> std::string {
        // The library's message names the flag ("--lat = 91 is outside [-90, 90]"): thrown as
        // it is rather than under CLI11's "--lat: " prefix (main() prints it).
        spec.check(spec.parse(text));
        return {};
      },
      "");
}

std::string value_label(const ParameterSpec& spec) {
  switch (spec.kind) {
    case ParameterKind::integer:
      return "INT";
    case ParameterKind::number:
      return "NUMBER";
    case ParameterKind::numbers: {
      if (spec.count <= 0) return "N,N,...";
      std::string label = "N";
      for (std::size_t i = 1; i < spec.count; ++i) label += ",N";
      return label;
    }
    case ParameterKind::text:
      return spec.choices.empty() ? "TEXT" : fmt::format("{{{}}}", fmt::join(spec.choices, "|"));
    case ParameterKind::flag:
      return {};
  }
  return {};
}

void SchemaFlags::add(CLI::App& app, const std::vector<ParameterSpec>& specs) {
  for (const ParameterSpec& spec : specs) {
    specs_.push_back(spec);
    auto& raw = raw_[spec.name];
    CLI::Option* opt = nullptr;
    if (spec.kind == ParameterKind::flag) {
      opt = app.add_flag_callback(
          spec.flag(), [&raw] { raw = "true"; }, spec.help());
    } else if (spec.repeated) {
      opt = app.add_option_function<std::vector<std::string>>(
          spec.flag(), [&raw](const std::vector<std::string>& v) { raw = join_repeated(v); },
          spec.help());
    } else {
      opt = app.add_option_function<std::string>(
          spec.flag(), [&raw](const std::string& s) { raw = s; }, spec.help());
      if (spec.kind != ParameterKind::text || !spec.choices.empty()) opt->check(schema_check(spec));
    }
    if (spec.kind != ParameterKind::flag) opt->type_name(value_label(spec));
    options_[spec.name] = opt;
  }
}

CLI::Option* SchemaFlags::option(std::string_view name) const {
  const auto it = options_.find(name);
  SKYLIGHT_CHECK(it != options_.end(), "SchemaFlags: no such flag");
  return it->second;
}

bool SchemaFlags::given(std::string_view name) const {
  const auto it = raw_.find(name);
  return it != raw_.end() && it->second.has_value();
}

ParameterValues SchemaFlags::values() const {
  ParameterValues v;
  for (const ParameterSpec& spec : specs_)
    if (const auto& raw = raw_.at(spec.name)) v.set(spec.name, spec.parse(*raw));
  return v;
}

std::optional<sun::SpaInput> solar_position_input(const ParameterValues& given) {
  return operations::solar_position_input(given);
}

void warn_unread_layout(const ImageOptions& layout, const ParameterValues& given) {
  for (const std::string& name : layout.unread(given))
    warn(fmt::format("{} is not read ({}); ignored", flag_spelling(name),
                     layout.calibration.empty()
                         ? "not a parameter of this projection"
                         : flag_spelling(layout.calibration_flag) + " gives the layout"));
}

void wire_solar_position(const SchemaFlags& flags, const std::vector<std::string>& angles,
                         bool spa_needs_time) {
  CLI::Option* time = flags.option("time");
  for (const std::string& a : angles) time->excludes(flags.option(a));
  if (!spa_needs_time) return;
  for (const auto& spec : sun::spa_parameter_specs())
    if (flags.has(spec.name)) flags.option(spec.name)->needs(time);
}

// ---- model flags --------------------------------------------------------------------------------

std::vector<std::pair<std::string, std::vector<std::pair<std::string, ParameterSpec>>>>
model_parameter_names() {
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, ParameterSpec>>>> out;
  for (const auto& m : model_registry()) {
    for (const auto& spec : m.parameters) {
      auto it = std::find_if(out.begin(), out.end(),
                             [&](const auto& entry) { return entry.first == spec.name; });
      if (it == out.end()) {
        out.push_back({spec.name, {}});
        it = out.end() - 1;
      }
      it->second.emplace_back(m.name, spec);
    }
  }
  return out;
}

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

}  // namespace

void ModelOptions::add(CLI::App& app) {
  // --model without CLI11's membership check: an unknown name is the registry's error, which
  // lists the models.
  const ParameterSpec model = model_spec();
  app.add_option(model.flag(), model_, model.description)->required();
  std::vector<ParameterSpec> specs = operations::model_specs();
  specs.erase(std::remove_if(specs.begin(), specs.end(),
                             [&](const ParameterSpec& s) { return s.name == model.name; }),
              specs.end());
  flags_.add(app, specs);
  flags_.option("sun-zenith")->excludes(flags_.option("sun-elevation"));
  wire_solar_position(flags_, {"sun-zenith", "sun-elevation", "sun-azimuth"});
  flags_.option("include-sun")->excludes(flags_.option("sun-only"));
  for (const auto& [name, specs] : model_parameter_names()) {
    const bool flag = std::all_of(specs.begin(), specs.end(), [](const auto& s) {
      return s.second.kind == ParameterKind::flag;
    });
    if (flag) {
      // A switch (no value): present = true.
      raw_[name];
      app.add_flag_callback(
          "--" + name, [this, n = name] { raw_[n] = "true"; }, model_flag_help(specs));
    } else {
      app.add_option("--" + name, raw_[name], model_flag_help(specs))
          ->type_name(value_label(specs.front().second));
    }
  }
}

std::string ModelOptions::model_name() const {
  return model_;
}

SunMode ModelOptions::sun_mode() const {
  return flags_.bind(SolarDisc::schema(), SolarDisc{}, "solar disc").mode;
}

const ModelInfo& ModelOptions::info() const {
  return require_model(model_name());
}

SkyParameters ModelOptions::parameters() const {
  const ModelInfo& m = info();
  ParameterValues given = flags_.values();
  for (const auto& [name, text] : raw_) {
    if (!text) continue;
    const ParameterSpec* spec = m.find_parameter(name);
    if (spec == nullptr) {
      warn(fmt::format("--{} is not a parameter of model '{}'; ignored", name, m.name));
      continue;
    }
    given.set(name, spec->parse(*text));
  }
  return operations::sky_request(m, given).parameters;
}

std::unique_ptr<SkyModel> ModelOptions::make() const {
  const SkyParameters p = parameters();
  auto model = make_sky_model(info().name, p);
  // A parameter of the schema that this model, with these values, does not read (e.g. nn's
  // turbidity for a network trained without one): said, and not recorded (parameter_values()).
  const ParameterValues read = model->parameter_values();
  for (const auto& [name, value] : p.values.all())
    if (!read.has(name))
      warn(fmt::format("--{} is not read by model '{}' with these parameters; ignored", name,
                       model->name()));
  check_sun_mode(*model, sun_mode());
  return model;
}

io::Metadata ModelOptions::solar_position_metadata() const {
  const auto spa = solar_position_input(flags_.values());
  if (!spa) return {};
  const sun::SpaInput& in = *spa;
  return {
      {"skylight:time", sun::format_iso8601(in.time, 3)},
      {"skylight:latitude_deg", fmt::format("{}", rad_to_deg(in.latitude))},
      {"skylight:longitude_deg", fmt::format("{}", rad_to_deg(in.longitude))},
      {"skylight:elevation_m", fmt::format("{}", in.elevation)},
      {"skylight:pressure_mbar", fmt::format("{}", in.pressure)},
      {"skylight:temperature_degC", fmt::format("{}", in.temperature)},
      {"skylight:delta_t_s", fmt::format("{}", in.delta_t)},
  };
}

void warn(std::string_view message) {
  std::cerr << "skylight: warning: " << message << "\n";
}

void warn_domain(const SkyModel& model, bool spectral) {
  for (const auto& issue : model.domain().issues)
    if (spectral || !issue.spectral_only)
      warn(fmt::format("{} ({}): {}", model.name(), to_string(issue.validity), issue.message));
}

io::Metadata model_metadata(const SkyModel& model, std::string_view sun_mode) {
  const auto& sun = sun_parameter_specs();
  io::Metadata md{
      {"skylight:version", kVersion},
      {"skylight:model", std::string(model.name())},
      {sun[0].metadata_key(), fmt::format("{}", rad_to_deg(model.sun().zenith))},
      {sun[1].metadata_key(), fmt::format("{}", rad_to_deg(model.sun().azimuth))},
  };
  const ParameterValues values = model.parameter_values();
  const ModelInfo& info = require_model(model.name());
  for (const auto& spec : info.parameters)
    if (const ParameterValue* v = values.find(spec.name))
      md.emplace_back(spec.metadata_key(), spec.format(*v));
  md.emplace_back("skylight:sun", std::string(sun_mode));
  md.emplace_back("skylight:colour", info.colour_note());
  return md;
}

// ---- output -------------------------------------------------------------------------------------

void write_stdout(std::string_view text) {
  std::cout.write(text.data(), static_cast<std::streamsize>(text.size()));
  std::cout.flush();
  if (!std::cout) {
    const int err = errno;
    std::cout.clear();
    throw IoError(fmt::format("cannot write to standard output: {}",
                              err != 0 ? io::errno_message(err) : "write failed"));
  }
}

namespace {
std::vector<std::pair<std::string, bool>>& commit_notices() {
  static std::vector<std::pair<std::string, bool>> notices;
  return notices;
}
}  // namespace

void announce_after_commit(std::string line, bool to_stderr) {
  commit_notices().emplace_back(std::move(line), to_stderr);
}

void print_commit_notices() {
  std::vector<std::pair<std::string, bool>> notices;
  notices.swap(commit_notices());
  for (const auto& [line, to_stderr] : notices) {
    if (to_stderr)
      std::cerr << line << "\n";
    else
      write_stdout(line + "\n");
  }
}

std::string read_stdin() {
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(STDIN_FILENO, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0) {
      return text;
    } else if (errno != EINTR) {
      throw IoError(fmt::format("cannot read standard input: {}", io::errno_message(errno)));
    }
  }
}

Progress::Progress(std::string command)
    : command_(std::move(command)),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

double Progress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::operator()(int done, int total, std::string_view step) {
  if (tty_) {
    constexpr int kBar = 30;
    const int filled = total > 0 ? done * kBar / total : kBar;
    std::cerr << fmt::format("\r\x1b[K[{}{}] {:>2}/{} {:5.1f} s  {}", std::string(filled, '#'),
                             std::string(kBar - filled, ' '), done, total, elapsed_s(), step)
              << std::flush;
    if (done == total) std::cerr << "\n";
  } else if (elapsed_s() >= kQuietSeconds) {
    // A log (not a terminal): one line per step, none while the command is still short.
    std::cerr << fmt::format("skylight {}: [{}/{}] {:.1f} s {}\n", command_, done, total,
                             elapsed_s(), step);
  }
}

}  // namespace skylight::cli
