// Per-material-pair normal softness of the lcp model (FrictionTable compliance c and erp e,
// world.hpp) and its learning on the scene path (flag softness, learn/scene_params.hpp):
// - stewart_trinkle_lcp puts c on the normal diagonal and e·min(φ, 0)/Δt in q; rigid values
//   leave the LCP bit for bit as before;
// - the spring–damper reading: a box overlapping the ground by m g/k (k = e/(cΔt²)) is held
//   at rest by one step's LCP, and per-pair values reach the contacts of that pair only;
// - scene JSON: read, written back, bad values named;
// - layout: "compliance", "erp" after everything else, per listed pair with mu_per_pair;
//   apply/parameters round trip; the bounds (c ≥ 0, e in [0, 1]) clamp;
// - ∂ℓ/∂(c, e) of the hard, relaxed and convex losses against central differences of the
//   whole pipeline on steps of a small generated pile;
// - the convex model: c on phase 2's λn diagonal and the push-out in v_ref, so that a lone
//   sliding-free contact's stationarity reads Jn v⁺ + e·min(φ,0)/Δt + c·λn = −g Wnn λn;
//   the convex Simulator runs a soft scene; zero softness leaves its answer bit for bit;
// - refusals: the relaxed-dual loss, the polygon flags, bad values.
#include "learn_scene_fd_support.hpp"
#include "learn_scene_pile_support.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/polygon_params.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>
#include <lcprelax/learn/step_loss_relaxed.hpp>
#include <lcprelax/learn/step_loss_relaxed_dual.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/scene_json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax::learn {
namespace {

using test::parameters_named;

SceneParameterSettings learn(const std::string& flags, bool per_pair = false) {
  SceneParameterSettings ps;
  ps.learn = parse_scene_learn_flags(flags);
  ps.mu_per_pair = per_pair;
  return ps;
}

// A unit box (m = 1 kg) on the ground y ≥ 0, its bottom at y = bottom, at rest.
World box_on_ground(double bottom) {
  World w;
  RigidBody b;
  b.shape.vertices = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)};
  b.mass = 1.0;
  b.inertia = 1.0 / 6.0;
  b.pose = Vec3(0.0, 0.5 + bottom, 0.0);
  w.bodies.push_back(b);
  w.half_planes.push_back(HalfPlane{});
  w.friction.default_mu = 0.5;
  return w;
}

TEST(SceneSoftness, LcpTakesComplianceOnTheNormalDiagonalAndErpInQ) {
  const double dt = 0.01;
  World w = box_on_ground(-0.002);  // both corners 2 mm deep
  const SimulatorSettings settings;
  const StepContacts rigid_found = find_step_contacts(w, settings);
  ASSERT_EQ(rigid_found.contacts.size(), 2u);
  const ContactSystem s0 = assemble_contact_system(w, rigid_found.contacts, rigid_found.islands[0], dt);
  const StewartTrinkleLcp l0 = stewart_trinkle_lcp(s0, delassus(s0), dt);
  w.friction.default_compliance = 0.3;
  w.friction.default_erp = 0.25;
  const StepContacts found = find_step_contacts(w, settings);
  for (const Contact& c : found.contacts) {
    EXPECT_EQ(c.compliance, 0.3);
    EXPECT_EQ(c.erp, 0.25);
  }
  const ContactSystem s1 = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  EXPECT_TRUE(has_normal_softness(s1));
  EXPECT_FALSE(has_normal_softness(s0));
  const StewartTrinkleLcp l1 = stewart_trinkle_lcp(s1, delassus(s1), dt);
  const DenseMatrix dM = DenseMatrix(l1.M) - DenseMatrix(l0.M);
  const Vector dq = l1.q - l0.q;
  for (Index i = 0; i < dM.rows(); ++i)
    for (Index j = 0; j < dM.cols(); ++j)
      EXPECT_NEAR(dM(i, j), i == j && i < 2 ? 0.3 : 0.0, 1e-15) << "(" << i << ", " << j << ")";
  for (Index i = 0; i < dq.size(); ++i)
    EXPECT_NEAR(dq(i), i < 2 ? 0.25 * s1.phi(i) / dt : 0.0, 1e-15) << "q(" << i << ")";
  EXPECT_LT(s1.phi(0), 0.0);
  // A positive gap keeps the rigid term: normal_gap_rate = φ/Δt there.
  ContactSystem apart = s1;
  apart.phi.setConstant(0.001);
  EXPECT_EQ(normal_gap_rate(apart, dt), Vector::Constant(2, 0.1));
  // Bad values are named.
  ContactSystem bad = s1;
  bad.erp(0) = 1.5;
  EXPECT_THROW(stewart_trinkle_lcp(bad, delassus(bad), dt), InputError);
  bad = s1;
  bad.compliance(1) = -1.0;
  EXPECT_THROW(stewart_trinkle_lcp(bad, delassus(bad), dt), InputError);
}

