// Normal softening methods of the convex model (models/normal_softening.hpp) on the
// learning path (learn/step_loss_convex.hpp): for each of exp_phi, linear_penalty and
// mujoco_impedance,
//   - the per-contact terms' derivatives g′(φ), ∂v_ref/∂φ, ∂v_ref/∂vn against central
//     differences (away from the kinks at φ = 0 and |φ| = width);
//   - with w = 0 the loss's forward is solve_convex_model with the same softening;
//   - ∂ℓ/∂(φ, Jn, Jt, μ, M⁻¹, v*) against central differences of ℓ, in the dual and the
//     lifted formulation, on a box resting with a small overlap and on two stacked boxes
//     (overlapping and separated contacts, so that the penalty's push-out is active).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/normal_softening.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace lcprelax::learn {
namespace {

constexpr double kDt = 1e-2;
constexpr NormalSoftening kMethods[] = {NormalSoftening::exp_phi, NormalSoftening::linear_penalty,
                                        NormalSoftening::mujoco_impedance};

NormalSofteningSettings softening(NormalSoftening m) {
  NormalSofteningSettings o;
  o.method = m;
  o.width = 0.01;  // wider than the test gaps, so that d(φ) varies at every contact
  o.time_constant = 0.05;
  return o;
}

// `count` boxes of side 0.5 m stacked on the ground (slightly tilted, moving), with the
// gaps set to `gaps` (one per contact, m; some negative: overlapping).
ContactSystem stack(int count, const std::vector<Vec3>& v, const std::vector<double>& gaps) {
  Scene scene = make_box_stack_scene(count, 0.5, 0.5);
  for (int k = 0; k < count; ++k) {
    RigidBody& b = scene.world.bodies[static_cast<std::size_t>(k)];
    b.pose(2) += 0.004 * (k % 2 == 0 ? 1.0 : -1.0);
    b.velocity = v[static_cast<std::size_t>(k)];
  }
  SimulatorSettings settings;
  settings.dt = kDt;
  const StepContacts sc = find_step_contacts(scene.world, settings);
  EXPECT_EQ(sc.islands.size(), 1u);
  ContactSystem s = assemble_contact_system(scene.world, sc.contacts, sc.islands[0], settings.dt);
  s.Jn.makeCompressed();
  s.Jt.makeCompressed();
  for (Index i = 0; i < s.num_contacts(); ++i) s.phi(i) = gaps[static_cast<std::size_t>(i) % gaps.size()];
  return s;
}

struct Island {
  std::string name;
  ContactSystem s;
};

std::vector<Island> islands() {
  return {{"box overlapping", stack(1, {Vec3(0.4, -0.2, 0.05)}, {-2.0e-3, -1.3e-3})},
          {"box overlapping, slow", stack(1, {Vec3(0.1, -0.2, 0.05)}, {-2.0e-3, -1.3e-3})},
          {"two boxes", stack(2, {Vec3(0.01, -0.1, 0.02), Vec3(-0.02, -0.3, -0.03)}, {-1.7e-3, 2.1e-3, -0.6e-3, 1.1e-3})}};
}

ConvexStepLossSettings loss_settings(NormalSoftening m, ConvexFormulation form, double w) {
  ConvexStepLossSettings s;
  s.qp.eps_abs = 1e-12;
  s.formulation = form;
  s.deviation = w;
  s.rho = 1e-2;
  s.softening = softening(m);
  return s;
}

Vector noisy(const Vector& v, double scale, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector out = v;
  for (Index i = 0; i < out.size(); ++i) out(i) += scale * u(rng);
  return out;
}

TEST(NormalSoftening, TermDerivativesMatchCentralDifferences) {
  const Vector phi = (Vector(4) << -7e-3, -2e-3, 3e-3, 0.02).finished();
  const Vector vn = (Vector(4) << -0.3, 0.1, -0.05, -1.0).finished();
  for (NormalSoftening m : kMethods) {
    const NormalSofteningSettings o = softening(m);
    ASSERT_EQ(o.validation_error(), "");
    const NormalSofteningTerms t = normal_softening_terms(o, 1e-2, kDt, phi, vn);
    for (Index i = 0; i < phi.size(); ++i) {
      const double h = 1e-7;
      Vector pp = phi, pm = phi;
      pp(i) += h, pm(i) -= h;
      const NormalSofteningTerms tp = normal_softening_terms(o, 1e-2, kDt, pp, vn);
      const NormalSofteningTerms tm = normal_softening_terms(o, 1e-2, kDt, pm, vn);
      const double dg = (tp.g(i) - tm.g(i)) / (2 * h), dv = (tp.v_ref(i) - tm.v_ref(i)) / (2 * h);
      EXPECT_NEAR(t.dg_dphi(i), dg, 1e-6 * std::max(1.0, std::abs(dg))) << to_string(m) << " g′ at " << i;
      EXPECT_NEAR(t.dvref_dphi(i), dv, 1e-6 * std::max(1.0, std::abs(dv))) << to_string(m) << " v_ref′ at " << i;
      Vector vp = vn, vm = vn;
      vp(i) += h, vm(i) -= h;
      const double dvn = (normal_softening_terms(o, 1e-2, kDt, phi, vp).v_ref(i) -
                          normal_softening_terms(o, 1e-2, kDt, phi, vm).v_ref(i)) / (2 * h);
      EXPECT_NEAR(t.dvref_dvn(i), dvn, 1e-6) << to_string(m);
      EXPECT_GT(t.g(i), 0.0) << to_string(m);
    }
  }
}

TEST(NormalSoftening, ExpPhiIsTheDefaultAndNamesParse) {
  EXPECT_EQ(NormalSofteningSettings{}.method, NormalSoftening::exp_phi);
  EXPECT_EQ(ConvexStepLossSettings{}.softening.method, NormalSoftening::exp_phi);
  EXPECT_EQ(SimulatorSettings{}.convex_softening.method, NormalSoftening::exp_phi);
  for (NormalSoftening m : kMethods) EXPECT_EQ(parse_normal_softening(to_string(m)), m);
  EXPECT_EQ(parse_normal_softening("impedance"), NormalSoftening::mujoco_impedance);
  EXPECT_THROW(parse_normal_softening("soft"), InputError);
  NormalSofteningSettings bad;
  bad.d0 = 1.0;
  EXPECT_NE(bad.validation_error().find("d0"), std::string::npos);
  ConvexStepLossSettings ls;
  ls.softening.width = -1.0;
  EXPECT_NE(ls.validation_error().find("softening.width"), std::string::npos);
}

TEST(NormalSoftening, ZeroDeviationForwardIsTheConvexModel) {
  for (const Island& is : islands())
    for (NormalSoftening m : kMethods)
      for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
        ConvexStepLossSettings settings = loss_settings(m, form, 0.0);
        settings.qp.eps_abs = 1e-10;
        settings.phase1_regularization = 0.0;
        const Vector target = noisy(is.s.v_star, 0.1, 3);
        const StepLossResult r = convex_step_loss(is.s, target, kDt, settings);
        const ContactSolution c = solve_convex_model(is.s, kDt, settings.qp, settings.rho, form, settings.softening);
        ASSERT_TRUE(has_solution(r.status)) << is.name << " " << to_string(m) << ": " << r.message;
        ASSERT_TRUE(has_solution(c.status)) << is.name << " " << to_string(m) << ": " << c.message;
        EXPECT_LE((r.v_next - c.v_next).lpNorm<Eigen::Infinity>(), 1e-7) << is.name << " " << to_string(m);
      }
}

