// Shared machinery of the command-line tool: the subcommand table, exit statuses, flags built from
// the parameter schema (core/parameters.h), the model flags of `render` and `eval`, output
// metadata, checked writes to standard output and progress lines. Each subcommand family lives in
// its own file (models_cmd.cpp, render_cmd.cpp, eval_cmd.cpp, bench_cmd.cpp, report_cmd.cpp,
// sun_cmd.cpp, estimate_cmd.cpp, sh_cmd.cpp, haze_cmd.cpp; the nn family in nn/) and only parses,
// validates through the operation's schema, calls the library and writes outputs.
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/parameters.h"
#include "skylight/io/image.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/sky_model.h"
#include "skylight/sun/spa.h"

namespace skylight::cli {

// Exit status: 0 success, 1 runtime failure (I/O, ...), 2 usage error or invalid value.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

// One subcommand: its CLI11 app and what runs when it was given.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
using Commands = std::vector<Command>;

// The subcommand families; each adds its subcommands to `app` and `commands`.
void add_models_command(CLI::App& app, Commands& commands);
void add_render_command(CLI::App& app, Commands& commands);
void add_eval_command(CLI::App& app, Commands& commands);
void add_bench_command(CLI::App& app, Commands& commands);
void add_report_command(CLI::App& app, Commands& commands);
void add_sun_command(CLI::App& app, Commands& commands);
void add_daylight_command(CLI::App& app, Commands& commands);
void add_nn_command(CLI::App& app, Commands& commands);
void add_estimate_command(CLI::App& app, Commands& commands);
void add_sh_command(CLI::App& app, Commands& commands);
void add_haze_command(CLI::App& app, Commands& commands);

// When CLI11 refused the command line: the first flag that no command on the path (or the global
// options) has, or the first word that is not a subcommand where one is expected, as a one-line
// message with the nearest name ("unknown option '--turbidty' for 'render'; did you mean
// '--turbidity'?"). nullopt when every name is known (CLI11's own message then stands).
std::optional<std::string> unknown_name_error(const CLI::App& app, int argc,
                                              const char* const* argv);

// ---- flags from the schema ----------------------------------------------------------------------

// How the library's messages name a parameter here (set_parameter_spelling): its flag, "--name";
// "output" is every command's -o.
std::string flag_spelling(std::string_view name);

// A CLI11 check of a value by its spec: a number (strict parser) in the spec's range, or one of a
// text's choices; the help text shows the unit and range. A bad value throws the library's
// InvalidArgument, which names the flag (and the nearest choice).
CLI::Validator schema_check(const ParameterSpec& spec);
// What --help shows for a flag's value: INT, NUMBER, N,N (a list of two), TEXT or {a|b|c}.
std::string value_label(const ParameterSpec& spec);

// --help as a manual page: option descriptions wrapped at kHelpWidth columns under their flag. A
// command's description is "summary" or "summary\ndetail": its line in the parent's list shows the
// summary, its own page the detail.
class HelpFormatter : public CLI::Formatter {
 public:
  static constexpr std::size_t kHelpWidth = 100;
  HelpFormatter();
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;
};

// The flags of a library schema (an operation's settings, core/parameters.h): one per spec, the
// values kept as given until the command runs, then parsed and checked by the specs and bound
// into the library's settings by its schema. --help, the range errors and the defaults are the
// specs'.
class SchemaFlags {
 public:
  // Adds --NAME per spec: numbers range-checked and a text of choices checked (schema_check), a
  // flag as a switch. Returns the first option added.
  void add(CLI::App& app, const std::vector<ParameterSpec>& specs);
  CLI::Option* option(std::string_view name) const;
  bool has(std::string_view name) const { return options_.count(name) > 0; }
  bool given(std::string_view name) const;
  // The given values, parsed by their specs.
  ParameterValues values() const;
  // Binds the given values of the schema's specs over p (the schema checks them).
  template <class P>
  P bind(const ParameterSchema<P>& schema, P p, std::string_view context) const {
    schema.bind(values().only(schema.specs()), p, context);
    return p;
  }

