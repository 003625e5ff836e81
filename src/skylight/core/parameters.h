// The parameter schema: every parameter of a model (and of commands that take numbers) is
// declared once, as a ParameterSpec: name, unit, kind, inclusive range, a typed default (or
// "required", or "absent" with what the model does then) and a description. Constructor
// validation, command-line flags, `skylight models --json`, file metadata and the parameter
// tables of docs/MODELS.md all derive from it (docs/ARCHITECTURE.md, "Parameters").
//
// ParameterSchema<P> binds the specs to the fields of a typed parameter struct P (one per model,
// e.g. PreethamParameters): named values from the command line or from code are bound into a P
// (defaults applied, required ones and ranges checked), a P built in code is validated with the
// same checks, and a P is turned back into named values for metadata.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace skylight {

enum class ParameterKind {
  number,   // a finite double
  integer,  // a whole number (stored as double in a ParameterValue)
  numbers,  // a list of finite doubles (`count` values, 0: any number >= 1; comma-separated text)
  text,     // a string (e.g. a file path), or one of `choices` when the spec lists them
  flag,     // a boolean switch (present = true)
};

// "number", "integer", "numbers", "text", "flag".
std::string_view to_string(ParameterKind kind);

// A value: number/integer -> double, numbers -> vector<double>, text -> string, flag -> bool.
using ParameterValue = std::variant<double, std::vector<double>, std::string, bool>;

struct Required {};
// No default value: the model then does something else, said in `meaning` (e.g. "the
// Kittler-Darula typical value", "no ground reflection").
struct Absent {
  std::string meaning;
};
using ParameterDefault = std::variant<Required, Absent, ParameterValue>;

// A parameter that names a file: one the operation reads, writes, or a directory it writes into
// (operations/operation.h checks them before any work: inputs exist, outputs collide with
// nothing).
enum class FileRole { none, input, output, output_directory };

struct ParameterSpec {
  std::string name{};  // flag name without dashes, e.g. "turbidity", "sun-zenith"
  std::string unit{};  // "1" (dimensionless), "deg", "m", "cd/m^2", "W m^-2 nm^-1", "DU", "" (text)
  ParameterKind kind = ParameterKind::number;
  double min = 0.0, max = 0.0;  // inclusive range of each number
  std::size_t count = 1;        // values of a `numbers` parameter
  ParameterDefault default_value = Required{};
  std::string description{};
  // A text parameter that takes one of these names (an enumeration); empty: any text.
  std::vector<std::string> choices{};
  // A text parameter that may be given more than once: its values joined by '\n'
  // (join_repeated, split_repeated).
  bool repeated = false;
  // A file's role, the endings it may have (".exr", ...; empty: any) and whether "-" names the
  // standard input or output.
  FileRole file = FileRole::none;
  std::vector<std::string> formats{};
  bool standard_stream = false;
  // A number whose flag may be given without a value: the value it then takes (`view --serve`
  // alone: port 8000). Absent: a value is required.
  std::optional<ParameterValue> implicit{};

  // The command line's flag, "--" + name (the CLI's flags and the docs' tables of them).
  std::string flag() const { return "--" + name; }
  bool required() const { return std::holds_alternative<Required>(default_value); }
  // "skylight:" + name with '-' -> '_' + a unit suffix ("_deg", "_m", "_cd_m2", "_W_m2_nm",
  // "_DU"; none for "1" and ""): e.g. skylight:zenith_luminance_cd_m2.
  std::string metadata_key() const;
  // "1 .. 64" for numbers (an integer's bounds whole: "0 .. 2147483647"); "a|b|c" for a text of
  // choices; a file's endings ".exr/.png" ("/-" with the standard stream); "" for other text and
  // flags.
  std::string range_text() const;
  // The default as the user sees it: "3", "-1,-0.32,10,-3,0.45", "required", "none (<meaning>)".
  std::string default_text() const;
  // One line for --help: "<description> [<unit>], <range>; default <default>" (no unit shown for
  // a dimensionless "1"; an integer's bounds and default written whole).
  std::string help() const;

