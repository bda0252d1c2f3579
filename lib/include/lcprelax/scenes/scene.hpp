#pragma once
// A simulation scene: the world (models/world.hpp) plus the time-stepping settings that a
// scene file carries (DESIGN §3). SI units: seconds, metres.
//
// Conventions:
// - `dt` > 0 is the time step (s); `steps` ≥ 0 the number of steps to simulate.
// - `margin` ≥ 0 (m): contacts whose gap φ exceeds the margin enter no contact problem.
// - `model` picks the contact model: `lcp` (Stewart–Trinkle/Anitescu velocity-level LCP,
//   solved by Lemke) or `convex` (the two-phase convex model, solved by the interior-point
//   QP); DESIGN §1.4.
#include <lcprelax/models/world.hpp>

#include <string>
#include <string_view>

namespace lcprelax {

/// The contact model a scene is simulated with.
enum class ContactModel { lcp, convex };

/// "lcp" or "convex".
constexpr const char* to_string(ContactModel m) {
  switch (m) {
    case ContactModel::lcp: return "lcp";
    case ContactModel::convex: return "convex";
  }
  return "unknown";
}

/// Inverse of to_string; throws InputError "unknown contact model 'x' (expected lcp or
/// convex)" for any other text (case-sensitive).
ContactModel parse_contact_model(std::string_view text);

struct SimulationSettings {
  double dt = 1e-2;                   ///< time step (s), > 0 and finite
  ContactModel model = ContactModel::lcp;  ///< contact model
  double margin = 1e-2;               ///< contact margin (m), ≥ 0 and finite
  int steps = 100;                    ///< number of steps to simulate, ≥ 0
};

/// Throws InputError naming the field ("dt: must be > 0", ...) if the settings are invalid.
void check_settings(const SimulationSettings& settings);

struct Scene {
  World world;
  SimulationSettings settings;
  std::string name;  ///< free text, may be empty
};

}  // namespace lcprelax