// Central differences of ℓ against every entry of the cotangent: |fd − an| ≤ 1e-5·den with
// den = max(|an|, 1e-3·max|an of the kind|, 1e-4) (measured worst: 2.8e-6; a wrong term in
// the chain rule is off by O(1)).
void check_gradient(const ContactSystem& s0, const Vector& target, const ConvexStepLossSettings& settings,
                    const std::string& label) {
  const StepLossResult r0 = convex_step_loss(s0, target, kDt, settings);
  ASSERT_TRUE(has_solution(r0.status)) << label << ": " << r0.message;
  struct View {
    const char* name;
    double* (*data)(ContactSystem&);
    const double* grad;
    Index n;
  };
  ContactSystem s = s0;
  const std::vector<View> views = {
      {"phi", [](ContactSystem& x) { return x.phi.data(); }, r0.grad.phi.data(), s.num_contacts()},
      {"Jn", [](ContactSystem& x) { return x.Jn.valuePtr(); }, r0.grad.Jn.valuePtr(), static_cast<Index>(s.Jn.nonZeros())},
      {"Jt", [](ContactSystem& x) { return x.Jt.valuePtr(); }, r0.grad.Jt.valuePtr(), static_cast<Index>(s.Jt.nonZeros())},
      {"mu", [](ContactSystem& x) { return x.mu.data(); }, r0.grad.mu.data(), s.num_friction()},
      {"minv", [](ContactSystem& x) { return x.minv.data(); }, r0.grad.minv.data(), s.num_dofs()},
      {"v_star", [](ContactSystem& x) { return x.v_star.data(); }, r0.grad.v_star.data(), s.num_dofs()}};
  for (const View& v : views) {
    double scale = 0.0;
    for (Index i = 0; i < v.n; ++i) scale = std::max(scale, std::abs(v.grad[i]));
    double worst = 0.0;
    for (Index i = 0; i < v.n; ++i) {
      double* x = v.data(s) + i;
      const double x0 = *x, h = 1e-6 * std::max(1.0, std::abs(x0));
      *x = x0 + h;
      const StepLossResult rp = convex_step_loss(s, target, kDt, settings);
      *x = x0 - h;
      const StepLossResult rm = convex_step_loss(s, target, kDt, settings);
      *x = x0;
      ASSERT_TRUE(has_solution(rp.status) && has_solution(rm.status)) << label << " " << v.name << i;
      const double fd = (rp.loss - rm.loss) / (2 * h);
      const double den = std::max({std::abs(v.grad[i]), 1e-3 * scale, 1e-4});
      worst = std::max(worst, std::abs(fd - v.grad[i]) / den);
      EXPECT_NEAR(v.grad[i], fd, 1e-5 * den) << label << " " << v.name << "[" << i << "] (scale " << scale << ")";
    }
    std::printf("%-44s %-6s max|grad| %.3e, worst rel. error %.2e\n", label.c_str(), v.name, scale, worst);
  }
}

