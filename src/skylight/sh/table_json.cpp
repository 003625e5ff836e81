// JSON form of a PolynomialTable (docs/SH.md).
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "skylight/core/detail/json_reader.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/polynomial.h"

namespace skylight::sh {
namespace {

constexpr const char* kFormat = "skylight-sh-polynomial-table";
// Version 2 added theta_axis and tau_pieces; version 1 files load as theta axis, one piece.
constexpr int kVersion = 2;

using skylight::detail::json::bad;

const nlohmann::json& field(const nlohmann::json& j, const std::string& where, const char* name) {
  return skylight::detail::json::field(j, where, name);
}

double number(const nlohmann::json& j, const std::string& where, const char* name) {
  return skylight::detail::json::number(field(j, where, name), where, name);
}

int integer(const nlohmann::json& j, const std::string& where, const char* name, int lo, int hi) {
  return static_cast<int>(
      skylight::detail::json::integer(field(j, where, name), where, name, lo, hi));
}

std::string text(const nlohmann::json& j, const std::string& where, const char* name) {
  return skylight::detail::json::text(field(j, where, name), where, name);
}

}  // namespace

std::string table_to_json(const PolynomialTable& t) {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["model"] = t.model;
  j["parameter"] = t.parameter;
  nlohmann::json fixed = nlohmann::json::object();
  for (const auto& [name, value] : t.fixed.all()) {
    std::visit([&, n = name](const auto& v) { fixed[n] = v; }, value);
  }
  j["fixed"] = fixed;
  j["channels"] = t.channels == Channels::xyz ? "xyz" : "linear_srgb";
  j["bands"] = t.bands;
  j["degree_theta"] = t.degree_theta;
  j["degree_tau"] = t.degree_tau;
  j["theta_min_rad"] = t.theta_min;
  j["theta_max_rad"] = t.theta_max;
  j["tau_min"] = t.tau_min;
  j["tau_max"] = t.tau_max;
  j["theta_axis"] = t.theta_axis == ThetaAxis::theta ? "theta" : "elevation_cbrt";
  j["tau_pieces"] = t.tau_pieces;
  if (t.ground_albedo) j["ground_albedo"] = *t.ground_albedo;
  j["basis"] =
      "chebyshev T_i(u) T_j(v), u = the theta axis' coordinate mapped from its range onto [-1, 1], "
      "v = tau mapped from its piece onto [-1, 1]";
  j["layout"] =
      "[((piece * bands (bands + 1) / 2 + l (l + 1) / 2 + m) * 3 + channel) * terms + i * "
      "(degree_tau + 1) + j], m >= 0";
  j["coefficients"] = t.coefficients;
  return j.dump(1);
}

namespace {

// The optional "fixed" object: the values the table's model was held at.
ParameterValues read_fixed(const nlohmann::json& j, const std::string& where) {
  ParameterValues fixed_values;
  if (j.contains("fixed")) {
    const auto& fixed = j.at("fixed");
    if (!fixed.is_object()) bad(where, "fixed", "is not an object");
    for (const auto& [name, v] : fixed.items()) {
      if (v.is_number() && std::isfinite(v.get<double>())) {
        fixed_values.set(name, v.get<double>());
      } else if (v.is_boolean()) {
        fixed_values.set(name, v.get<bool>());
      } else if (v.is_string()) {
        fixed_values.set(name, ParameterValue(v.get<std::string>()));
      } else if (v.is_array()) {
        std::vector<double> list;
        for (const auto& x : v) {
          if (!x.is_number() || !std::isfinite(x.get<double>()))
            bad(where, "fixed", "entry " + excerpt(name) + " holds a value that is not a number");
          list.push_back(x.get<double>());
        }
        fixed_values.set(name, ParameterValue(list));
      } else {
        bad(where, "fixed", "entry " + excerpt(name) + " is not a number, flag, text or list");
      }
    }
  }
  return fixed_values;
}

}  // namespace

PolynomialTable table_from_json(const std::string& s, const std::string& where) {
  const nlohmann::json j = skylight::detail::json::parse_object(s, where);
  if (text(j, where, "format") != kFormat)
    bad(where, "format", "is not '" + std::string(kFormat) + "'");
  const int version = integer(j, where, "version", 0, 1000);
  if (version != 1 && version != kVersion) bad(where, "version", "is not 1 or 2");
  PolynomialTable t;
  t.model = text(j, where, "model");
  t.parameter = text(j, where, "parameter");
  t.fixed = read_fixed(j, where);
  const std::string ch = text(j, where, "channels");
  if (ch == "xyz") {
    t.channels = Channels::xyz;
  } else if (ch == "linear_srgb") {
    t.channels = Channels::linear_srgb;
  } else {
    bad(where, "channels", "is " + excerpt(ch) + ", not 'xyz' or 'linear_srgb'");
  }
  t.bands = integer(j, where, "bands", 1, kMaxBands);
  t.degree_theta = integer(j, where, "degree_theta", 0, 40);
  t.degree_tau = integer(j, where, "degree_tau", 0, 40);
  t.theta_min = number(j, where, "theta_min_rad");
  t.theta_max = number(j, where, "theta_max_rad");
  t.tau_min = number(j, where, "tau_min");
  t.tau_max = number(j, where, "tau_max");
  if (!(t.theta_min >= 0.0 && t.theta_max >= t.theta_min && t.theta_max <= kPi)) {
    bad(where, "theta_max_rad", "must give 0 <= theta_min_rad <= theta_max_rad <= pi");
  }
  if (!(t.tau_max >= t.tau_min)) bad(where, "tau_max", "is below tau_min");
  if (version >= 2) {
    const std::string axis = text(j, where, "theta_axis");
    if (axis == "theta") {
      t.theta_axis = ThetaAxis::theta;
    } else if (axis == "elevation_cbrt") {
      t.theta_axis = ThetaAxis::elevation_cbrt;
    } else {
      bad(where, "theta_axis", "is " + excerpt(axis) + ", not 'theta' or 'elevation_cbrt'");
    }
    t.tau_pieces = integer(j, where, "tau_pieces", 1, kMaxTauPieces);
    if (j.contains("ground_albedo")) {
      const double rho = number(j, where, "ground_albedo");
      if (!(rho >= 0.0 && rho <= 1.0)) bad(where, "ground_albedo", "is outside [0, 1]");
      t.ground_albedo = rho;
    }
  }
  const auto& c = field(j, where, "coefficients");
  const std::size_t expect = static_cast<std::size_t>(t.tau_pieces) *
                             static_cast<std::size_t>(t.bands * (t.bands + 1) / 2) * 3 *
                             static_cast<std::size_t>(t.terms());
  if (!c.is_array() || c.size() != expect) {
    bad(where, "coefficients", "is not an array of " + std::to_string(expect) + " numbers");
  }
  t.coefficients.reserve(expect);
  for (const auto& v : c) {
    // Stored in float: a finite double beyond FLT_MAX would become infinite.
    if (!v.is_number() || !std::isfinite(v.get<double>()) ||
        !std::isfinite(static_cast<float>(v.get<double>()))) {
      bad(where, "coefficients", "holds a value that is not a finite float number");
    }
    t.coefficients.push_back(static_cast<float>(v.get<double>()));
  }
  return t;
}

}  // namespace skylight::sh