  // Parses the text form (command line, metadata) with the strict number parser. Throws
  // InvalidArgument "--<name>: ..." for malformed text.
  ParameterValue parse(std::string_view text) const;
  // The text form: numbers in shortest round-trip form, lists comma-separated.
  std::string format(const ParameterValue& value) const;
  // Throws InvalidArgument naming the parameter, the value and the range (and `context`, e.g.
  // "model 'hosek'", when not empty) if the value has the wrong kind or is outside the range.
  void check(const ParameterValue& value, std::string_view context = {}) const;
};

// How the library's messages name a parameter or an operation's option: by its name as the schema
// declares it ("top-radius"), unless a front end has installed its own spelling once, before any
// call (the CLI: the flag "--top-radius"; the Python package: the argument "top_radius"), so that
// each message names what the user wrote. set_parameter_spelling(nullptr) restores the names.
using ParameterSpelling = std::string (*)(std::string_view name);
void set_parameter_spelling(ParameterSpelling spelling);
std::string spelled(std::string_view name);

// The specs as a Markdown table (flag, unit, range, default, description), as docs/MODELS.md shows
// them (a test keeps the two equal; `skylight models --markdown` prints them).
std::string markdown_table(const std::vector<ParameterSpec>& specs);

// The values of a repeated text parameter as one text and back (joined by '\n').
std::string join_repeated(const std::vector<std::string>& values);
std::vector<std::string> split_repeated(const std::string& text);

// Named values as a user gives them (command line, JSON, code).
class ParameterValues {
 public:
  ParameterValues& set(std::string_view name, ParameterValue value);
  // Typed overloads, so that set("n", 3) stores a number and set("fast", true) a flag.
  ParameterValues& set(std::string_view name, double value) {
    return set(name, ParameterValue(value));
  }
  ParameterValues& set(std::string_view name, int value) {
    return set(name, ParameterValue(static_cast<double>(value)));
  }
  ParameterValues& set(std::string_view name, bool value) {
    return set(name, ParameterValue(value));
  }
  ParameterValues& set(std::string_view name, const char* value) {
    return set(name, ParameterValue(std::string(value)));
  }
  const ParameterValue* find(std::string_view name) const;
  // A number's value, nullopt if absent (or not a number).
  std::optional<double> number(std::string_view name) const;
  bool has(std::string_view name) const { return find(name) != nullptr; }
  // The values whose names the specs declare (one schema's share of an operation's values).
  ParameterValues only(const std::vector<ParameterSpec>& specs) const;
  void erase(std::string_view name);
  bool empty() const { return values_.empty(); }
  const std::map<std::string, ParameterValue, std::less<>>& all() const { return values_; }

 private:
  std::map<std::string, ParameterValue, std::less<>> values_;
};

// Binds specs to the fields of a parameter struct P. Field setters/getters convert between the
// user's value (the spec's unit) and the field (the library's unit, e.g. deg -> rad).
template <class P>
class ParameterSchema {
 public:
  struct Entry {
    ParameterSpec spec;
    std::function<void(P&, const ParameterValue&)> set;
    std::function<std::optional<ParameterValue>(const P&)> get;  // nullopt: absent
  };

