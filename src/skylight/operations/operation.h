// An operation of the library, executable (docs/ARCHITECTURE.md, "Operations"): its name as the
// command line spells it, what it does, its parameters (the files it reads and writes among them),
// the relations between them, the fields of its result, a check of a request that does no work,
// and the work itself. Front ends (the CLI, the Python package) are adapters: they turn what the
// user typed into named values, call prepare() (every usage error, before any work) and
// execute(), and present the result's record as text, JSON or a Python dict, all generated from
// the declared fields; so two front ends give the same verdict and message for the same request.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"
#include "skylight/core/progress.h"
#include "skylight/io/image.h"

namespace skylight::operations {

// ---- relations ----------------------------------------------------------------------------------

// How two parameters of an operation relate, checked when values are bound (prepare):
// excludes: not both ("a and b exclude each other"); requires: `a` only with `b` ("a needs b").
// With `unread` the broken relation is a warning, not an error: `a` is not read ("a is not read
// with b; ignored", "a is not read without b; ignored") and its value is dropped. `why`, when
// given, is said in the message.
enum class RelationKind { excludes, requires_ };  // "excludes", "requires" (a C++ keyword)
std::string_view to_string(RelationKind kind);

struct Relation {
  RelationKind kind = RelationKind::excludes;
  std::string a{}, b{};
  bool unread = false;
  std::string why{};
};
inline Relation excludes(std::string a, std::string b, std::string why = {}) {
  return {RelationKind::excludes, std::move(a), std::move(b), false, std::move(why)};
}
inline Relation needs(std::string a, std::string b, std::string why = {}) {
  return {RelationKind::requires_, std::move(a), std::move(b), false, std::move(why)};
}
inline Relation unread_with(std::string a, std::string b, std::string why = {}) {
  return {RelationKind::excludes, std::move(a), std::move(b), true, std::move(why)};
}
inline Relation unread_without(std::string a, std::string b, std::string why = {}) {
  return {RelationKind::requires_, std::move(a), std::move(b), true, std::move(why)};
}

// ---- results ------------------------------------------------------------------------------------

// The kind of a result's field: a number, an integer, a text, a flag (true/false), a list of
// numbers or of texts, one record or a list of records (a table) of sub-fields.
enum class FieldKind { number, integer, text, flag, numbers, texts, record, records };
std::string_view to_string(FieldKind kind);

// A field of an operation's result, declared once: the record (JSON, the CLI's text, Python's
// dict) is generated from it.
struct FieldSpec {
  std::string name{};  // the key, e.g. "sun_zenith_deg"
  std::string unit{};  // "deg", "1" (dimensionless), "" (text, flag, records)
  FieldKind kind = FieldKind::number;
  std::string meaning{};            // one line
  bool nullable = false;            // null where it does not apply (said in `meaning`)
  int decimals = -1;                // the text form's digits after the point; -1: shortest
  std::vector<FieldSpec> fields{};  // a record's or records' sub-fields
  // A list of texts whose text form is its lines, verbatim and without a label (text the work
  // lays out itself, e.g. bench's table); other lists are one labelled, comma-separated line.
  bool verbatim = false;
};

// A result's values: an ordered JSON object whose keys are the declared fields'.
using Record = nlohmann::ordered_json;

// Binds the declared fields to a typed result R: each field's value from R (a member or a
// function of R), so that the operation's work returns R and the record is made here, from the
// declaration alone (as ParameterSchema binds parameters to a settings struct).
template <class R>
class ResultSchema {
 public:
  using Get = std::function<Record(const R&)>;

