// The brief report of the learn commands (learn_report.hpp).
#include "learn_report.hpp"

#include <cmath>

namespace lcprelax::cli {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

double number_in(const Json& object, const std::string& key) {
  if (!object.is_object()) return std::nan("");
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : std::nan("");
}

}  // namespace

void add_training_status(BriefReport& r, const Json& j, bool failed) {
  const int epochs = j["epochs"].get<int>();
  const std::string status = failed                         ? "failed"
                             : epochs == 0                  ? "evaluated"
                             : j["converged"].get<bool>()   ? "converged"
                                                            : "not converged";
  r.add("status", status);
  r.add("stop reason", epochs == 0 ? std::string("--epochs 0: loss evaluated, nothing trained")
                                   : j["stop_reason"].get<std::string>());
}

void add_parameter_lines(BriefReport& r, const Json& j, std::string (*unit_of)(const std::string& name)) {
  const Json& errors = j.contains("relative_error") ? j["relative_error"] : Json();
  for (const auto& [name, value] : j["learned"].items()) {
    const double learned = value.is_number() ? value.get<double>() : std::nan("");
    std::string note = "(initial " + format_number(number_in(j["initial"], name));
    const double truth = number_in(j["true"], name);
    if (std::isfinite(truth)) note += ", true " + format_number(truth);
    if (errors.is_object() && errors.contains(name))
      note += ", relative error " + format_number(number_in(errors, name), 3);
    note += ")";
    const std::string unit = unit_of(name);
    r.add(name, format_number(learned) + (unit.empty() || !std::isfinite(learned) ? "" : " " + unit), note);
  }
}

void add_training_effort(BriefReport& r, const Json& j, int epochs_cap) {
  r.add("epochs", std::to_string(j["epochs"].get<int>()) + " of at most " + std::to_string(epochs_cap));
  r.add("time", j["seconds"].is_number() ? j["seconds"].get<double>() : std::nan(""), "s", 3);
}

std::string parameter_unit(const std::string& name) {
  if (ends_with(name, "inertia")) return "kg·m²";
  if (ends_with(name, "mass")) return "kg";
  if (name == "mg") return "N·s";
  if (ends_with(name, "angle")) return "rad";
  if (ends_with(name, ".x") || ends_with(name, ".y") || ends_with(name, "height") || ends_with(name, "offset") ||
      ends_with(name, ".gap"))
    return "m";
  return "";
}

}  // namespace lcprelax::cli