  // A field of type double; `scale` converts the user's unit into the field's (field = value x
  // scale, e.g. kDegree).
  ParameterSchema& number(double P::*field, ParameterSpec spec, double scale = 1.0) {
    spec.kind = ParameterKind::number;
    return add(
        std::move(spec),
        [field, scale](P& p, const ParameterValue& v) { p.*field = std::get<double>(v) * scale; },
        [field, scale](const P& p) -> std::optional<ParameterValue> { return p.*field / scale; });
  }
  ParameterSchema& optional_number(std::optional<double> P::*field, ParameterSpec spec) {
    spec.kind = ParameterKind::number;
    return add(
        std::move(spec), [field](P& p, const ParameterValue& v) { p.*field = std::get<double>(v); },
        [field](const P& p) -> std::optional<ParameterValue> {
          if (!(p.*field)) return std::nullopt;
          return *(p.*field);
        });
  }
  // A field of any integer type (int, std::uint64_t, ...).
  template <class T>
  ParameterSchema& integer(T P::*field, ParameterSpec spec) {
    static_assert(std::is_integral_v<T>, "an integer field");
    spec.kind = ParameterKind::integer;
    return add(
        std::move(spec),
        [field](P& p, const ParameterValue& v) { p.*field = static_cast<T>(std::get<double>(v)); },
        [field](const P& p) -> std::optional<ParameterValue> {
          return static_cast<double>(p.*field);
        });
  }
  ParameterSchema& optional_integer(std::optional<int> P::*field, ParameterSpec spec) {
    spec.kind = ParameterKind::integer;
    return add(
        std::move(spec),
        [field](P& p, const ParameterValue& v) {
          p.*field = static_cast<int>(std::get<double>(v));
        },
        [field](const P& p) -> std::optional<ParameterValue> {
          if (!(p.*field)) return std::nullopt;
          return static_cast<double>(*(p.*field));
        });
  }
  // A list (spec.count values, 0: any number); an empty list is absent.
  ParameterSchema& numbers(std::vector<double> P::*field, ParameterSpec spec) {
    spec.kind = ParameterKind::numbers;
    return add(
        std::move(spec),
        [field](P& p, const ParameterValue& v) { p.*field = std::get<std::vector<double>>(v); },
        [field](const P& p) -> std::optional<ParameterValue> {
          if ((p.*field).empty()) return std::nullopt;
          return p.*field;
        });
  }
  // An enumeration by name: `names` pairs each choice with its value (spec.choices from them).
  template <class E>
  ParameterSchema& choice(E P::*field, ParameterSpec spec,
                          std::vector<std::pair<std::string, E>> names) {
    spec.kind = ParameterKind::text;
    spec.choices.clear();
    for (const auto& [n, e] : names) spec.choices.push_back(n);
    return add(
        std::move(spec),
        [field, names](P& p, const ParameterValue& v) {
          for (const auto& [n, e] : names)
            if (n == std::get<std::string>(v)) p.*field = e;
        },
        [field, names](const P& p) -> std::optional<ParameterValue> {
          for (const auto& [n, e] : names)
            if (e == p.*field) return n;
          return std::nullopt;
        });
  }
  template <std::size_t N>
  ParameterSchema& optional_numbers(std::optional<std::array<double, N>> P::*field,
                                    ParameterSpec spec) {
    spec.kind = ParameterKind::numbers;
    spec.count = N;
    return add(
        std::move(spec),
        [field](P& p, const ParameterValue& v) {
          const auto& list = std::get<std::vector<double>>(v);
          std::array<double, N> a{};
          for (std::size_t i = 0; i < N; ++i) a[i] = list[i];
          p.*field = a;
        },
        [field](const P& p) -> std::optional<ParameterValue> {
          if (!(p.*field)) return std::nullopt;
          return std::vector<double>((p.*field)->begin(), (p.*field)->end());
        });
  }
  ParameterSchema& text(std::string P::*field, ParameterSpec spec) {
    spec.kind = ParameterKind::text;
    return add(
        std::move(spec),
        [field](P& p, const ParameterValue& v) { p.*field = std::get<std::string>(v); },
        [field](const P& p) -> std::optional<ParameterValue> {
          if ((p.*field).empty()) return std::nullopt;
          return p.*field;
        });
  }
  ParameterSchema& flag(bool P::*field, ParameterSpec spec) {
    spec.kind = ParameterKind::flag;
    spec.default_value = ParameterValue(false);
    return add(
        std::move(spec), [field](P& p, const ParameterValue& v) { p.*field = std::get<bool>(v); },
        [field](const P& p) -> std::optional<ParameterValue> { return p.*field; });
  }
  // Every entry of `inner`, bound to the member `field` (a nested options struct).
  template <class Q>
  ParameterSchema& nested(Q P::*field, const ParameterSchema<Q>& inner) {
    for (const auto& e : inner.entries()) {
      add(
          e.spec, [field, set = e.set](P& p, const ParameterValue& v) { set(p.*field, v); },
          [field, get = e.get](const P& p) { return get(p.*field); });
    }
    return *this;
  }
  // Every entry of the schema of P's base class B (P derives from B): a model whose parameters
  // extend another's.
  template <class B>
  ParameterSchema& inherit(const ParameterSchema<B>& base) {
    static_assert(std::is_base_of_v<B, P>);
    for (const auto& e : base.entries())
      add(
          e.spec, [set = e.set](P& p, const ParameterValue& v) { set(static_cast<B&>(p), v); },
          [get = e.get](const P& p) { return get(static_cast<const B&>(p)); });
    return *this;
  }
  // Replaces the default (and, if given, the description) of the entry `name` (e.g. of an
  // inherited entry whose default differs here). The entry must exist.
  ParameterSchema& redefault(std::string_view name, ParameterDefault value,
                             std::string description = {}) {
    for (auto& e : entries_)
      if (e.spec.name == name) {
        e.spec.default_value = std::move(value);
        if (!description.empty()) e.spec.description = std::move(description);
        return *this;
      }
    throw std::logic_error("redefault: no parameter " + std::string(name));
  }
  // Any other mapping (e.g. one value into two fields).
  ParameterSchema& custom(ParameterSpec spec, std::function<void(P&, const ParameterValue&)> set,
                          std::function<std::optional<ParameterValue>(const P&)> get) {
    return add(std::move(spec), std::move(set), std::move(get));
  }

