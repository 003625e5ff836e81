#include "skylight/core/parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/text.h"

namespace skylight {
namespace {

std::string format_number(double v) {
  return fmt::format("{}", v);
}

// Compact form for people (ranges, defaults in help and docs): 6 significant digits.
std::string display_number(double v) {
  return fmt::format("{:.6g}", v);
}

std::string join(const std::vector<double>& list) {
  std::string out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i > 0) out += ',';
    out += format_number(list[i]);
  }
  return out;
}

std::string where(std::string_view context) {
  return context.empty() ? std::string() : fmt::format(" ({})", context);
}

}  // namespace

std::string_view to_string(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::number:
      return "number";
    case ParameterKind::integer:
      return "integer";
    case ParameterKind::numbers:
      return "numbers";
    case ParameterKind::text:
      return "text";
    case ParameterKind::flag:
      return "flag";
  }
  return "number";
}

namespace {
std::atomic<ParameterSpelling> g_spelling{nullptr};
}  // namespace

void set_parameter_spelling(ParameterSpelling spelling) {
  g_spelling.store(spelling);
}

std::string spelled(std::string_view name) {
  const ParameterSpelling f = g_spelling.load();
  return f ? f(name) : std::string(name);
}

std::string ParameterSpec::metadata_key() const {
  std::string key = "skylight:" + name;
  std::replace(key.begin(), key.end(), '-', '_');
  if (unit == "deg") return key + "_deg";
  if (unit == "m") return key + "_m";
  if (unit == "cd/m^2") return key + "_cd_m2";
  if (unit == "W m^-2 nm^-1") return key + "_W_m2_nm";
  if (unit == "DU") return key + "_DU";
  if (unit == "nm") return key + "_nm";
  if (unit == "px") return key + "_px";
  if (unit == "W/m^2") return key + "_W_m2";
  if (unit == "lx") return key + "_lx";
  if (unit == "degC") return key + "_degC";
  if (unit == "cm") return key + "_cm";
  return key;  // "1" (dimensionless) and text
}

std::string ParameterSpec::range_text() const {
  if (kind == ParameterKind::text) {
    std::string out;
    for (const auto& c : choices) out += (out.empty() ? "" : "|") + c;
    // A file's accepted endings ("-": the standard stream).
    for (const auto& f : formats) out += (out.empty() ? "" : "/") + f;
    if (standard_stream) out += out.empty() ? "-" : "/-";
    return out;
  }
  if (kind == ParameterKind::flag) return {};
  // An integer's bounds are written out whole (0 .. 2147483647, not 2.14748e+09).
  if (kind == ParameterKind::integer) return fmt::format("{:.0f} .. {:.0f}", min, max);
  return fmt::format("{} .. {}", display_number(min), display_number(max));
}

std::string ParameterSpec::default_text() const {
  if (std::holds_alternative<Required>(default_value)) return "required";
  if (const auto* a = std::get_if<Absent>(&default_value)) return "none (" + a->meaning + ")";
  const ParameterValue& v = std::get<ParameterValue>(default_value);
  if (const auto* d = std::get_if<double>(&v))
    return kind == ParameterKind::integer ? fmt::format("{:.0f}", *d) : display_number(*d);
  return format(v);
}

std::string ParameterSpec::help() const {
  std::string h = description;
  // A dimensionless value ("1") shows no unit.
  if (!unit.empty() && unit != "1") h += fmt::format(" [{}]", unit);
  if (kind == ParameterKind::numbers && count > 0) h += fmt::format(", {} values", count);
  // (A text's choices are the front end's to show: CLI11 lists them beside the flag.)
  if (const std::string r = range_text(); !r.empty() && kind != ParameterKind::text)
    h += fmt::format(", {}{}", kind == ParameterKind::numbers ? "each " : "", r);
  if (!formats.empty()) h += fmt::format(", {}", range_text());
  if (kind != ParameterKind::flag) h += "; default " + default_text();
  return h;
}

ParameterValue ParameterSpec::parse(std::string_view text) const {
  switch (kind) {
    case ParameterKind::number:
      return parse_number(text, spelled(name));
    case ParameterKind::integer:
      return static_cast<double>(parse_integer(text, spelled(name)));
    case ParameterKind::numbers:
      return parse_number_list(text, spelled(name));
    case ParameterKind::text:
      return std::string(text);
    case ParameterKind::flag:
      if (text == "true" || text == "1") return true;
      if (text == "false" || text == "0") return false;
      throw InvalidArgument(
          fmt::format("{}: '{}' is not true or false", spelled(name), excerpt(text)));
  }
  return {};
}

std::string ParameterSpec::format(const ParameterValue& value) const {
  if (const auto* d = std::get_if<double>(&value)) return format_number(*d);
  if (const auto* l = std::get_if<std::vector<double>>(&value)) return join(*l);
  if (const auto* s = std::get_if<std::string>(&value)) return *s;
  return std::get<bool>(value) ? "true" : "false";
}