  // A field of any kind from a function of R (its JSON value; null when it does not apply).
  ResultSchema& field(FieldSpec spec, Get get) {
    entries_.push_back({std::move(spec), std::move(get)});
    return *this;
  }
  // A number: a member or a function of R; a nullopt function value is null (nullable).
  template <class G>
  ResultSchema& number(std::string name, std::string unit, std::string meaning, G get,
                       int decimals = -1) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name),
                  std::move(unit),
                  FieldKind::number,
                  std::move(meaning),
                  nullable,
                  decimals,
                  {}},
                 getter(std::move(get)));
  }
  template <class G>
  ResultSchema& integer(std::string name, std::string unit, std::string meaning, G get) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name),
                  std::move(unit),
                  FieldKind::integer,
                  std::move(meaning),
                  nullable,
                  -1,
                  {}},
                 getter(std::move(get)));
  }
  template <class G>
  ResultSchema& text(std::string name, std::string meaning, G get) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name), "", FieldKind::text, std::move(meaning), nullable, -1, {}},
                 getter(std::move(get)));
  }
  template <class G>
  ResultSchema& flag(std::string name, std::string meaning, G get) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name), "", FieldKind::flag, std::move(meaning), nullable, -1, {}},
                 getter(std::move(get)));
  }
  template <class G>
  ResultSchema& numbers(std::string name, std::string unit, std::string meaning, G get,
                        int decimals = -1) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name),
                  std::move(unit),
                  FieldKind::numbers,
                  std::move(meaning),
                  nullable,
                  decimals,
                  {}},
                 getter(std::move(get)));
  }
  template <class G>
  ResultSchema& texts(std::string name, std::string meaning, G get) {
    const bool nullable = returns_optional<G>();
    return field({std::move(name), "", FieldKind::texts, std::move(meaning), nullable, -1, {}},
                 getter(std::move(get)));
  }
  // Lines of text the work lays out itself (FieldSpec::verbatim).
  template <class G>
  ResultSchema& lines(std::string name, std::string meaning, G get) {
    FieldSpec spec{std::move(name), "", FieldKind::texts, std::move(meaning), false, -1, {}};
    spec.verbatim = true;
    return field(std::move(spec), getter(std::move(get)));
  }
  // A list of records of `inner`'s fields: get(r) returns a container of S.
  template <class S, class G>
  ResultSchema& records(std::string name, std::string meaning, const ResultSchema<S>& inner,
                        G get) {
    return field(
        {std::move(name), "", FieldKind::records, std::move(meaning), false, -1, inner.fields()},
        [inner, get = std::move(get)](const R& r) {
          Record list = Record::array();
          for (const S& s : call(get, r)) list.push_back(inner.record(s));
          return list;
        });
  }
  // One record of `inner`'s fields: get(r) returns an optional<S> or a pointer to S (null: the
  // field is null).
  template <class S, class G>
  ResultSchema& nested(std::string name, std::string meaning, const ResultSchema<S>& inner, G get) {
    return field(
        {std::move(name), "", FieldKind::record, std::move(meaning), true, -1, inner.fields()},
        [inner, get = std::move(get)](const R& r) {
          const auto& v = call(get, r);
          return v ? inner.record(*v) : Record(nullptr);
        });
  }

  std::vector<FieldSpec> fields() const {
    std::vector<FieldSpec> out;
    for (const auto& e : entries_) out.push_back(e.spec);
    return out;
  }
  // The record of r: every declared field, in order.
  Record record(const R& r) const {
    Record out = Record::object();
    for (const auto& e : entries_) out[e.spec.name] = e.get(r);
    return out;
  }

 private:
  struct Entry {
    FieldSpec spec;
    Get get;
  };
  template <class G>
  static decltype(auto) call(const G& get, const R& r) {
    if constexpr (std::is_member_object_pointer_v<G>)
      return (r.*get);
    else
      return get(r);
  }
  template <class G>
  static constexpr bool returns_optional() {
    using V = std::decay_t<decltype(call(std::declval<const G&>(), std::declval<const R&>()))>;
    return is_optional<V>::value;
  }
  template <class T>
  struct is_optional : std::false_type {};
  template <class T>
  struct is_optional<std::optional<T>> : std::true_type {};
  template <class G>
  static Get getter(G get) {
    return [get = std::move(get)](const R& r) -> Record {
      const auto& v = call(get, r);
      using V = std::decay_t<decltype(v)>;
      if constexpr (is_optional<V>::value)
        return v ? Record(*v) : Record(nullptr);
      else
        return Record(v);
    };
  }
  std::vector<Entry> entries_;
};

// ---- requests -----------------------------------------------------------------------------------

struct OperationInfo;

// What a front end gives an operation besides the values: where warnings and progress go, the
// standard input, inputs in memory instead of files (the Python package's arrays) and whether
// outputs without a path are kept in memory (and returned in the Result) instead of refused.
struct Frontend {
  std::function<void(const std::string&)> warn{};  // one line, as it arises
  ProgressSink progress{};
  std::function<std::string()> standard_input{};            // a text input given as "-"
  std::map<std::string, io::ImageF, std::less<>> images{};  // image inputs by parameter name
  std::map<std::string, std::string, std::less<>> texts{};  // text inputs by parameter name
  bool keep_outputs = false;
  // Whether the user asked to stop (the Python package: a pending KeyboardInterrupt); asked by
  // work that runs until stopped (Result::then). Empty: never (the command line stops by signal).
  std::function<bool()> interrupted{};
};

// The outputs an operation made and its record.
struct Result {
  Record record = Record::object();
  // Outputs kept in memory (Frontend::keep_outputs, no path given), by parameter name.
  std::map<std::string, io::ImageF, std::less<>> images;
  std::map<std::string, std::string, std::less<>> texts;
  // A text output given as "-": what goes to standard output (the front end writes it).
  std::string standard_output;
  bool wrote_standard_output = false;
  // Lines a front end shows once the outputs are committed ("wrote x.exr").
  std::vector<std::string> notices;
  // Work a front end runs after the outputs are committed and the notices shown (`view --serve`:
  // the server, until Frontend::interrupted or the process is stopped). Empty: none.
  std::function<void()> then;
};

