// The loss methods' names (step_loss.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/step_loss.hpp>

namespace lcprelax::learn {

const char* to_string(LossMethod m) {
  switch (m) {
    case LossMethod::hard: return "hard";
    case LossMethod::relaxed: return "relaxed";
    case LossMethod::convex: return "convex";
  }
  return "unknown";
}

LossMethod parse_loss_method(const std::string& s) {
  if (s == "hard") return LossMethod::hard;
  if (s == "relaxed") return LossMethod::relaxed;
  if (s == "convex") return LossMethod::convex;
  throw InputError("--method: unknown method '" + s + "' (expected hard, relaxed or convex)");
}

}  // namespace lcprelax::learn