  const std::vector<Entry>& entries() const { return entries_; }
  std::vector<ParameterSpec> specs() const {
    std::vector<ParameterSpec> out;
    for (const auto& e : entries_) out.push_back(e.spec);
    return out;
  }
  const ParameterSpec* find(std::string_view name) const {
    for (const auto& e : entries_)
      if (e.spec.name == name) return &e.spec;
    return nullptr;
  }

  // Applies `values` over `p` (which holds the defaults): each given value is checked and set, a
  // required parameter that is missing throws, and so does a name that is not in the schema.
  // `context` names the model in messages.
  void bind(const ParameterValues& values, P& p, std::string_view context) const;
  // Checks every field of `p` against its spec (the same checks as bind; a required field that is
  // absent, e.g. an empty optional, throws).
  void validate(const P& p, std::string_view context) const;
  // The present fields of `p` as named values (for metadata and listings).
  ParameterValues values_of(const P& p) const;

 private:
  ParameterSchema& add(ParameterSpec spec, std::function<void(P&, const ParameterValue&)> set,
                       std::function<std::optional<ParameterValue>(const P&)> get) {
    entries_.push_back({std::move(spec), std::move(set), std::move(get)});
    return *this;
  }
  std::vector<Entry> entries_;
};

namespace detail {
[[noreturn]] void throw_missing_parameter(const ParameterSpec& spec, std::string_view context);
[[noreturn]] void throw_unknown_parameter(std::string_view name, std::string_view context,
                                          const std::vector<std::string>& known);
}  // namespace detail

template <class P>
void ParameterSchema<P>::bind(const ParameterValues& values, P& p, std::string_view context) const {
  for (const auto& [name, value] : values.all()) {
    if (!find(name)) {
      std::vector<std::string> known;
      for (const auto& e : entries_) known.push_back(e.spec.name);
      detail::throw_unknown_parameter(name, context, known);
    }
  }
  for (const auto& e : entries_) {
    if (const ParameterValue* v = values.find(e.spec.name)) {
      e.spec.check(*v, context);
      e.set(p, *v);
    } else if (e.spec.required()) {
      detail::throw_missing_parameter(e.spec, context);
    }
  }
}

template <class P>
void ParameterSchema<P>::validate(const P& p, std::string_view context) const {
  for (const auto& e : entries_) {
    if (const auto v = e.get(p))
      e.spec.check(*v, context);
    else if (e.spec.required())
      detail::throw_missing_parameter(e.spec, context);
  }
}

template <class P>
ParameterValues ParameterSchema<P>::values_of(const P& p) const {
  ParameterValues out;
  for (const auto& e : entries_)
    if (const auto v = e.get(p)) out.set(e.spec.name, *v);
  return out;
}

}  // namespace skylight