TEST(SceneSoftness, AnOverlapOfWeightOverStiffnessIsHeldAtRest) {
  // Per contact k = e/(c Δt²), d = (1 − e)/(c Δt); the box rests on two contacts (2k, 2d),
  // so its weight m g needs an overlap of m g/(2k).
  const double dt = 0.01, c = 2.0, e = 0.5, g = 9.81;
  const double k = e / (c * dt * dt), d = (1.0 - e) / (c * dt);
  auto step = [&](double overlap) {
    World w = box_on_ground(-overlap);
    w.friction.default_compliance = c;
    w.friction.default_erp = e;
    const StepContacts found = find_step_contacts(w, SimulatorSettings{});
    EXPECT_EQ(found.contacts.size(), 2u);
    const ContactSystem s = assemble_contact_system(w, found.contacts, found.islands[0], dt);
    const ContactSolution sol = solve_lcp_model(s, dt, LemkeSettings{});
    EXPECT_EQ(sol.status, ContactStatus::solved) << sol.message;
    return sol;
  };
  const ContactSolution rest = step(g / (2.0 * k));
  EXPECT_LE(rest.v_next.cwiseAbs().maxCoeff(), 1e-10) << "the springs hold the box";
  EXPECT_NEAR(rest.lambda_n.sum(), g * dt, 1e-10) << "the impulse of the weight";
  // Half that overlap: m v⁺ = −m g Δt + 2Δt(k δ − (kΔt + d) v⁺).
  const double delta = g / (4.0 * k);
  const ContactSolution half = step(delta);
  EXPECT_NEAR(half.v_next(1), -(g - 2.0 * k * delta) * dt / (1.0 + 2.0 * (k * dt + d) * dt), 1e-10);
}

TEST(SceneSoftness, PerPairValuesReachOnlyThatPairsContacts) {
  World w = box_on_ground(-0.001);
  RigidBody second = w.bodies[0];
  second.pose.x() = 3.0;
  second.material = 1;
  w.bodies.push_back(second);
  w.friction.pairs.push_back(FrictionTable::Pair{0, 1, 0.4, 0.7, 0.2});
  const StepContacts found = find_step_contacts(w, SimulatorSettings{});
  ASSERT_EQ(found.contacts.size(), 4u);
  for (const Contact& c : found.contacts) {
    const bool pair = w.bodies[c.body_a].material == 1;
    EXPECT_EQ(c.compliance, pair ? 0.7 : 0.0);
    EXPECT_EQ(c.erp, pair ? 0.2 : 0.0);
    EXPECT_EQ(c.mu, pair ? 0.4 : 0.5);
  }
}

