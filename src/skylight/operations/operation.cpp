#include "skylight/operations/operation.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "skylight/core/numbers.h"
#include "skylight/core/text.h"
#include "skylight/io/file.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/tonemap.h"

namespace skylight::operations {

namespace fs = std::filesystem;

std::string_view to_string(RelationKind kind) {
  return kind == RelationKind::excludes ? "excludes" : "requires";
}

std::string_view to_string(FieldKind kind) {
  switch (kind) {
    case FieldKind::number:
      return "number";
    case FieldKind::integer:
      return "integer";
    case FieldKind::text:
      return "text";
    case FieldKind::flag:
      return "flag";
    case FieldKind::numbers:
      return "numbers";
    case FieldKind::texts:
      return "texts";
    case FieldKind::record:
      return "record";
    case FieldKind::records:
      return "records";
  }
  return "number";
}

const ParameterSpec* OperationInfo::find(std::string_view parameter) const {
  for (const ParameterSpec& s : parameters)
    if (s.name == parameter) return &s;
  return nullptr;
}

// ---- the request --------------------------------------------------------------------------------

std::optional<std::string> output_target(const Request& r, std::string_view name);

Request::Request(const OperationInfo& op, ParameterValues values, Frontend frontend)
    : op_(&op), values_(std::move(values)), frontend_(std::move(frontend)) {}

bool Request::given(std::string_view name) const {
  return values_.has(name);
}

std::optional<std::string> Request::text(std::string_view name) const {
  if (const ParameterValue* v = values_.find(name))
    if (const auto* s = std::get_if<std::string>(v)) return *s;
  return std::nullopt;
}

std::optional<double> Request::number(std::string_view name) const {
  return values_.number(name);
}

std::string Request::context() const {
  return op_->name;
}

void Request::warn(const std::string& message) const {
  if (frontend_.warn) frontend_.warn(message);
}

void Request::progress(int done, int total, std::string_view step) const {
  if (frontend_.progress) frontend_.progress(done, total, step);
}

std::optional<std::string> Request::file(std::string_view name) const {
  if (auto t = text(name)) return t;
  if (const ParameterSpec* s = op_->find(name))
    if (const auto* v = std::get_if<ParameterValue>(&s->default_value))
      if (const auto* t = std::get_if<std::string>(v)) return *t;
  return std::nullopt;
}

bool Request::has_input(std::string_view name) const {
  return frontend_.images.count(name) > 0 || frontend_.texts.count(name) > 0 || given(name);
}

std::string Request::source(std::string_view name) const {
  if (const auto path = text(name)) return fmt::format("{} '{}'", spelled(name), excerpt(*path));
  return fmt::format("the {}", spelled(name));
}

io::ImageF Request::image(std::string_view name) const {
  if (const auto it = frontend_.images.find(name); it != frontend_.images.end()) return it->second;
  const auto path = text(name);
  SKYLIGHT_CHECK(path.has_value(), "Request::image: an input without a value");
  return io::read_image(*path);
}

io::ImageF Request::scalar_image(std::string_view name) const {
  if (const auto it = frontend_.images.find(name); it != frontend_.images.end()) {
    if (it->second.channels != 1)
      throw InvalidArgument(fmt::format("{} must have one channel", source(name)));
    return it->second;
  }
  const auto path = text(name);
  SKYLIGHT_CHECK(path.has_value(), "Request::scalar_image: an input without a value");
  return io::read_scalar_image(*path);
}

std::string Request::text_file(std::string_view name) const {
  if (const auto it = frontend_.texts.find(name); it != frontend_.texts.end()) return it->second;
  const auto path = file(name);
  SKYLIGHT_CHECK(path.has_value(), "Request::text_file: an input without a value");
  if (*path == "-") {
    if (!frontend_.standard_input)
      throw InvalidArgument(fmt::format("{}: this front end has no standard input", spelled(name)));
    return frontend_.standard_input();
  }
  return io::read_text_file(*path);
}

bool Request::output_wanted(std::string_view name) const {
  if (given(name)) return true;
  const ParameterSpec* s = op_->find(name);
  if (frontend_.keep_outputs) return s && (s->required() || file(name));
  return file(name).has_value();
}

// Where an output goes: its path (or "-"), nullopt when kept in memory or not made.
std::optional<std::string> output_target(const Request& r, std::string_view name) {
  if (r.given(name)) return r.text(name);
  if (r.frontend().keep_outputs) return std::nullopt;
  return r.file(name);
}

std::string Request::output_path(std::string_view name) const {
  return output_target(*this, name).value_or("");
}

void Request::write_image(Result& result, std::string_view name, const io::ImageF& image,
                          const io::Metadata& metadata) const {
  const auto path = output_target(*this, name);
  if (!path) {
    if (output_wanted(name)) result.images[std::string(name)] = image;
    return;
  }
  render::write_image_or_preview(*path, image, metadata);
  result.notices.push_back(fmt::format("wrote {}", io::shown_path(*path)));
}

void Request::write_png(Result& result, std::string_view name, const io::Image8& image,
                        const io::Metadata& metadata) const {
  const auto path = output_target(*this, name);
  if (!path) {
    if (!output_wanted(name)) return;
    io::ImageF f(image.width, image.height, 3);
    for (std::size_t i = 0; i < f.data.size(); ++i) f.data[i] = image.data[i];
    result.images[std::string(name)] = std::move(f);
    return;
  }
  io::write_png(*path, image, metadata);
  result.notices.push_back(fmt::format("wrote {}", io::shown_path(*path)));
}

void Request::write_text(Result& result, std::string_view name, std::string text) const {
  const auto path = output_target(*this, name);
  if (!path) {
    if (output_wanted(name)) result.texts[std::string(name)] = std::move(text);
    return;
  }
  if (*path == "-") {
    result.standard_output += text;
    result.wrote_standard_output = true;
    return;
  }
  io::write_text_file(*path, text);
  result.notices.push_back(fmt::format("wrote {}", io::shown_path(*path)));
}

// ---- prepare ------------------------------------------------------------------------------------

std::string unknown_parameter_message(const OperationInfo& op, std::string_view name,
                                      const std::vector<std::string>& known) {
  std::vector<std::string> spelled_known;
  for (const auto& k : known) spelled_known.push_back(spelled(k));
  return fmt::format("{} is not a parameter of {}{}", spelled(name), op.name,
                     did_you_mean(spelled(name), spelled_known));
}

const ParameterSpec* parameter_spec(const OperationInfo& op, std::string_view model,
                                    std::string_view name) {
  if (const ParameterSpec* s = op.find(name)) return s;
  if (!op.model_parameters) return nullptr;
  if (const ModelInfo* m = find_model(model))
    if (const ParameterSpec* s = m->find_parameter(name)) return s;
  for (const ModelInfo& m : model_registry())
    if (const ParameterSpec* s = m.find_parameter(name)) return s;
  return nullptr;
}

namespace {

bool ends_with_any(const std::string& path, const std::vector<std::string>& endings) {
  std::string lower = fs::path(path).extension().string();
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return std::find(endings.begin(), endings.end(), lower) != endings.end();
}

std::string endings_text(const std::vector<std::string>& endings) {
  std::string out;
  for (std::size_t i = 0; i < endings.size(); ++i)
    out += (i == 0 ? "" : i + 1 == endings.size() ? " or " : ", ") + endings[i];
  return out;
}

// Two paths that name one file: the same text once normalised, or the same existing file.
bool same_file(const std::string& a, const std::string& b) {
  if (fs::path(a).lexically_normal() == fs::path(b).lexically_normal()) return true;
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// Names the operation takes: its parameters and, with model_parameters, the chosen model's
// (values of other models' parameters are warned of and dropped).
void check_names(const OperationInfo& op, ParameterValues& given, const Frontend& fe) {
  std::vector<std::string> known;
  for (const ParameterSpec& s : op.parameters) known.push_back(s.name);
  const ModelInfo* model = nullptr;
  if (op.model_parameters)
    if (const ParameterValue* m = given.find("model"))
      if (const auto* name = std::get_if<std::string>(m)) model = &require_model(*name, "model");
  std::vector<std::string> dropped;
  for (const auto& [name, value] : given.all()) {
    if (op.find(name)) continue;
    if (op.model_parameters) {
      if (model && model->find_parameter(name)) continue;
      if (parameter_spec(op, "", name)) {
        if (model) {
          if (fe.warn)
            fe.warn(fmt::format("{} is not a parameter of model '{}'; ignored", spelled(name),
                                model->name));
          dropped.push_back(name);
        }
        continue;
      }
      // A name no model has: refused, with the nearest of the operation's and the chosen
      // model's (every model's when none is chosen).
      std::vector<std::string> all = known;
      for (const ModelInfo& m : model_registry())
        if (!model || &m == model)
          for (const ParameterSpec& s : m.parameters) all.push_back(s.name);
      if (!model) throw InvalidArgument(unknown_parameter_message(op, name, all));
      std::vector<std::string> spelled_all;
      for (const auto& k : all) spelled_all.push_back(spelled(k));
      throw InvalidArgument(fmt::format("{} is not a parameter of {} or of model '{}'{}",
                                        spelled(name), op.name, model->name,
                                        did_you_mean(spelled(name), spelled_all)));
    }
    throw InvalidArgument(unknown_parameter_message(op, name, known));
  }
  for (const auto& name : dropped) given.erase(name);
}

void check_values(const OperationInfo& op, const ParameterValues& given) {
  const std::string model = [&] {
    const ParameterValue* m = given.find("model");
    const auto* s = m ? std::get_if<std::string>(m) : nullptr;
    return s ? *s : std::string();
  }();
  for (const auto& [name, value] : given.all()) {
    const ParameterSpec* spec = parameter_spec(op, model, name);
    SKYLIGHT_CHECK(spec != nullptr, "check_values: an unchecked name");
    spec->check(value, op.find(name) ? std::string() : fmt::format("model '{}'", model));
  }
}

void check_required(const OperationInfo& op, const ParameterValues& given, const Frontend& fe) {
  for (const ParameterSpec& s : op.parameters) {
    if (!s.required() || given.has(s.name)) continue;
    if (fe.images.count(s.name) || fe.texts.count(s.name)) continue;
    if (fe.keep_outputs && s.file == FileRole::output) continue;
    detail::throw_missing_parameter(s, "");
  }
}

void check_relations(const OperationInfo& op, Request& request) {
  for (const Relation& r : op.relations) {
    const bool a = request.has_input(r.a), b = request.has_input(r.b);
    const bool excludes = r.kind == RelationKind::excludes;
    if (!(a && (excludes ? b : !b))) continue;
    const std::string why = r.why.empty() ? "" : " (" + r.why + ")";
    if (r.unread) {
      request.warn(fmt::format("{} is not read {} {}{}; ignored", spelled(r.a),
                               excludes ? "with" : "without", spelled(r.b), why));
      request.drop(r.a);
    } else if (excludes) {
      throw InvalidArgument(
          fmt::format("{} and {} exclude each other{}", spelled(r.a), spelled(r.b), why));
    } else {
      throw InvalidArgument(fmt::format("{} needs {}{}", spelled(r.a), spelled(r.b), why));
    }
  }
}

void check_input(const ParameterSpec& s, const std::string& path) {
  if (s.standard_stream && path == "-") return;
  const std::string shown = fmt::format("{} '{}'", spelled(s.name), io::shown_path(path));
  if (path.empty()) throw InvalidArgument(fmt::format("{} names no file", spelled(s.name)));
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InvalidArgument(fmt::format("{}: no such file", shown));
  if (fs::is_directory(st)) throw InvalidArgument(fmt::format("{}: is a directory", shown));
  if (::access(path.c_str(), R_OK) != 0)
    throw InvalidArgument(fmt::format("{}: cannot be read ({})", shown, io::errno_message(errno)));
  if (!s.formats.empty() && !ends_with_any(path, s.formats))
    throw InvalidArgument(fmt::format("{}: read {} files", shown, endings_text(s.formats)));
}

void check_output(const ParameterSpec& s, const std::string& path) {
  if (s.standard_stream && path == "-") return;
  if (path.empty()) throw InvalidArgument(fmt::format("{} names no file", spelled(s.name)));
  if (!s.formats.empty() && !ends_with_any(path, s.formats))
    throw InvalidArgument(fmt::format("{} '{}': write {}", spelled(s.name), io::shown_path(path),
                                      endings_text(s.formats)));
  // Not a directory (a report's directory is its own role), and the directory the file goes into
  // (a report's: its parent) exists.
  std::error_code ec;
  if (s.file == FileRole::output && fs::is_directory(path, ec))
    io::throw_write_error(path, "is a directory");
  const fs::path dir = fs::path(path).lexically_normal().parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    io::throw_write_error(path, fmt::format("no directory '{}'", io::shown_path(dir)));
}

// Inputs exist and are readable; outputs have an accepted ending, a directory, and name no input
// and not each other.
void check_files(const OperationInfo& op, const ParameterValues& given) {
  std::vector<std::pair<const ParameterSpec*, std::string>> inputs, outputs;
  for (const ParameterSpec& s : op.parameters) {
    if (s.file == FileRole::none) continue;
    const ParameterValue* v = given.find(s.name);
    if (!v) continue;
    const std::string& text = std::get<std::string>(*v);
    for (const std::string& path : s.repeated ? split_repeated(text) : std::vector{text}) {
      if (s.file == FileRole::input) {
        check_input(s, path);
        if (path != "-") inputs.emplace_back(&s, path);
      } else {
        check_output(s, path);
        if (path != "-") outputs.emplace_back(&s, path);
      }
    }
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (const auto& [in, path] : inputs)
      if (same_file(outputs[i].second, path))
        throw InvalidArgument(fmt::format(
            "{} '{}' is the input {}: an output never overwrites an input",
            spelled(outputs[i].first->name), io::shown_path(outputs[i].second), spelled(in->name)));
    for (std::size_t j = 0; j < i; ++j)
      if (same_file(outputs[i].second, outputs[j].second))
        throw InvalidArgument(fmt::format(
            "{} and {} name the same file '{}'; give each its own", spelled(outputs[j].first->name),
            spelled(outputs[i].first->name), io::shown_path(outputs[i].second)));
  }
}

}  // namespace

Request prepare(const OperationInfo& op, ParameterValues given, Frontend frontend) {
  check_names(op, given, frontend);
  check_values(op, given);
  check_required(op, given, frontend);
  Request request(op, std::move(given), std::move(frontend));
  check_relations(op, request);
  check_files(op, request.values());
  if (op.check) op.check(request);
  return request;
}

// ---- execute ------------------------------------------------------------------------------------

namespace {

// Every number of the record is finite (an operation never returns NaN or Inf).
void check_finite(const Record& r, const std::string& where) {
  if (r.is_number_float() && !std::isfinite(r.get<double>()))
    throw std::runtime_error(
        fmt::format("the result's {} is not finite; nothing was written", where));
  if (r.is_object())
    for (const auto& [k, v] : r.items()) check_finite(v, k);
  if (r.is_array())
    for (const auto& v : r) check_finite(v, where);
}

}  // namespace

Result execute(const Request& request, const std::function<void(const Result&)>& present) {
  const OperationInfo& op = request.operation();
  SKYLIGHT_CHECK(static_cast<bool>(op.run), "an operation without work");
  io::OutputTransaction outputs;
  // What the library precomputes on the operation's behalf (a model's tables) reports its steps
  // to the same sink.
  const ProgressSink& sink = request.frontend().progress;
  const ScopedProgressSink scoped(sink);
  Result result = op.run(request, sink);
  check_finite(result.record, "record");
  for (const FieldSpec& f : op.result)
    SKYLIGHT_CHECK(result.record.contains(f.name), "a declared field missing from the record");
  SKYLIGHT_CHECK(result.record.size() == op.result.size(), "a field the operation did not declare");
  if (present) present(result);
  outputs.commit();
  return result;
}

// ---- text ---------------------------------------------------------------------------------------

namespace {

std::string value_text(const FieldSpec& f, const Record& v) {
  if (v.is_null()) return "none";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number()) {
    const double d = v.get<double>();
    // Seven significant digits unless the field says how many decimals (JSON: every digit).
    return f.decimals >= 0 ? fmt::format("{:.{}f}", d, f.decimals) : fmt::format("{:.7g}", d);
  }
  if (v.is_array()) {
    std::string out;
    for (const auto& e : v) {
      if (!out.empty()) out += ',';
      out += value_text(f, e);
    }
    return out;
  }
  return v.dump();
}

// A unit after a value, where it says something.
std::string with_unit(const FieldSpec& f, std::string text) {
  if (f.unit.empty() || f.unit == "1") return text;
  return text + " " + f.unit;
}

// The field's name as a label: '_' as spaces, without the unit's suffix that the value then shows
// ("sun_zenith_deg" of unit "deg": "sun zenith"; "zenith_luminance_cd_m2": "zenith luminance").
std::string stripped_label(const FieldSpec& f) {
  std::string label = f.name, slug = "_";
  for (const char c : f.unit)
    if (std::isalnum(static_cast<unsigned char>(c)))
      slug += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (c == '/' || c == ' ')
      slug += '_';
  std::string lower = label;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (f.unit != "1" && slug.size() > 1 && label.size() > slug.size() && lower.ends_with(slug))
    label.resize(label.size() - slug.size());
  std::replace(label.begin(), label.end(), '_', ' ');
  return label;
}

// The labels of a record's fields: without the unit's suffix unless two would then read alike
// ("elevation_m" and "elevation_deg" keep theirs).
std::vector<std::string> labels_of(const std::vector<FieldSpec>& fields) {
  std::vector<std::string> out;
  for (const FieldSpec& f : fields) out.push_back(stripped_label(f));
  const std::vector<std::string> stripped = out;
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (std::count(stripped.begin(), stripped.end(), stripped[i]) > 1) {
      out[i] = fields[i].name;
      std::replace(out[i].begin(), out[i].end(), '_', ' ');
    }
  return out;
}

// A table's cell of a nested list of records: each row's values joined by '=' ("turbidity=3.1"),
// the rows by spaces. A nested list with more than kMaxCellFields fields is not a column of the
// text table (the JSON holds it).
constexpr std::size_t kMaxCellFields = 2;
std::string cell_text(const FieldSpec& f, const Record& v) {
  if (f.kind != FieldKind::records || v.is_null()) return value_text(f, v);
  std::vector<std::string> rows;
  for (const auto& row : v) {
    std::vector<std::string> values;
    for (const FieldSpec& c : f.fields) values.push_back(value_text(c, row.at(c.name)));
    rows.push_back(fmt::format("{}", fmt::join(values, "=")));
  }
  return fmt::format("{}", fmt::join(rows, " "));
}
bool in_table(const FieldSpec& c) {
  return c.kind != FieldKind::records || c.fields.size() <= kMaxCellFields;
}

void append_table(std::string& out, const FieldSpec& f, const Record& rows) {
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> header;
  for (const FieldSpec& c : f.fields)
    if (in_table(c))
      header.push_back(c.unit.empty() || c.unit == "1" ? c.name : c.name + " [" + c.unit + "]");
  cells.push_back(header);
  for (const auto& row : rows) {
    std::vector<std::string> line;
    for (const FieldSpec& c : f.fields)
      if (in_table(c)) line.push_back(cell_text(c, row.at(c.name)));
    cells.push_back(std::move(line));
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : cells)
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  for (const auto& line : cells) {
    std::string text = " ";
    for (std::size_t i = 0; i < line.size(); ++i)
      text += " " + line[i] + std::string(i + 1 < line.size() ? width[i] - line[i].size() : 0, ' ');
    out += text + "\n";
  }
}

}  // namespace

std::string text_of(const std::vector<FieldSpec>& fields, const Record& record) {
  const std::vector<std::string> labels = labels_of(fields);
  // The labels' column as wide as the longest shown (a null field is not shown).
  std::size_t width = 0;
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (!record.at(fields[i].name).is_null() && !fields[i].verbatim)
      width = std::max(width, labels[i].size());
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const FieldSpec& f = fields[i];
    const Record& v = record.at(f.name);
    // A field that does not apply, an empty list.
    if (v.is_null() || (f.kind == FieldKind::records && v.empty())) continue;
    const std::string& label = labels[i];
    if (f.verbatim) {
      for (const auto& line : v) out += line.get<std::string>() + "\n";
    } else if (f.kind == FieldKind::records) {
      out += label + ":\n";
      append_table(out, f, v);
    } else if (f.kind == FieldKind::record) {
      out += label + ":\n";
      std::string inner = text_of(f.fields, v);
      for (std::size_t at = 0; at < inner.size();) {
        const std::size_t nl = inner.find('\n', at);
        out += "  " + inner.substr(at, nl - at + 1);
        at = nl + 1;
      }
    } else {
      out += fmt::format("{:<{}}  {}\n", label, width, with_unit(f, value_text(f, v)));
    }
  }
  return out;
}

}  // namespace skylight::operations
