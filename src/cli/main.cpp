// skylight command-line tool: the listings (models_cmd.cpp) and one command per operation of the
// library, generated from its declaration (operation_cmd.cpp). main() wires them, parses, and
// maps errors to exit statuses:
// 0 success, 2 usage error or invalid value, 1 runtime failure (I/O etc.).
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "gpu_backend.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/version.h"

namespace cli = skylight::cli;

namespace {

// --threads: checked by its spec like every flag (strict decimal integer: no 0x10, no 1e3).
const skylight::ParameterSpec& threads_spec() {
  static const skylight::ParameterSpec spec{
      .name = "threads",
      .unit = "1",
      .kind = skylight::ParameterKind::integer,
      .min = 1,
      .max = skylight::kMaxThreads,
      .default_value = skylight::Absent{"SKYLIGHT_THREADS, else all cores"},
      .description = "worker threads"};
  return spec;
}

// Each subcommand's --help, a group's (nn, sh, haze) too, also lists the global option (CLI11
// shows only the page's own options).
void add_global_footers(CLI::App& app, const cli::HelpFormatter& formatter) {
  const std::string global = fmt::format("Global option (before or after the subcommand):\n{}",
                                         formatter.make_option(app.get_option("--threads"), false));
  const auto add_footer = [&global](CLI::App* sub, auto& self) -> void {
    sub->footer(global);
    for (CLI::App* s : sub->get_subcommands([](const CLI::App*) { return true; })) self(s, self);
  };
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    add_footer(sub, add_footer);
}

// --help and --version print to standard output like any command: a failed write (closed stdout,
// full disk) is an error, not a silent success.
int printed(int status) {
  std::cout.flush();
  if (std::cout) return status;
  std::cerr << "skylight: error: cannot write to standard output\n";
  return cli::kExitRuntime;
}

// Parses the command line: nullopt when a command is to run, else the exit status (help, version,
// a usage error).
std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return printed(app.exit(e));
  } catch (const skylight::InvalidArgument& e) {
    // A value out of its schema's range (schema_check): the library's message names the flag.
    std::cerr << "skylight: error: " << e.what() << "\n";
    return cli::kExitUsage;
  } catch (const CLI::ParseError& e) {
    // A mistyped flag or subcommand is named with the nearest known one; CLI11 would report
    // whatever it checks first (a missing --model before an unknown flag).
    if (const auto unknown = cli::unknown_name_error(app, argc, argv)) {
      std::cerr << "skylight: error: " << *unknown << "\n";
      return cli::kExitUsage;
    }
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    std::cerr << "skylight: error: " << msg << " (see --help)\n";
    return cli::kExitUsage;
  }
  return std::nullopt;
}

// Runs the command given (its outputs are one transaction: operations::execute), with the thread
// count of --threads or SKYLIGHT_THREADS; extras (flags no command knows) go to an operation, whose
// own check refuses them naming the nearest parameter.
int run(const CLI::App& app, const cli::Commands& commands, const std::string& threads, int argc,
        char** argv) {
  const auto unexpected = [&](const std::vector<std::string>& extras) {
    const auto unknown = cli::unknown_name_error(app, argc, argv);
    return skylight::InvalidArgument(
        unknown ? *unknown
                : fmt::format("unexpected argument '{}'", skylight::excerpt(extras.front())));
  };
  try {
    if (const char* env = std::getenv("SKYLIGHT_THREADS");
        env && !skylight::parse_thread_count(env))
      throw skylight::InvalidArgument(
          fmt::format("SKYLIGHT_THREADS = '{}' is not an integer in [1, {}]",
                      skylight::excerpt(env), skylight::kMaxThreads));
    if (!threads.empty())
      skylight::set_thread_count(static_cast<int>(std::get<double>(threads_spec().parse(threads))));
    const std::vector<std::string> extras = app.remaining(true);
    for (const auto& c : commands) {
      if (!c.app->parsed()) continue;
      if (!extras.empty() && !c.takes_extras) throw unexpected(extras);
      return c.run(extras);
    }
    if (!extras.empty()) throw unexpected(extras);
  } catch (const std::bad_alloc&) {
    std::cerr << "skylight: error: out of memory\n";
    return cli::kExitRuntime;
  } catch (const skylight::InvalidArgument& e) {
    std::cerr << "skylight: error: " << e.what() << "\n";
    return cli::kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "skylight: error: " << e.what() << "\n";
    return cli::kExitRuntime;
  }
  return cli::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  // The library's messages name parameters; here they read as the flags the user typed.
  skylight::set_parameter_spelling(cli::flag_spelling);
  CLI::App app{"skylight: daylight sky models, renders and checks"};
  // Before the subcommands: they take their parent's formatter.
  const auto formatter = std::make_shared<cli::HelpFormatter>();
  app.formatter(formatter);
  app.set_version_flag("--version", std::string("skylight ") + skylight::kVersion);
  app.require_subcommand(1);
  std::string threads;
  app.add_option("--threads", threads, threads_spec().help())
      ->type_name(cli::value_label(threads_spec()))
      ->check(cli::schema_check(threads_spec()));
  // Global options (--threads) are accepted after the subcommand too.
  app.fallthrough();
  // The GL paths of the operations, when this build has the GPU module.
  skylight::frontend::install_gpu_backend();
  cli::Commands commands;
  cli::add_models_command(app, commands);
  cli::add_operation_commands(app, commands);
  add_global_footers(app, *formatter);
  // Flags no command knows are collected (they fall through to here) and handed to the operation
  // of the command line.
  app.allow_extras();
  if (const auto status = parse(app, argc, argv)) return *status;
  return run(app, commands, threads, argc, argv);
}
