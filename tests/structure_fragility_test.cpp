// Stick/slip fragility (learn/stick_slip_fragility.hpp, docs/structure.md): the thresholds
// derived from the LCP's complementarity conditions agree with Lemke's solutions of the
// perturbed LCPs to 1 %, for the 1-D block and a square standing on one corner.
//
// What a wrong derivation would break: the finite thresholds (the friction-cone slack −s⁰ on
// q_γ, s⁰/|λt| on the cone row's coefficient, the stick path's root for q_pair, q_active,
// q_normal) are compared relatively; the zero thresholds (one friction row's q, or the
// antisymmetry of the two friction rows broken in M) by |measured| ≤ 1e-6·scale and the
// sliding speed γ = −ε/2 (q) or −ε·z_c/2 (M) just below 0, to 1 %. A square lying flat
// (two contacts, W singular) gets the bound γ ≥ −ε/2 of the same argument.
#include <lcprelax/learn/stick_slip_fragility.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

StickCase block_case(double mu, double v_star) {
  Block1d b;
  b.mass = 1.0, b.mg = 1.0, b.mu = mu;
  return block_stick_case(b, v_star);
}

StickCase square_case(double tilt, double vx, double vy, double w, double mu) {
  Vector v(3);
  v << vx, vy, w;
  return polygon_stick_case(square_on_corner(tilt, v, mu, 0.01), 0.01, "square");
}

void expect_threshold(double derived, double measured, double scale, const std::string& what) {
  if (std::isinf(derived)) {
    EXPECT_TRUE(std::isinf(measured) && (measured > 0) == (derived > 0)) << what << ": measured " << measured;
  } else if (derived == 0.0) {
    EXPECT_LE(std::abs(measured), 1e-6 * scale) << what;
  } else {
    EXPECT_NEAR(measured, derived, 0.01 * std::abs(derived)) << what;
  }
}

void check_case(const StickCase& c) {
  ASSERT_NO_THROW(c.validate()) << c.name;
  for (FragilityPerturbation p : fragility_perturbations(c)) {
    const FragilityThreshold d = derived_threshold(c, p);
    const FragilityMeasurement m = measured_threshold(c, p);
    const bool matrix = p == FragilityPerturbation::M_pair_inactive || p == FragilityPerturbation::M_cone_active ||
                        p == FragilityPerturbation::M_gamma_active;
    const double scale = matrix ? c.M.cwiseAbs().maxCoeff() : c.scale;
    const std::string what = c.name + " " + to_string(p);
    // Only thresholds within the scanned range (10·scale) are measurable.
    if (std::isinf(d.negative) || std::abs(d.negative) <= 10.0 * scale)
      expect_threshold(d.negative, m.threshold.negative, scale, what + " (ε < 0)");
    if (std::isinf(d.positive) || d.positive <= 10.0 * scale)
      expect_threshold(d.positive, m.threshold.positive, scale, what + " (ε > 0)");
    if (!std::isnan(d.slope)) {
      EXPECT_NEAR(m.threshold.slope, d.slope, 0.01 * std::abs(d.slope)) << what << " slope";
    }
  }
}

TEST(StructureFragility, BlockClosedForms) {
  // v* = 0.2, μmg = 0.5, m = 1: slack s⁰ = 0.3, λt = −0.2.
  const StickCase c = block_case(0.5, 0.2);
  const StickSolution st = stick_solution(c);
  EXPECT_NEAR(st.slack, 0.3, 1e-12);
  EXPECT_NEAR(st.lambda_t, -0.2, 1e-12);
  // q_pair moves v*: slides at v* + ε = ±μg, i.e. ε = 0.3 and −0.7.
  const FragilityThreshold pair = derived_threshold(c, FragilityPerturbation::q_pair);
  EXPECT_NEAR(pair.positive, 0.3, 1e-12);
  EXPECT_NEAR(pair.negative, -0.7, 1e-12);
  EXPECT_NEAR(derived_threshold(c, FragilityPerturbation::q_cone).negative, -0.3, 1e-12);
  EXPECT_NEAR(derived_threshold(c, FragilityPerturbation::M_cone_active).negative, -1.5, 1e-12);
  EXPECT_EQ(derived_threshold(c, FragilityPerturbation::q_inactive).negative, 0.0);
}

TEST(StructureFragility, BlockMeasuredMatchesDerived) {
  check_case(block_case(0.5, 0.2));
  check_case(block_case(0.5, -0.35));
  check_case(block_case(1.0, 0.9));
}

TEST(StructureFragility, SquareOnCornerMeasuredMatchesDerived) {
  check_case(square_case(0.2, 0.05, -0.5, 0.0, 0.8));
  check_case(square_case(0.5, -0.02, -1.0, 0.3, 1.0));
}

TEST(StructureFragility, OneElementBreaksStickingAtAnyNegativeSize) {
  // The claim: ε = −1e-9·‖q‖∞ on one friction row's q already gives γ = −ε/2 > 0.
  for (const StickCase& c : {block_case(0.5, 0.2), square_case(0.2, 0.05, -0.5, 0.0, 0.8)}) {
    const double eps = -1e-7 * c.scale;
    for (FragilityPerturbation p : {FragilityPerturbation::q_active, FragilityPerturbation::q_inactive}) {
      EXPECT_NEAR(measured_sliding_speed(c, p, eps), -0.5 * eps, 0.01 * 0.5 * std::abs(eps)) << c.name << to_string(p);
      EXPECT_LE(measured_sliding_speed(c, p, -eps), 1e-12) << c.name << to_string(p);
    }
    // The same ε on both rows, antisymmetrically (a change of v*), keeps it sticking.
    EXPECT_LE(measured_sliding_speed(c, FragilityPerturbation::q_pair, eps), 1e-12) << c.name;
  }
}

TEST(StructureFragility, FlatSquareTwoContacts) {
  // Two contacts with the same Jt row (W singular): one friction row of q perturbed by
  // ε < 0 forces γ ≥ −ε/2 at its contact (w⁺ + w⁻ = 2γ + ε); measured: γ = −ε at that contact
  // when the other contact holds the body (only one of its β positive), or −ε/2 at both
  // when the body drifts. ε > 0 leaves both sticking.
  Vector v(3);
  v << 0.05, -0.5, 0.0;
  const PolygonContactData d = square_flat(v, 0.8, 0.01);
  ASSERT_TRUE(polygon_sliding_speeds(d, 0.01, 2, 0.0).cwiseAbs().maxCoeff() <= 1e-12);
  for (Index row = 2; row < 6; ++row) {  // β⁺₀, β⁺₁, β⁻₀, β⁻₁
    const Index contact = row % 2;
    for (double eps : {-1e-7, -1e-4, -1e-2}) {
      const Vector g = polygon_sliding_speeds(d, 0.01, row, eps);
      ASSERT_FALSE(std::isnan(g(0))) << row;
      EXPECT_GE(g(contact), -0.5 * eps * (1 - 1e-6)) << "row " << row << " eps " << eps;
      EXPECT_LE(g(contact), -eps * (1 + 1e-6)) << "row " << row << " eps " << eps;
    }
    for (double eps : {1e-7, 1e-4, 1e-2})
      EXPECT_LE(polygon_sliding_speeds(d, 0.01, row, eps).cwiseAbs().maxCoeff(), 1e-12) << row;
  }
}

}  // namespace