TEST(NormalSoftening, LossGradientMatchesCentralDifferences) {
  for (const Island& is : islands())
    for (NormalSoftening m : kMethods)
      for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
        const ConvexStepLossSettings settings = loss_settings(m, form, 1.0);
        const StepLossResult r = convex_step_loss(is.s, is.s.v_star, kDt, settings);
        ASSERT_TRUE(has_solution(r.status)) << r.message;
        const Vector target = noisy(r.v_next, 0.05, 7);
        check_gradient(is.s, target, settings,
                       is.name + " " + to_string(m) + (form == ConvexFormulation::dual ? " dual" : " lifted"));
      }
}

TEST(NormalSoftening, MethodsDifferWherePenetrating) {
  // The penalty and MuJoCo's reference velocity push an overlapping contact out (within
  // phase 1's budget κ); exp_phi never asks for a separating velocity.
  const Island is = islands()[0];
  std::vector<Vector> v;
  for (NormalSoftening m : kMethods) {
    const ContactSolution c = solve_convex_model(is.s, kDt, QpSettings{}, 1e-2, ConvexFormulation::dual, softening(m));
    ASSERT_TRUE(has_solution(c.status)) << to_string(m) << ": " << c.message;
    v.push_back(c.v_next);
  }
  EXPECT_GT((v[1] - v[0]).norm(), 1e-6);
  EXPECT_GT((v[2] - v[0]).norm(), 1e-6);
}

}  // namespace
}  // namespace lcprelax::learn
