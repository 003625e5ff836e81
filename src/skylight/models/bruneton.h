// The `bruneton` sky model: precomputed multiple scattering after Bruneton & Neyret 2008 and
// Bruneton 2017 ("A Qualitative and Quantitative Evaluation of 8 Clear Sky Models", and its
// reference implementation), in `nishita`'s atmosphere (atmosphere.h) with `nishita`'s parameters
// and `--scattering-orders N`. The view sees L_1 (exactly, as nishita: integrated along each view
// ray, within 0.2 % of the brute force) plus the orders 2 .. N of the precomputed tables (by
// default 6 and the geometric remainder of the orders above: atmosphere::kConvergedOrders)
// (atmosphere/scattering_orders.h, where the equations and the differences from Bruneton 2017
// are), held per observer and sun in the sky-view LUT of physical_sky.h (Hillaire 2020), not in a
// 4D table lookup per pixel.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "skylight/atmosphere/scattering_orders.h"
#include "skylight/models/physical_sky.h"

namespace skylight {

inline constexpr int kMaxScatteringOrders = 10;

// `nishita`'s parameters, with the ozone layer on by default (OzoneLayerParameters), and the
// number of scattering orders (none: converged, atmosphere::kConvergedOrders).
struct BrunetonParameters : OzoneLayerParameters {
  std::optional<int> scattering_orders;
  atmosphere::OrderSettings orders() const {
    return scattering_orders ? atmosphere::OrderSettings::exactly(*scattering_orders)
                             : atmosphere::kConvergedOrders;
  }
  static const ParameterSchema<BrunetonParameters>& schema();
};

class BrunetonModel final : public PhysicalSkyModel {
 public:
  explicit BrunetonModel(const BrunetonParameters& params);
  static constexpr std::string_view kName = "bruneton";
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Domain domain() const override;

  // Orders 2 .. N (and the remainder) along the view ray: the ray integral of T (J_2 + ... + J_N)
  // and the ground's reflection of E_1 + ... + E_{N-1} (0 for N = 1).
  void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                           const std::vector<LutWeight>& weights,
                           std::span<double> out) const override;
  // The tables (null for --scattering-orders 1).
  const atmosphere::ScatteringOrderTables* tables() const { return tables_.get(); }

 private:
  BrunetonParameters params_;
  std::shared_ptr<const atmosphere::ScatteringOrderTables> tables_;
};

}  // namespace skylight
