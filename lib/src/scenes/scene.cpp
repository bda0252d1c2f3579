// ContactModel text form and SimulationSettings validation (scenes/scene.hpp).
#include <lcprelax/scenes/scene.hpp>
#include <lcprelax/sparse/errors.hpp>

#include <cmath>
#include <string>

namespace lcprelax {

ContactModel parse_contact_model(std::string_view text) {
  for (ContactModel m : {ContactModel::lcp, ContactModel::convex})
    if (text == to_string(m)) return m;
  throw InputError("unknown contact model '" + std::string(text) + "' (expected lcp or convex)");
}

void check_settings(const SimulationSettings& s) {
  if (!std::isfinite(s.dt) || !(s.dt > 0.0)) throw InputError("dt: must be finite and > 0");
  if (!std::isfinite(s.margin) || !(s.margin >= 0.0))
    throw InputError("margin: must be finite and >= 0");
  if (s.steps < 0) throw InputError("steps: must be >= 0");
  if (s.model != ContactModel::lcp && s.model != ContactModel::convex)
    throw InputError("model: unknown contact model");
}

}  // namespace lcprelax
