#pragma once
// The brief human-readable report of the learn commands (docs/cli.md, "Human output";
// cli_report.hpp for the layout), made from the same JSON object that --json prints, so
// that both outputs always agree:
//
//   status           converged
//   stop reason      converged: relative loss change <= 1e-09 and gradient norm <= 1e-07 for 5 epochs
//   method           relaxed
//   mu               0.100146  (initial 1, true 0.1)
//   final loss       5.43966e-05  (mean over the training samples)
//   epochs           278
//   time             0.97 s
//
// status: "failed" when the run's solves failed (exit 1), "evaluated" with --epochs 0,
// else "converged" or "not converged" (the trainer's convergence test, trainer.hpp). One
// line per learned parameter: learned value, initial value, true value (when known) and,
// when the JSON has it, the relative error.
#include "cli_common.hpp"
#include "cli_report.hpp"

#include <string>

namespace lcprelax::cli {

/// Adds the status line (first) and the stop reason of a learn run's JSON `j` (keys epochs,
/// stop_reason, converged of add_train_outcome); `failed` is whether the run exits with 1.
void add_training_status(BriefReport& r, const Json& j, bool failed);

/// Adds one line per entry of j["learned"]: the value, then in brackets j["initial"]'s,
/// j["true"]'s (when a number) and j["relative_error"]'s (when present). `unit_of` names a
/// parameter's unit (may return "").
void add_parameter_lines(BriefReport& r, const Json& j, std::string (*unit_of)(const std::string& name));

/// Adds "epochs" (run, and the cap) and "time" (s) from j["epochs"] and j["seconds"].
void add_training_effort(BriefReport& r, const Json& j, int epochs_cap);

/// The unit of a parameter named as in the learn commands' JSON ("mu", "mass",
/// "class0.inertia", "vertex2.x", "ground_angle", "class1.gap", ...): "kg", "kg·m²", "m",
/// "rad", "N·s" or "" (dimensionless, or a residual entry whose unit depends on its column).
std::string parameter_unit(const std::string& name);

}  // namespace lcprelax::cli
