// The `sh` model: a sky reconstructed from an SH polynomial table (Habel, Mustata & Wimmer 2008:
// eq. 1 at the sun's zenith angle and turbidity, rotated to the sun's azimuth by eq. 4, optionally
// filtered by eq. 5), so that every tool works on the reconstruction (docs/SH.md).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "skylight/models/sky_model.h"
#include "skylight/sh/irradiance.h"
#include "skylight/sh/polynomial.h"

namespace skylight {

// The table used when none is given (data/sh/, docs/SH.md): Preetham in XYZ, 7 bands, degrees
// (17, 12) over theta_s in [0, 90] deg and T in [2.5, 6].
inline constexpr const char* kDefaultShTable = "sh/preetham_xyz_7_17_12.json";

struct ShParameters {
  SunPosition sun;
  std::string table;  // --table FILE (JSON, `skylight sh fit`); empty: kDefaultShTable (embedded)
  int bands = 0;      // --bands N; 0: all of the table's
  bool no_ringing_filter = false;  // --no-ringing-filter
  // --turbidity: the table's second parameter tau (named in the table, e.g. "turbidity");
  // absent: the middle of the table's range.
  std::optional<double> turbidity;

  static const ParameterSchema<ShParameters>& schema();
};

// `skylight sh eval`: the sky's coefficients, or with --irradiance those of the irradiance
// (sh/irradiance.h).
struct ShEvalOptions {
  bool irradiance = false;
  static const ParameterSchema<ShEvalOptions>& schema();
};
// `skylight sh render`: the reconstructed sky as an equirect environment map --width px wide
// (height = width / 2).
struct ShRenderOptions {
  int width = 512;
  static const ParameterSchema<ShRenderOptions>& schema();
};

// The table of a file (IoError if unreadable, InvalidArgument naming the field if malformed), or
// the embedded default for an empty path.
sh::PolynomialTable load_sh_table(const std::string& path);

// The `sh` model.
//  * tristimulus(), rgb(): the reconstruction sum_lm c_lm Y_lm(view) in the table's channels (XYZ
//    or linear sRGB, the other converted by the sRGB matrix) in EVERY direction, below the horizon
//    too, unclamped: it rings and may be negative (docs/SH.md). No solar disc.
//  * The sun's zenith angle and tau must lie in the table's fitted ranges (InvalidArgument).
class ShSkyModel final : public SkyModel {
 public:
  explicit ShSkyModel(const ShParameters& params);
  // With an already loaded table (params.table is then only recorded).
  ShSkyModel(const ShParameters& params, std::shared_ptr<const sh::PolynomialTable> table);
  static constexpr std::string_view kName = "sh";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const ShParameters& parameters() const { return params_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  Rgb rgb(Vec3 view) const override;
  Domain domain() const override;

  const sh::PolynomialTable& table() const { return *table_; }
  // The SH coefficients of the sky (rotated and, unless switched off, filtered): what the model
  // reconstructs (radiance for display).
  const sh::Coefficients& coefficients() const { return coefficients_; }
  // The coefficients of the sky's irradiance, E_lm = A_l c_lm (sh/irradiance.h), from the
  // UNFILTERED radiance: the ringing filter (eq. 5) is for display of radiance; it scales the l = 1
  // and l = 2 terms by sinc(pi l / N) and would bias the cosine convolution (upward irradiance
  // 10 % low at 3 bands). Used by `sh eval --irradiance` and `sh render --sphere`.
  // Evaluated when asked (the table once more, unfiltered), not with every model.
  sh::Coefficients irradiance_coefficients() const;

 private:
  ShParameters params_;
  std::shared_ptr<const sh::PolynomialTable> table_;
  sh::Coefficients coefficients_;
};

}  // namespace skylight