TEST(SceneSoftness, SceneJsonReadsWritesAndNamesBadValues) {
  const std::string text = R"({"friction": {"default": 0.4, "compliance": 0.01, "erp": 0.2,
      "pairs": [{"materials": [0, 1], "mu": 0.3, "erp": 0.5}]},
      "bodies": [{"vertices": [[0,0],[1,0],[1,1],[0,1]], "density": 1}]})";
  const Scene scene = parse_scene(text);
  const FrictionTable& f = scene.world.friction;
  EXPECT_EQ(f.default_compliance, 0.01);
  EXPECT_EQ(f.default_erp, 0.2);
  ASSERT_EQ(f.pairs.size(), 1u);
  EXPECT_EQ(f.pairs[0].compliance, 0.01) << "a pair without the key takes the table's default";
  EXPECT_EQ(f.pairs[0].erp, 0.5);
  const Scene back = parse_scene(write_scene(scene));
  EXPECT_EQ(back.world.friction.default_compliance, 0.01);
  EXPECT_EQ(back.world.friction.pairs[0].erp, 0.5);
  EXPECT_EQ(write_scene(parse_scene(R"({"bodies": []})")).find("compliance"), std::string::npos)
      << "a rigid table writes no softness keys";
  auto message = [](const std::string& json) {
    try {
      parse_scene(json);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"friction": {"erp": 1.5}})").find("friction.erp"), std::string::npos);
  EXPECT_NE(message(R"({"friction": {"compliance": -1}})").find("friction.compliance"), std::string::npos);
  EXPECT_NE(message(R"({"friction": {"pairs": [{"materials": [0, 1], "mu": 0.3, "erp": -0.1}]}})").find("erp"),
            std::string::npos);
}

TEST(SceneSoftness, LayoutRoundTripAndBounds) {
  Scene scene = make_learning_pile(LearningPileOptions{});
  const SceneParameterMap plain(scene.world, learn("mu,block"));
  const SceneParameterMap soft(scene.world, learn("mu,block,softness"));
  ASSERT_EQ(soft.size(), plain.size() + 2);
  EXPECT_EQ(soft.kind(plain.size()), SceneParameterMap::Kind::compliance);
  EXPECT_EQ(soft.kind(plain.size() + 1), SceneParameterMap::Kind::erp);
  ParameterSet theta = soft.parameters(scene.world);
  EXPECT_EQ(theta[plain.size()].name, "compliance");
  EXPECT_EQ(theta[plain.size() + 1].name, "erp");
  EXPECT_EQ(theta[plain.size()].value, 0.0);
  theta.set_value("compliance", 0.02);
  theta.set_value("erp", 0.4);
  World w = scene.world;
  soft.apply(theta, w);
  EXPECT_EQ(w.friction.default_compliance, 0.02);
  EXPECT_EQ(w.friction.default_erp, 0.4);
  const ParameterSet back = soft.parameters(w);
  for (Index k = 0; k < soft.size(); ++k) EXPECT_EQ(back[k].value, theta[k].value) << back[k].name;
  Vector v = theta.values();
  v(plain.size()) = -1.0, v(plain.size() + 1) = 2.0;
  theta.set_values(v);
  EXPECT_EQ(theta[plain.size()].value, 0.0) << "compliance clamps at 0";
  EXPECT_EQ(theta[plain.size() + 1].value, 1.0) << "erp clamps at 1";
  // Per pair: a listed pair gets its own two.
  scene.world.friction.pairs.push_back(FrictionTable::Pair{0, 2, 0.5, 0.0, 0.0});
  const SceneParameterMap pairs(scene.world, learn("mu,softness", true));
  const ParameterSet tp = pairs.parameters(scene.world);
  EXPECT_EQ(parameters_named(tp, "compliance").size(), 2u);
  EXPECT_EQ(tp[tp.size() - 1].name, "erp[0,2]");
  EXPECT_EQ(perturb_scene_parameters(tp, pairs, 0.2, 7)[tp.size() - 1].value, 0.0) << "kept by the perturbation";
}

SceneDataset soft_pile() {
  return test::last_transitions(make_learning_pile(test::learning_pile_options(6, 2, ContactModel::lcp)), 60, 40);
}

void check_softness_gradient(LossMethod method) {
  const SceneDataset data = soft_pile();
  const SceneParameterMap map(data.scene.world, learn("mu,mass,softness"));
  ParameterSet theta = perturb_scene_parameters(map.parameters(data.scene.world), map, 0.05, 3);
  const std::vector<Index> soft = {map.size() - 2, map.size() - 1};
  Vector v = theta.values();
  v(soft[0]) = 0.2 * map.length_scale(soft[0]);  // a fifth of a Delassus diagonal
  v(soft[1]) = 0.3;
  theta.set_values(v);
  SceneObjective objective(data, map, test::fd_loss_settings(method));
  const std::vector<Index> samples = test::samples_by_gradient(objective, theta, soft, 4);
  ASSERT_FALSE(samples.empty()) << "no step where compliance and erp both act (no overlapping contact?)";
  test::check_first_smooth_sample(objective, map, theta, samples, soft, std::string(to_string(method)) + " softness",
                                  [](const test::FdReport& r) { return r.checked == 2; });
}

