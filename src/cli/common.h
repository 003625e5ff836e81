// The command-line tool's adapter machinery: the subcommand table, exit statuses, flags built
// from the parameter schema (core/parameters.h), --help as a manual page, checked writes to
// standard output and progress lines. Every operation's command is generated from its
// declaration (operation_cmd.cpp); `models` and `operations` list the declarations
// (models_cmd.cpp).
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/parameters.h"

namespace skylight::cli {

// Exit status: 0 success, 1 runtime failure (I/O, ...), 2 usage error or invalid value.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

// One subcommand: its CLI11 app and what runs when it was given, with the arguments CLI11 did not
// know (the operations refuse unknown names themselves, as every front end's are refused).
struct Command {
  CLI::App* app = nullptr;
  std::function<int(const std::vector<std::string>& extras)> run;
  bool takes_extras = false;
};
using Commands = std::vector<Command>;

// `models` and `operations`: the declarations as text, JSON or Markdown.
void add_models_command(CLI::App& app, Commands& commands);
// One command per operation of the library (operations::registry()), the groups (sh, haze, nn)
// from operations::families().
void add_operation_commands(CLI::App& app, Commands& commands);

// When CLI11 refused the command line: the first word that is not a subcommand where one is
// expected, as a one-line message with the nearest name ("unknown subcommand 'trian' for 'nn';
// did you mean 'train'?"), or the first unknown flag of a command that is not an operation's.
// nullopt when every name is known (CLI11's own message then stands).
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
// What --help shows for a flag's value: INT, NUMBER, N,N (a list of two), TEXT, FILE or {a|b|c}.
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

// The flags of a list of specs (an operation's parameters): one per spec, the values kept as
// given until the command runs, then parsed by their specs. --help, the range errors and the
// defaults are the specs'.
class SchemaFlags {
 public:
  // Adds --NAME per spec (-o,--output for "output"): numbers range-checked and a text of choices
  // checked (schema_check), a flag as a switch, a repeated text as a repeatable option.
  void add(CLI::App& app, const std::vector<ParameterSpec>& specs);
  // The given values, parsed by their specs.
  ParameterValues values() const;

 private:
  std::vector<ParameterSpec> specs_;
  std::map<std::string, std::optional<std::string>, std::less<>> raw_;
};

// Every parameter name of the registry's models, in first-seen order, with the specs declaring it.
std::vector<std::pair<std::string, std::vector<std::pair<std::string, ParameterSpec>>>>
model_parameter_names();

// One warning line on stderr.
void warn(std::string_view message);

// ---- output -------------------------------------------------------------------------------------

// Writes `text` to standard output and flushes; a failed write (closed stdout, full disk) throws
// IoError "cannot write to standard output: <reason>".
void write_stdout(std::string_view text);

// The whole of standard input; a read error (e.g. stdin is a directory) throws IoError "cannot read
// standard input: <reason>".
std::string read_stdin();

// Progress of a long command on stderr: a bar redrawn in place on a terminal (at most every
// kRedrawSeconds); otherwise (logs, CI) a line per step once the command has run kQuietSeconds,
// so a short command prints none, and at most one a second (a training reports every iteration),
// the last step always. A total <= 0: steps without a known end (a count instead of a bar).
class Progress {
 public:
  static constexpr double kQuietSeconds = 1.0;
  static constexpr double kLineSeconds = 1.0;
  static constexpr double kRedrawSeconds = 0.1;
  explicit Progress(std::string command);
  void operator()(int done, int total, std::string_view step);
  double elapsed_s() const;

 private:
  std::string command_;
  bool tty_ = false;
  std::chrono::steady_clock::time_point start_;
  double last_shown_ = -1e9;  // elapsed_s() when a step was last shown
};

}  // namespace skylight::cli
