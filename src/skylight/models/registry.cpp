// The model registry: name -> documentation, parameters (unit, range, default) and factory.
#include <memory>

#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/nishita.h"
#include "skylight/models/perez.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sh.h"
#include "skylight/models/sky_model.h"

namespace skylight {
namespace {

// A registry factory: binds the generic values into the model's typed parameters (its schema
// applies defaults and checks them) and builds the model.
template <class Model, class Params>
std::function<std::unique_ptr<SkyModel>(const SkyParameters&)> factory(std::string_view name) {
  return [name = std::string(name)](const SkyParameters& sp) -> std::unique_ptr<SkyModel> {
    return std::make_unique<Model>(bind_parameters<Params>(sp, name));
  };
}

}  // namespace

const std::vector<ModelInfo>& model_registry() {
  static const std::vector<ModelInfo> registry = [] {
    std::vector<ModelInfo> r;
    r.push_back(ModelInfo{
        "perez",
        "Perez all-weather relative luminance (Perez et al. 1993) with user coefficients A..E",
        "luminance Y [cd/m^2] = Lz F(theta,gamma)/F(0,theta_s); XYZ at D65 chromaticity",
        PerezParameters::schema().specs(),
        "any coefficients that keep F > 0; sun above the horizon (below: 0)", false, false,
        factory<PerezModel, PerezParameters>("perez"),
        // A clear sky: the CIE S 011 type 12 gradation and indicatrix coefficients as A..E.
        ParameterValues()
            .set("perez", std::vector<double>{-1.0, -0.32, 10.0, -3.0, 0.45})
            .set("zenith-luminance", 5000.0)});
    r.push_back(ModelInfo{
        "preetham",
        "Preetham, Shirley & Smits 1999 analytic daylight: luminance, chromaticity, spectral, sun",
        "XYZ with Y [cd/m^2]; spectral radiance [W m^-2 sr^-1 nm^-1] 300-830 nm via the CIE "
        "daylight basis; sun disc 380-750 nm",
        PreethamParameters::schema().specs(),
        "fitted for turbidity 2-6; unusable below 1.9 and above 10 (Zotti et al. 2007); the "
        "zenith luminance formula is negative (Zotti Fig. 1) for T < 1.12 with a high sun "
        "(T = 1: sun zenith < 12.9 deg) and T > 11.2 with the sun at the horizon: returned as 0, "
        "flagged unphysical; sun below the horizon: 0 (undefined)",
        true, true, factory<PreethamModel, PreethamParameters>("preetham")});
    r.push_back(ModelInfo{
        "cie",
        "ISO 15469 / CIE S 011:2003 Standard General Sky, types 1-15, and 16 = traditional "
        "overcast",
        "luminance Y [cd/m^2]; XYZ at D65 chromaticity (0.3127, 0.3290)",
        CieParameters::schema().specs(),
        "all sun positions above the horizon; the Kittler-Darula typical zenith luminance is "
        "recommended for solar elevations 10-80 deg (flagged extrapolated outside)",
        false, false, factory<CieSkyModel, CieParameters>("cie")});
    r.push_back(ModelInfo{
        "hosek",
        "Hosek & Wilkie 2012 analytic sky (9-parameter extended Perez form fitted to "
        "simulations; ArHosekSkyModel v1.4a datasets) with the 2013 solar radiance function",
        "XYZ = the CIE XYZ dataset x 683 (Y [cd/m^2]); rgb = the native RGB dataset x 683 (linear "
        "sRGB primaries, same photometric scale); spectral radiance [W m^-2 sr^-1 nm^-1] "
        "320-720 nm; sun disc radius 0.255 deg with limb darkening",
        HosekParameters::schema().specs(),
        "turbidity 1-10 and albedo 0-1 (rejected outside: no dataset knots there); sun "
        "elevation 0-90 deg; sun below the horizon: sky and sun 0 (undefined); the fit's slightly "
        "negative values exactly at the horizon with a low sun are returned as 0",
        true, true, factory<HosekWilkieModel, HosekParameters>("hosek")});
    r.push_back(ModelInfo{
        "nishita",
        "Physically based single scattering (Nishita et al. 1993) in a spherical planet's "
        "exponential Rayleigh + Mie atmosphere (optional ozone layer), fast path with Pietras' "
        "optical-length tables; "
        "Earth defaults, any observer altitude (ground to orbit), planet shadow at twilight",
        "XYZ with Y [cd/m^2] for the ASTM G-173 extraterrestrial sun (20 nm bins 380-780 nm); "
        "spectral radiance [W m^-2 sr^-1 nm^-1] 360-830 nm; with --solar-irradiance E both per "
        "flat irradiance E [W m^-2 nm^-1] (E = 1: sr^-1); in-scattered light only, the ground "
        "reflects only with an explicit --albedo; no solar disc",
        NishitaParameters::schema().specs(),
        "any observer altitude 0-10000 km, any view direction, sun at any elevation (below the "
        "horizon: single scattering with the planet's shadow, flagged extrapolated); fast path "
        "within 0.5 % of the brute-force reference (tested)",
        true, false, factory<NishitaModel, NishitaParameters>("nishita")});
    r.push_back(ModelInfo{
        "nn",
        "Neural sky model (Satilmis et al. 2016): a small MLP trained on another sky model "
        "(skylight nn train), e.g. the paper's 6-12-3 network; fixed cost per direction",
        "rgb = the network's linear sRGB in the units of its source model's rgb() (the weights "
        "file's target_scale); XYZ = rgb converted (D65)",
        NeuralSkyParameters::schema().specs(),
        "the source model's validity within the network's training range (weights file "
        "provenance: turbidities, suns 0-90 deg); outside it extrapolated (flagged); sun below "
        "the horizon: 0 (undefined); no spectral output, no solar disc",
        false, false, factory<NeuralSkyModel, NeuralSkyParameters>("nn")});
    r.push_back(ModelInfo{
        "sh",
        "a sky reconstructed from an SH polynomial table (Habel, Mustata & Wimmer 2008: "
        "coefficients as polynomials in the sun zenith and turbidity, eq. 1; rotation to the "
        "sun's azimuth, eq. 4; ringing filter, eq. 5) fitted to any model by `skylight sh fit`",
        "the table's channels (XYZ with Y [cd/m^2], or linear sRGB on the same scale) of the "
        "reconstruction sum c_lm Y_lm in every direction, below the horizon too, UNCLAMPED (it "
        "rings and may be negative); no solar disc",
        ShParameters::schema().specs(),
        "the sun zenith and turbidity within the table's fitted ranges (refused outside); the "
        "error against the fitted model is in docs/SH.md",
        false, false, factory<ShSkyModel, ShParameters>("sh"), ParameterValues{}, true});
    return r;
  }();
  return registry;
}

}  // namespace skylight