TEST(SceneSoftness, HardLossGradientMatchesCentralDifferences) { check_softness_gradient(LossMethod::hard); }
TEST(SceneSoftness, RelaxedLossGradientMatchesCentralDifferences) { check_softness_gradient(LossMethod::relaxed); }
TEST(SceneSoftness, ConvexLossGradientMatchesCentralDifferences) { check_softness_gradient(LossMethod::convex); }

// At the rigid start (c = e = 0, on the bounds) the relaxed and convex losses have the
// gradient that the soft values tend to, nonzero in c and e (the rigid systems carry no
// softness vectors; the convex loss still differentiates its push-out in e). The hard loss
// does not: on a degenerate island (more contact rows than degrees of freedom) Lemke's λ at
// c = 0 is one vertex of a set of solutions and any c > 0 selects another (the regularized
// one), so its ∂ℓ/∂(c, e) jump at 0 (measured here: 5e-10 at 0 against 0.34 at c = 1e-8/kg);
// it is only required finite. The convex loss is also checked with open contacts released
// (ConvexStepLossSettings::release_open_contacts): phase 1's v_ref = max(e·|φ|/Δt, 0) is 0
// at e = 0 on an overlapping contact, and its one-sided derivative into e ≥ 0 must be kept
// (normal_softening.hpp phase1_softening_terms; without it ∂ℓ/∂e was −0.099 at e = 0
// against −0.4328 at every e from 1e-10 to 1e-5, the released set the same).
TEST(SceneSoftness, GradientAtTheRigidStartIsTheLimitOfSoftOnes) {
  const SceneDataset data = soft_pile();
  const SceneParameterMap map(data.scene.world, learn("mu,softness"));
  const ParameterSet rigid = map.parameters(data.scene.world);
  const Index c = map.size() - 2, e = map.size() - 1;
  ParameterSet soft = rigid;
  Vector v = soft.values();
  v(c) = 1e-7 * map.length_scale(c), v(e) = 1e-7;
  soft.set_values(v);
  SceneLossSettings released = test::fd_loss_settings(LossMethod::convex);
  released.convex.release_open_contacts = true;
  const std::vector<std::pair<std::string, SceneLossSettings>> cases = {
      {"hard", test::fd_loss_settings(LossMethod::hard)},
      {"relaxed", test::fd_loss_settings(LossMethod::relaxed)},
      {"convex", test::fd_loss_settings(LossMethod::convex)},
      {"convex, open contacts released", released}};
  for (const auto& [name, settings] : cases) {
    SceneObjective objective(data, map, settings);
    const std::vector<Index> samples = test::samples_by_gradient(objective, rigid, {c, e}, 4);
    ASSERT_FALSE(samples.empty()) << name << ": no step with a gradient in both at the rigid start";
    objective.prepare(rigid, 1);
    const SampleResult g0 = objective.evaluate(samples[0], rigid, 0);
    objective.prepare(soft, 1);
    const SampleResult g1 = objective.evaluate(samples[0], soft, 0);
    ASSERT_TRUE(g0.ok && g1.ok) << name;
    if (settings.method == LossMethod::hard) {
      EXPECT_TRUE(g0.gradient.allFinite());
      continue;
    }
    for (Index k : {c, e})
      EXPECT_NEAR(g0.gradient(k), g1.gradient(k), 1e-3 * std::abs(g1.gradient(k))) << name << " " << rigid[k].name;
  }
}