 private:
  std::vector<ParameterSpec> specs_;
  std::map<std::string, std::optional<std::string>, std::less<>> raw_;
  std::map<std::string, CLI::Option*, std::less<>> options_;
};

// The SPA input of --time and its flags among the given values (sun::spa_input_schema() binds
// them; a missing --lat/--lon throws), nullopt without --time.
std::optional<sun::SpaInput> solar_position_input(const ParameterValues& given);
// --time excludes the given angle flags; each SPA flag needs --time.
// spa_needs_time = false: the SPA options may also go with another source of the time (estimate's
// --exif), which the command checks itself.
void wire_solar_position(const SchemaFlags& flags, const std::vector<std::string>& angles,
                         bool spa_needs_time = true);

// ---- model flags (render, eval) -----------------------------------------------------------------

// --model, the sun (--sun-zenith | --sun-elevation, --sun-azimuth, or the solar position from
// --time --lat --lon [--elevation --pressure --temperature --delta-t], exclusive with the angles),
// one flag per parameter name of every registered model (its help lists each model's unit, range
// and default), and the solar disc switches. The values are kept as text and parsed by the chosen
// model's schema.
class ModelOptions {
 public:
  // The model's flags: the operation's --model, sun, solar-position and solar-disc parameters
  // (operations::model_specs()) and one flag per parameter name of every registered model.
  void add(CLI::App& app);
  // The registry entry of --model (InvalidArgument for an unknown name).
  const ModelInfo& info() const;
  // The sun and the chosen model's values. A given flag that the model does not read is reported
  // on stderr as a warning and ignored.
  SkyParameters parameters() const;
  // The model (InvalidArgument for bad values, or for --include-sun/--sun-only without a sun).
  std::unique_ptr<SkyModel> make() const;
  // The solar-position inputs as metadata (skylight:time, skylight:latitude_deg, ...) when the sun
  // came from --time; empty otherwise.
  io::Metadata solar_position_metadata() const;
  // The solar disc switches (--include-sun, --sun-only).
  SunMode sun_mode() const;
  std::string model_name() const;

 private:
  std::string model_;
  SchemaFlags flags_;
  std::map<std::string, std::optional<std::string>> raw_;  // parameter name -> text as given
};

// Every parameter name of the registry's models, in first-seen order, with the specs declaring it.
std::vector<std::pair<std::string, std::vector<std::pair<std::string, ParameterSpec>>>>
model_parameter_names();

// "skylight: warning: MODEL (VALIDITY): message" for each issue of model.domain() (issues of the
// spectral output only when `spectral`).
void warn_domain(const SkyModel& model, bool spectral = false);
// One warning line on stderr.
void warn(std::string_view message);
// Warns of each given image option that `layout` does not read (a projection's, or every layout
// flag beside a calibration file: ImageOptions::unread).
void warn_unread_layout(const ImageOptions& layout, const ParameterValues& given);

// Metadata of an output made from `model`: version, model, the sun and every parameter the model
// read (ParameterSpec::metadata_key()), the solar disc mode and what the colours mean
// (skylight:colour, ModelInfo::colour_note()).
io::Metadata model_metadata(const SkyModel& model, std::string_view sun_mode);

// ---- output -------------------------------------------------------------------------------------

// Writes `text` to standard output and flushes; a failed write (closed stdout, full disk) throws
// IoError "cannot write to standard output: <reason>".
void write_stdout(std::string_view text);

// "wrote <path>" notices: queued, and printed by main() only once the command's outputs have
// committed (io::OutputTransaction), so that a command whose commit fails never claims a file.
// `to_stderr` for notices that go with the progress lines.
void announce_after_commit(std::string line, bool to_stderr = false);
// Prints the queued notices (main(), after the commit) and empties the queue.
void print_commit_notices();

// The whole of standard input; a read error (e.g. stdin is a directory) throws IoError "cannot read
// standard input: <reason>".
std::string read_stdin();

// Progress of a long command on stderr: a bar redrawn in place on a terminal; otherwise (logs, CI)
// one line per step once the command has run kQuietSeconds, so a short command prints none.
class Progress {
 public:
  static constexpr double kQuietSeconds = 1.0;
  explicit Progress(std::string command);
  void operator()(int done, int total, std::string_view step);
  double elapsed_s() const;

 private:
  std::string command_;
  bool tty_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace skylight::cli
