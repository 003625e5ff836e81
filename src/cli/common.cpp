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
      if (spec.file != FileRole::none)
        return spec.file == FileRole::output_directory ? "DIR" : "FILE";
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
    const std::string names = spec.name == "output" ? "-o,--output" : spec.flag();
    CLI::Option* opt = nullptr;
    if (spec.kind == ParameterKind::flag) {
      opt = app.add_flag_callback(
          names, [&raw] { raw = "true"; }, spec.help());
    } else if (spec.repeated) {
      opt = app.add_option_function<std::vector<std::string>>(
          names, [&raw](const std::vector<std::string>& v) { raw = join_repeated(v); },
          spec.help());
    } else if (spec.implicit) {
      // `--serve` alone: the implicit value (CLI11 passes "" for a missing optional value).
      const std::string implicit = spec.format(*spec.implicit);
      opt = app.add_option_function<std::string>(
          names, [&raw, implicit](const std::string& s) { raw = s.empty() ? implicit : s; },
          spec.help());
      opt->expected(0, 1);
    } else {
      opt = app.add_option_function<std::string>(
          names, [&raw](const std::string& s) { raw = s; }, spec.help());
      if (spec.kind != ParameterKind::text || !spec.choices.empty()) opt->check(schema_check(spec));
    }
    if (spec.kind != ParameterKind::flag) opt->type_name(value_label(spec));
  }
}

ParameterValues SchemaFlags::values() const {
  ParameterValues v;
  for (const ParameterSpec& spec : specs_)
    if (const auto& raw = raw_.at(spec.name)) v.set(spec.name, spec.parse(*raw));
  return v;
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

void warn(std::string_view message) {
  std::cerr << "skylight: warning: " << message << "\n";
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
  const double now = elapsed_s();
  const bool last = total > 0 && done == total;
  if (!last && now - last_shown_ < (tty_ ? kRedrawSeconds : kLineSeconds)) return;
  if (!tty_ && now < kQuietSeconds) return;
  last_shown_ = now;
  if (total <= 0) {
    // Steps without a known end: their count.
    if (tty_)
      std::cerr << fmt::format("\r\x1b[K[{}] {:5.1f} s  {}", done, now, step) << std::flush;
    else
      std::cerr << fmt::format("skylight {}: [{}] {:.1f} s {}\n", command_, done, now, step);
    return;
  }
  if (tty_) {
    constexpr int kBar = 30;
    const int filled = done * kBar / total;
    std::cerr << fmt::format("\r\x1b[K[{}{}] {:>2}/{} {:5.1f} s  {}", std::string(filled, '#'),
                             std::string(kBar - filled, ' '), done, total, now, step)
              << std::flush;
    if (last) std::cerr << "\n";
  } else {
    // A log (not a terminal): one line per shown step.
    std::cerr << fmt::format("skylight {}: [{}/{}] {:.1f} s {}\n", command_, done, total, now,
                             step);
  }
}

}  // namespace skylight::cli
