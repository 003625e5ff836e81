// An XYZ quadrature on a few spectral samples (docs/ATMOSPHERE.md, "Spectral sampling"): for a
// spectrum S = E g with E known and tabulated finely (the extraterrestrial solar irradiance) and g
// smooth (what the atmosphere does to it), the integrals of S times the CIE 1931 CMFs from a few
// samples S(lambda_k), far closer than the CMFs at the samples times their spacing.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "skylight/core/colorimetry.h"

namespace skylight {

// Weights w_k with integral_{nodes.front()}^{nodes.back()} S(l) cmf(l) dl ~= sum_k w_k S(l_k): the
// CMFs times E integrated at 1 nm (trapezoid; the CMF table's own step) against the natural cubic
// spline of g = S / E through its node values (so w_k = integral cmf E phi_k / E(l_k), phi_k the
// spline's cardinal function of node k). Exact for g linear in wavelength. Nodes ascending, at
// least 3; E(l_k) > 0. A weight may be slightly negative (the spline's lobes where a CMF ends).
std::vector<Cmf> spline_xyz_weights(std::span<const double> nodes_nm,
                                    const std::function<double(double nm)>& e);

// K_m sum_k w_k S_k: XYZ with Y in cd/m^2 of spectral radiances S_k [W m^-2 sr^-1 nm^-1]. A sum
// below 0 (a spectrum all at the end of a CMF, met by a negative weight) is 0: a non-negative
// spectrum gives a non-negative XYZ.
Xyz weighted_xyz(std::span<const Cmf> weights, std::span<const double> radiance);

}  // namespace skylight