// A request bound and checked by prepare(): the operation, its values (the given ones, each
// checked by its spec; defaults are the settings' own, bound through their schemas) and the front
// end's.
class Request {
 public:
  Request(const OperationInfo& op, ParameterValues values, Frontend frontend);

  const OperationInfo& operation() const { return *op_; }
  const ParameterValues& values() const { return values_; }
  bool given(std::string_view name) const;
  std::optional<std::string> text(std::string_view name) const;
  std::optional<double> number(std::string_view name) const;
  // The given values of `schema`'s parameters bound over `p` (the operation's name in messages).
  template <class P>
  P bind(const ParameterSchema<P>& schema, P p = {}) const {
    schema.bind(values_.only(schema.specs()), p, context());
    return p;
  }
  std::string context() const;

  void warn(const std::string& message) const;
  void progress(int done, int total, std::string_view step) const;
  const Frontend& frontend() const { return frontend_; }
  // Drops a value (prepare: a value the request does not read, warned of).
  void drop(std::string_view name) { values_.erase(name); }

  // The file a parameter names: its value, else its spec's default ("-" of a standard stream).
  std::optional<std::string> file(std::string_view name) const;

  // ---- inputs: in memory, or read from the file the value names ("-": standard input)
  bool has_input(std::string_view name) const;
  io::ImageF image(std::string_view name) const;
  io::ImageF scalar_image(std::string_view name) const;  // one channel (io::read_scalar_image)
  std::string text_file(std::string_view name) const;
  // Where an input comes from, as messages name it ("--image 'a.exr'", "the image").
  std::string source(std::string_view name) const;

  // ---- outputs: written (atomically, inside the command's transaction) to the path the value
  // names, "-" to standard output (texts), or, when the front end keeps outputs, a required
  // output without a path kept in memory (an optional one without a path is not made)
  bool output_wanted(std::string_view name) const;
  std::string output_path(std::string_view name) const;  // "" when kept in memory
  // An image by the path's extension (.exr with metadata, .hdr, .pfm, .png a tone-mapped preview).
  void write_image(Result& result, std::string_view name, const io::ImageF& image,
                   const io::Metadata& metadata) const;
  // An 8-bit image as PNG (in memory: its values 0-255 as floats).
  void write_png(Result& result, std::string_view name, const io::Image8& image,
                 const io::Metadata& metadata) const;
  void write_text(Result& result, std::string_view name, std::string text) const;

 private:
  const OperationInfo* op_;
  ParameterValues values_;
  Frontend frontend_;
};

// ---- operations ---------------------------------------------------------------------------------

struct OperationInfo {
  std::string name{};     // as the command line spells it, e.g. "sh fit"
  std::string summary{};  // one line (a command list)
  std::string description{};
  std::vector<ParameterSpec> parameters{};
  std::vector<Relation> relations{};
  // The operation also takes the chosen model's own parameters (render, eval): every registered
  // model's parameter names are accepted; one the chosen model does not declare is warned of and
  // ignored (`skylight models` lists them).
  bool model_parameters = false;
  std::vector<FieldSpec> result{};  // the record's fields
  std::string result_type{};        // the library's types it fills, in words
  // The checks that need the values together but no work (which mode reads which values, a
  // file's format): InvalidArgument, or warnings (Request::warn) with Request::drop.
  std::function<void(Request&)> check{};
  // The work: outputs written through the request, the record made from the declared fields.
  std::function<Result(const Request&, const ProgressSink&)> run{};

  const ParameterSpec* find(std::string_view parameter) const;
};

// The spec that parses the value of `name` for `op` when the model named `model` is chosen (its
// own spec for a model parameter; else the first model's that declares the name), or null.
const ParameterSpec* parameter_spec(const OperationInfo& op, std::string_view model,
                                    std::string_view name);

// Binds and checks a request before any work: unknown names (with the nearest one), each value by
// its spec, the required values, the relations, the files (every input exists and is readable,
// outputs have an accepted format, name no input and not each other, and their directory
// exists), then op.check. Throws InvalidArgument (a usage error) or IoError (an output's
// directory); warnings go to frontend.warn.
Request prepare(const OperationInfo& op, ParameterValues given, Frontend frontend);

// Runs a prepared request: its outputs are one transaction (all or none), the record is checked
// (finite numbers: an operation never returns NaN or Inf), `present` (the front end showing the
// record; a failure there writes nothing) is called before the outputs commit.
Result execute(const Request& request, const std::function<void(const Result&)>& present = {});

// The record as labelled lines (a table per list of records), from the declared fields: the
// text form of the CLI.
std::string text_of(const std::vector<FieldSpec>& fields, const Record& record);

// "<name> is not a parameter of <op>; did you mean '<nearest>'?", names spelled by the front end.
std::string unknown_parameter_message(const OperationInfo& op, std::string_view name,
                                      const std::vector<std::string>& known);

}  // namespace skylight::operations
