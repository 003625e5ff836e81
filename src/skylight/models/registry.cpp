// The model registry: name -> documentation, parameters (unit, range, default) and factory.
#include <memory>

#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/perez.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sky_model.h"

namespace skylight {
namespace {

ParameterInfo sun_zenith() {
  return {"sun-zenith",
          "deg",
          0.0,
          180.0,
          "45",
          "solar zenith angle (or --sun-elevation = 90 - zenith); > 90 = below the horizon"};
}
ParameterInfo sun_azimuth() {
  return {"sun-azimuth", "deg", -360.0,
          360.0,         "180", "solar azimuth from north towards east (180 = south)"};
}

}  // namespace

const std::vector<ModelInfo>& model_registry() {
  static const std::vector<ModelInfo> registry = [] {
    std::vector<ModelInfo> r;
    r.push_back(ModelInfo{
        "perez",
        "Perez all-weather relative luminance (Perez et al. 1993) with user coefficients A..E",
        "luminance Y [cd/m^2] = Lz F(theta,gamma)/F(0,theta_s); XYZ at D65 chromaticity",
        {sun_zenith(),
         sun_azimuth(),
         {"perez", "1", -kPerezCoefficientLimit, kPerezCoefficientLimit, "required",
          "coefficients A,B,C,D,E of F = (1 + A e^{B/cos theta})(1 + C e^{D gamma} + E cos^2 "
          "gamma)"},
         {"zenith-luminance", "cd/m^2", 1e-9, 1e9, "required", "absolute zenith luminance Lz"}},
        "any coefficients that keep F > 0; sun above the horizon (below: 0)",
        false,
        false,
        [](const SkyParameters& p) -> std::unique_ptr<SkyModel> {
          return std::make_unique<PerezModel>(p);
        }});
    r.push_back(ModelInfo{
        "preetham",
        "Preetham, Shirley & Smits 1999 analytic daylight: luminance, chromaticity, spectral, sun",
        "XYZ with Y [cd/m^2]; spectral radiance [W m^-2 sr^-1 nm^-1] 300-830 nm via the CIE "
        "daylight basis; sun disc 380-750 nm",
        {sun_zenith(),
         sun_azimuth(),
         {"turbidity", "1", 1.0, 64.0, "3", "atmospheric turbidity T (fitted for 2-6)"}},
        "fitted for turbidity 2-6; unusable below 1.9 and above 10 (Zotti et al. 2007); the "
        "zenith luminance formula is negative (Zotti Fig. 1) for T < 1.12 with a high sun "
        "(T = 1: sun zenith < 12.9 deg) and T > 11.2 with the sun at the horizon: returned as 0, "
        "flagged unphysical; sun below the horizon: 0 (undefined)",
        true,
        true,
        [](const SkyParameters& p) -> std::unique_ptr<SkyModel> {
          return std::make_unique<PreethamModel>(p);
        }});
    r.push_back(ModelInfo{
        "cie",
        "ISO 15469 / CIE S 011:2003 Standard General Sky, types 1-15, and 16 = traditional "
        "overcast",
        "luminance Y [cd/m^2]; XYZ at D65 chromaticity (0.3127, 0.3290)",
        {sun_zenith(),
         sun_azimuth(),
         {"cie-type", "1", 1.0, 16.0, "12", "sky type 1-15 (CIE S 011), 16 = (1 + 2 cos Z)/3"},
         {"zenith-luminance", "cd/m^2", 1e-9, 1e9, "Kittler-Darula typical",
          "absolute zenith luminance Lz; default: Kittler & Darula typical value for the type"}},
        "all sun positions above the horizon; the Kittler-Darula typical zenith luminance is "
        "recommended for solar elevations 10-80 deg (flagged extrapolated outside)",
        false,
        false,
        [](const SkyParameters& p) -> std::unique_ptr<SkyModel> {
          return std::make_unique<CieSkyModel>(p);
        }});
    r.push_back(ModelInfo{
        "hosek",
        "Hosek & Wilkie 2012 analytic sky (9-parameter extended Perez form fitted to "
        "simulations; ArHosekSkyModel v1.4a datasets) with the 2013 solar radiance function",
        "XYZ = the CIE XYZ dataset x 683 (Y [cd/m^2]); rgb = the native RGB dataset x 683 (linear "
        "sRGB primaries, same photometric scale); spectral radiance [W m^-2 sr^-1 nm^-1] "
        "320-720 nm; sun disc radius 0.255 deg with limb darkening",
        {sun_zenith(),
         sun_azimuth(),
         {"turbidity", "1", kHwTurbidityMin, kHwTurbidityMax, "3",
          "atmospheric turbidity T (dataset knots 1..10, linear in between)"},
         {"albedo", "1", 0.0, 1.0, "0.3", "ground albedo (dataset knots 0 and 1, linear)"}},
        "turbidity 1-10 and albedo 0-1 (rejected outside: no dataset knots there); sun "
        "elevation 0-90 deg; sun below the horizon: sky and sun 0 (undefined); the fit's slightly "
        "negative values exactly at the horizon with a low sun are returned as 0",
        true,
        true,
        [](const SkyParameters& p) -> std::unique_ptr<SkyModel> {
          return std::make_unique<HosekWilkieModel>(p);
        }});
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
        {sun_zenith(),
         sun_azimuth(),
         {"observer-altitude", "m", 0.0, kNishitaMaxAltitude, "0", "observer above the ground"},
         {"solar-irradiance", "W m^-2 nm^-1", 1e-30, 1e30, "ASTM G-173 spectrum",
          "flat extraterrestrial solar spectral irradiance (1 = per unit irradiance)"},
         {"albedo", "1", 0.0, 1.0, "none (no ground reflection)",
          "Lambertian ground albedo (direct sunlight reflected by the ground)"},
         {"ground-radius", "m", 1.0, 1e9, "6360e3", "planet radius R0"},
         {"top-radius", "m", 1.0, 1e9, "6420e3", "top of the atmosphere (> ground radius)"},
         {"rayleigh-scale-height", "m", 1.0, 1e7, "8000", "Rayleigh scale height H_R"},
         {"mie-scale-height", "m", 1.0, 1e7, "1200", "Mie scale height H_M"},
         {"mie-g", "1", -0.999, 0.999, "0.8", "Cornette-Shanks asymmetry g"},
         {"ozone", "DU", 0.0, 1000.0, "none",
          "ozone column of an absorbing layer at 10-40 km (Bruneton 2017 profile)"}},
        "any observer altitude 0-10000 km, any view direction, sun at any elevation (below the "
        "horizon: single scattering with the planet's shadow, flagged extrapolated); fast path "
        "within 0.5 % of the brute-force reference (tested)",
        true,
        false,
        [](const SkyParameters& p) -> std::unique_ptr<SkyModel> {
          return std::make_unique<NishitaModel>(p);
        }});
    return r;
  }();
  return registry;
}

}  // namespace skylight