TEST(SceneSoftness, ConvexModelTakesComplianceAndPushOut) {
  // The unit box 2 mm into the ground, frictionless (one row per contact, no phase-2 friction),
  // at rest: phase 2's stationarity where λn > 0 and the hard rows are inactive reads
  // Jn v⁺ = v_ref − (g·Wnn + c) λn, with v_ref = −e·min(φ, 0)/Δt (exp_phi's own v_ref is 0).
  const double dt = 0.01, c = 0.5, e = 0.4;
  World w = box_on_ground(-0.002);
  w.friction.default_mu = 0.0;
  const StepContacts rigid_found = find_step_contacts(w, SimulatorSettings{});
  const ContactSystem s0 = assemble_contact_system(w, rigid_found.contacts, rigid_found.islands[0], dt);
  QpSettings qs;
  qs.eps_abs = 1e-12;
  const ContactSolution r0 = solve_convex_model(s0, dt, qs);
  w.friction.default_compliance = c;
  w.friction.default_erp = e;
  const StepContacts found = find_step_contacts(w, SimulatorSettings{});
  const ContactSystem s = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  const ContactSolution r = solve_convex_model(s, dt, qs);
  ASSERT_EQ(r.status, ContactStatus::solved) << r.message;
  const Vector vn = s.Jn * r.v_next;
  const double rho = 1e-3;  // solve_convex_model's default; exp_phi: g = 2ρ exp(φ)
  const SparseMatrix W = delassus(s);
  for (Index i = 0; i < 2; ++i) {
    ASSERT_GT(r.lambda_n(i), 1e-6);
    const double g = 2.0 * rho * std::exp(s.phi(i));
    const double lhs = vn(i) + e * s.phi(i) / dt + c * r.lambda_n(i);
    EXPECT_NEAR(lhs, -g * W.coeff(i, i) * r.lambda_n(i), 1e-8) << "contact " << i;
  }
  EXPECT_GT(r.v_next(1), r0.v_next(1)) << "the erp pushes the box out of the overlap";
  // Zero softness: the answer of the system without it, bit for bit.
  World zero = w;
  zero.friction.default_compliance = zero.friction.default_erp = 0.0;
  const StepContacts fz = find_step_contacts(zero, SimulatorSettings{});
  const ContactSolution rz = solve_convex_model(assemble_contact_system(zero, fz.contacts, fz.islands[0], dt), dt, qs);
  EXPECT_EQ(rz.v_next, r0.v_next);
}

TEST(SceneSoftness, RefusedByTheRelaxedDualLossAndBadValues) {
  SceneDataset data = soft_pile();
  data.transitions.resize(3);
  World w = data.scene.world;
  w.friction.default_compliance = 0.01;
  const StepContacts found = find_step_contacts(w, data.scene.settings);
  ASSERT_FALSE(found.islands.empty());
  const double dt = data.scene.settings.dt;
  const ContactSystem s = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  EXPECT_THROW(relaxed_dual_step_loss(s, s.v_star, dt), InputError);
  EXPECT_NO_THROW(convex_step_loss(s, s.v_star, dt, ConvexStepLossSettings{}));
  EXPECT_NO_THROW(solve_convex_model(s, dt, QpSettings{}));
  EXPECT_NO_THROW(relaxed_step_loss(s, s.v_star, dt));
  EXPECT_NO_THROW(hard_step_loss(s, s.v_star, dt));
  SimulatorSettings convex = data.scene.settings;
  convex.model = ContactModel::convex;
  Simulator soft_convex(w, convex);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(soft_convex.step().failed_islands, 0);
  SimulatorSettings lcp = data.scene.settings;
  lcp.model = ContactModel::lcp;
  EXPECT_NO_THROW(Simulator(w, lcp));
  w.friction.default_erp = 1.5;
  EXPECT_THROW(Simulator(w, lcp), InputError);
  EXPECT_THROW(Simulator(w, convex), InputError);
  ContactSystem bad = s;
  bad.compliance(0) = -1.0;
  EXPECT_THROW(solve_convex_model(bad, dt, QpSettings{}), InputError);
  EXPECT_THROW(parse_polygon_learn_flags("mu,softness"), InputError);
  EXPECT_TRUE(parse_scene_learn_flags("mu,softness").softness);
}

}  // namespace
}  // namespace lcprelax::learn
