#pragma once
// The validity rule of a normal softness (FrictionTable in world.hpp; the lcp model's
// implicit spring–damper in CFM/ERP form, models/contact_system.hpp): a compliance c in 1/kg,
// finite and ≥ 0, and an erp e in [0, 1]. One rule for every place that takes them (the
// Simulator's friction table, a ContactSystem's per-contact vectors, data settings).
#include <cmath>
#include <string>

namespace lcprelax {

/// Empty when (compliance, erp) are valid, else "compliance: must be finite and >= 0" or
/// "erp: must be in [0, 1]" (callers prefix where the values came from).
inline std::string normal_softness_value_error(double compliance, double erp) {
  if (!(std::isfinite(compliance) && compliance >= 0.0)) return "compliance: must be finite and >= 0";
  if (!(erp >= 0.0 && erp <= 1.0)) return "erp: must be in [0, 1]";
  return {};
}

}  // namespace lcprelax
