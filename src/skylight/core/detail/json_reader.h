// The one strict JSON reader of the library's files (the networks' weights files in nn/, the SH
// tables in sh/): every failure is one skylight::InvalidArgument naming the file (`where`) and the
// field. Header-only over nlohmann::json; a detail header (not installed).
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"

namespace skylight::detail::json {

// The text as a JSON object; "<where>: not valid JSON (...)" or "<where>: not a JSON object".
inline nlohmann::json parse_object(std::string_view text, const std::string& where) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for 1e400
    throw InvalidArgument(where + ": not valid JSON (" + excerpt(e.what()) + ")");
  }
  if (!j.is_object()) throw InvalidArgument(where + ": not a JSON object");
  return j;
}

[[noreturn]] inline void bad(const std::string& where, const std::string& field,
                             const std::string& why) {
  throw InvalidArgument(where + ": field '" + field + "' " + why);
}

// j[name]; `prefix` names the enclosing object in the message ("provenance.").
inline const nlohmann::json& field(const nlohmann::json& j, const std::string& where,
                                   const std::string& name, const std::string& prefix = {}) {
  if (!j.is_object() || !j.contains(name)) bad(where, prefix + name, "is missing");
  return j.at(name);
}

inline double number(const nlohmann::json& v, const std::string& where, const std::string& name) {
  if (!v.is_number() || !std::isfinite(v.get<double>())) bad(where, name, "is not a finite number");
  return v.get<double>();
}

inline double positive(const nlohmann::json& v, const std::string& where, const std::string& name) {
  const double x = number(v, where, name);
  if (!(x > 0.0)) bad(where, name, "is not positive");
  return x;
}

inline long long integer(const nlohmann::json& v, const std::string& where, const std::string& name,
                         long long lo, long long hi) {
  if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi) {
    bad(where, name,
        "is not an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v.get<long long>();
}

inline std::string text(const nlohmann::json& v, const std::string& where,
                        const std::string& name) {
  if (!v.is_string()) bad(where, name, "is not a string");
  return v.get<std::string>();
}

inline const nlohmann::json& array(const nlohmann::json& v, const std::string& where,
                                   const std::string& name) {
  if (!v.is_array()) bad(where, name, "is not an array");
  return v;
}

inline std::vector<double> numbers(const nlohmann::json& v, const std::string& where,
                                   const std::string& name) {
  std::vector<double> out;
  for (const auto& e : array(v, where, name)) out.push_back(number(e, where, name));
  return out;
}

}  // namespace skylight::detail::json