void ParameterSpec::check(const ParameterValue& value, std::string_view context) const {
  auto wrong_kind = [&] {
    throw InvalidArgument(
        fmt::format("{}{} must be of kind '{}'", spelled(name), where(context), to_string(kind)));
  };
  auto in_range = [&](double v, std::string_view shown) {
    if (!std::isfinite(v) || v < min || v > max)
      throw InvalidArgument(fmt::format("{} = {} is outside [{}, {}]{}", spelled(name), shown,
                                        format_number(min), format_number(max), where(context)));
  };
  switch (kind) {
    case ParameterKind::number:
    case ParameterKind::integer: {
      const auto* d = std::get_if<double>(&value);
      if (!d) wrong_kind();
      in_range(*d, format_number(*d));
      if (kind == ParameterKind::integer && std::trunc(*d) != *d)
        throw InvalidArgument(fmt::format("{} = {} is not an integer{}", spelled(name),
                                          format_number(*d), where(context)));
      return;
    }
    case ParameterKind::numbers: {
      const auto* l = std::get_if<std::vector<double>>(&value);
      if (!l) wrong_kind();
      if (count > 0 && l->size() != count)
        throw InvalidArgument(fmt::format("{} needs {} values, got {}{}", spelled(name), count,
                                          l->size(), where(context)));
      if (l->empty())
        throw InvalidArgument(
            fmt::format("{} needs at least one value{}", spelled(name), where(context)));
      for (std::size_t i = 0; i < l->size(); ++i)
        in_range((*l)[i], fmt::format("{} (value {})", format_number((*l)[i]), i + 1));
      return;
    }
    case ParameterKind::text: {
      const auto* s = std::get_if<std::string>(&value);
      if (!s) wrong_kind();
      if (!choices.empty() && std::find(choices.begin(), choices.end(), *s) == choices.end())
        throw InvalidArgument(fmt::format("{} = '{}' is not one of {}{}{}", spelled(name),
                                          excerpt(*s), range_text(), did_you_mean(*s, choices),
                                          where(context)));
      return;
    }
    case ParameterKind::flag:
      if (!std::holds_alternative<bool>(value)) wrong_kind();
      return;
  }
}

std::string markdown_table(const std::vector<ParameterSpec>& specs) {
  std::string t = "| flag | unit | range | default | description |\n|---|---|---|---|---|\n";
  for (const auto& s : specs) {
    std::string range = s.range_text();
    if (s.kind == ParameterKind::numbers)
      range = s.count > 0 ? fmt::format("{} values, each {}", s.count, range)
                          : fmt::format("values, each {}", range);
    if (s.kind == ParameterKind::integer) range += " (integer)";
    std::string description = s.description;
    std::replace(description.begin(), description.end(), '|', '/');
    std::replace(range.begin(), range.end(), '|', '/');
    t += fmt::format("| `{}` | {} | {} | {} | {} |\n", s.flag(), s.unit, range, s.default_text(),
                     description);
  }
  return t;
}

ParameterValues& ParameterValues::set(std::string_view name, ParameterValue value) {
  values_.insert_or_assign(std::string(name), std::move(value));
  return *this;
}

const ParameterValue* ParameterValues::find(std::string_view name) const {
  const auto it = values_.find(name);
  return it == values_.end() ? nullptr : &it->second;
}

std::optional<double> ParameterValues::number(std::string_view name) const {
  const ParameterValue* v = find(name);
  if (const auto* d = v ? std::get_if<double>(v) : nullptr) return *d;
  return std::nullopt;
}

std::string join_repeated(const std::vector<std::string>& values) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : "\n") + v;
  return out;
}

std::vector<std::string> split_repeated(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find('\n', start);
    out.push_back(text.substr(start, end - start));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

ParameterValues ParameterValues::only(const std::vector<ParameterSpec>& specs) const {
  ParameterValues out;
  for (const auto& s : specs)
    if (const ParameterValue* v = find(s.name)) out.set(s.name, *v);
  return out;
}

void ParameterValues::erase(std::string_view name) {
  const auto it = values_.find(name);
  if (it != values_.end()) values_.erase(it);
}

namespace detail {

void throw_missing_parameter(const ParameterSpec& spec, std::string_view context) {
  throw InvalidArgument(
      fmt::format("{} is required{}: {}", spelled(spec.name), where(context), spec.description));
}

void throw_unknown_parameter(std::string_view name, std::string_view context,
                             const std::vector<std::string>& known) {
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + spelled(k);
  throw InvalidArgument(fmt::format("{} is not a parameter{} (parameters: {})", spelled(name),
                                    where(context), list.empty() ? "none" : list));
}

}  // namespace detail
}  // namespace skylight
