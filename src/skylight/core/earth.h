// Earth's size and its air's Rayleigh scale height, the planet every default of the library
// describes: the physical atmosphere's (atmosphere/parameters.h) and the Pietras networks' inputs
// (nn/pietras.h). Bruneton 2017's demo values (docs/MODELS.md, `nishita`).
#pragma once

namespace skylight {

inline constexpr double kEarthGroundRadius = 6360e3;  // R0 [m]
inline constexpr double kEarthTopRadius = 6420e3;     // top of the atmosphere [m]
inline constexpr double kEarthAtmosphereHeight = kEarthTopRadius - kEarthGroundRadius;  // [m]
inline constexpr double kRayleighScaleHeight = 8000;  // H of the air's density exp(-h / H) [m]

}  // namespace skylight
