// Stick/slip fragility (issue 20, experiment 1): for sticking states of the 1-D block and
// of a square standing on one corner, the smallest perturbation ε of one element of q, or of
// one of M's friction coefficients, that makes Lemke's solution slide (γ > 0), measured by
// a scan and bisection, against the closed forms of docs/structure.md
// (learn/stick_slip_fragility.hpp).
//
//   run_fragility [--csv bench/results/fragility.csv] > bench/results/fragility.txt
//
// CSV: case,perturbation,side,derived,measured,error,slope_derived,slope_measured,solves,
// lemke_failures. side is neg or pos; ±inf means no sliding within |ε| ≤ 10^1·scale
// (measured) or none at all (derived); error is |measured − derived|/|derived| for finite
// nonzero thresholds, |measured|/scale for the zero thresholds, 0 when both are infinite.
// slope: dγ/dε just below 0 on a zero side (derived −½ for q, −z_c/2 for M).
#include <lcprelax/learn/stick_slip_fragility.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

std::vector<StickCase> cases() {
  std::vector<StickCase> out;
  for (const auto& [mu, vs] : std::vector<std::pair<double, double>>{{0.5, 0.2}, {0.5, -0.35}, {0.3, 0.05}, {1.0, 0.9}}) {
    Block1d b;
    b.mass = 1.0, b.mg = 1.0, b.mu = mu;
    out.push_back(block_stick_case(b, vs));
  }
  const double dt = 0.01;
  struct Poly {
    double tilt, vx, vy, w, mu;
  };
  for (const Poly& p : std::vector<Poly>{{0.2, 0.05, -0.5, 0.0, 0.8},
                                         {0.5, -0.02, -1.0, 0.3, 1.0},
                                         {0.35, 0.1, -0.8, -0.5, 0.6},
                                         {0.1, 0.0, -0.3, 0.0, 0.9}}) {
    char name[160];
    std::snprintf(name, sizeof name, "square tilt=%.2f v=(%.2f,%.2f,%.2f) mu=%.2f", p.tilt, p.vx, p.vy, p.w, p.mu);
    Vector v(3);
    v << p.vx, p.vy, p.w;
    out.push_back(polygon_stick_case(square_on_corner(p.tilt, v, p.mu, dt), dt, name));
  }
  return out;
}

double error_of(double derived, double measured, double scale) {
  if (std::isinf(derived) && std::isinf(measured) && (derived > 0) == (measured > 0)) return 0.0;
  if (std::isinf(derived) || std::isinf(measured)) return INFINITY;
  if (derived == 0.0) return std::abs(measured) / scale;
  return std::abs(measured - derived) / std::abs(derived);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Stick/slip fragility of the Stewart–Trinkle LCP: measured against derived thresholds");
  std::string csv_path = "bench/results/fragility.csv";
  app.add_option("--csv", csv_path, "CSV output");
  CLI11_PARSE(app, argc, argv);

  std::ofstream csv(csv_path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csv_path.c_str());
    return 1;
  }
  csv << "case,perturbation,side,derived,measured,error,slope_derived,slope_measured,solves,lemke_failures\n";
  std::printf("Stick/slip fragility: smallest ε that makes Lemke's solution slide (γ > 1e-9·max(1,‖q‖∞)),\n");
  std::printf("scan ±scale·10^(k/4), k = −48..4, then bisection to 1e-10 relative; derived: docs/structure.md.\n\n");
  double worst = 0.0;
  int skipped = 0;
  for (const StickCase& c : cases()) {
    try {
      c.validate();
    } catch (const std::exception& e) {
      std::printf("skipped (not sticking): %s: %s\n\n", c.name.c_str(), e.what());
      ++skipped;
      continue;
    }
    const StickSolution st = stick_solution(c);
    std::printf("%s\n  stick: lambda_n=%.6g lambda_t=%.6g slack=%.6g, scale ‖q‖∞=%.6g\n", c.name.c_str(),
                st.lambda_n, st.lambda_t, st.slack, c.scale);
    std::printf("  %-16s %-4s %14s %14s %10s %10s %10s\n", "perturbation", "side", "derived", "measured", "error",
                "slope_der", "slope_meas");
    for (FragilityPerturbation p : fragility_perturbations(c)) {
      const FragilityThreshold d = derived_threshold(c, p);
      const FragilityMeasurement m = measured_threshold(c, p);
      const double mscale = (p == FragilityPerturbation::M_pair_inactive || p == FragilityPerturbation::M_cone_active ||
                             p == FragilityPerturbation::M_gamma_active)
                                ? c.M.cwiseAbs().maxCoeff()
                                : c.scale;
      for (int s = 0; s < 2; ++s) {
        const double dv = s == 0 ? d.negative : d.positive, mv = s == 0 ? m.threshold.negative : m.threshold.positive;
        // A derived finite threshold beyond the scanned range (10·scale) is not measurable.
        const bool in_range = std::isinf(dv) || std::abs(dv) <= 10.0 * mscale;
        const double err = in_range ? error_of(dv, mv, mscale) : NAN;
        const double sd = s == 0 ? d.slope : NAN, sm = s == 0 ? m.threshold.slope : NAN;
        if (in_range) worst = std::max(worst, err);
        if (!std::isnan(sd)) worst = std::max(worst, std::abs(sm / sd - 1.0));
        std::printf("  %-16s %-4s %14.8g %14.8g %10.2e %10.4g %10.4g%s\n", to_string(p), s == 0 ? "neg" : "pos", dv, mv,
                    err, sd, sm, m.lemke_failures ? "  (some perturbed LCPs unsolvable)" : "");
        char line[512];
        std::snprintf(line, sizeof line, "\"%s\",%s,%s,%.12g,%.12g,%.3e,%.6g,%.6g,%d,%d\n", c.name.c_str(), to_string(p),
                      s == 0 ? "neg" : "pos", dv, mv, err, sd, sm, m.solves, m.lemke_failures);
        csv << line;
      }
    }
    std::printf("\n");
  }
  std::printf("worst error over measurable thresholds and slopes: %.3e (%d cases skipped)\n\n", worst, skipped);

  // The square lying flat (two contacts, W singular): one friction row of q perturbed.
  Vector v(3);
  v << 0.05, -0.5, 0.0;
  const PolygonContactData flat = square_flat(v, 0.8, 0.01);
  std::printf("square lying flat, v=(0.05,-0.50,0.00) mu=0.80: one friction row's q += ε, γ per contact\n");
  std::printf("  %-5s %10s %14s %14s\n", "row", "ε", "γ0/(−ε/2)", "γ1/(−ε/2)");
  const char* names[] = {"β⁺0", "β⁺1", "β⁻0", "β⁻1"};
  for (Index row = 2; row < 6; ++row)
    for (double eps : {-1e-7, -1e-2, 1e-2}) {
      const Vector g = polygon_sliding_speeds(flat, 0.01, row, eps);
      std::printf("  %-5s %10.0e %14.6g %14.6g\n", names[row - 2], eps, g(0) / (-0.5 * eps), g(1) / (-0.5 * eps));
    }
  return 0;
}
