// The sparse convex step loss (learn/step_loss_convex.hpp): with w = 0 its forward is
// models' solve_convex_model; central differences of ℓ against every entry of the
// cotangent (Jn, Jt on their patterns, φ, μ, M⁻¹, v*) in the dual and the lifted
// formulation, on hand-made islands and on one ≥ 60-contact island of a settled 20-body
// pile (≤ 40 entries per kind there, differences of the lifted form's ℓ for both
// cotangents, kinks of the degenerate pile counted and bounded); dual and lifted agree on
// the hand-made islands. Timings are measured by bench/run_learn_scene.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace lcprelax::learn {
namespace {

constexpr double kDt = 1e-2;

ConvexStepLossSettings tight(ConvexFormulation form, double w = 1.0, double eps = 1e-12) {
  ConvexStepLossSettings s;
  s.qp.eps_abs = eps;
  s.formulation = form;
  s.deviation = w;
  return s;
}

// The largest island of `world`'s next step (the simulator's own contacts and margin).
ContactSystem largest_island(const World& world, const SimulatorSettings& settings) {
  const StepContacts sc = find_step_contacts(world, settings);
  EXPECT_FALSE(sc.islands.empty());
  std::size_t best = 0;
  for (std::size_t k = 1; k < sc.islands.size(); ++k)
    if (sc.islands[k].contacts.size() > sc.islands[best].contacts.size()) best = k;
  ContactSystem s = assemble_contact_system(world, sc.contacts, sc.islands[best], settings.dt);
  s.Jn.makeCompressed();
  s.Jt.makeCompressed();
  return s;
}

// Boxes of side 0.5 m stacked on the ground, lifted by small distinct gaps (so that no gap
// sits on the kink of max(φ, 0)) and slightly tilted, with velocities `v` (one per box).
ContactSystem boxes(int count, double mu, const std::vector<Vec3>& v) {
  Scene scene = make_box_stack_scene(count, 0.5, mu);
  for (int k = 0; k < count; ++k) {
    RigidBody& b = scene.world.bodies[static_cast<std::size_t>(k)];
    b.pose(1) += 1e-3 * (k + 1) + 4e-4 * k;
    b.pose(2) += 0.004 * (k % 2 == 0 ? 1.0 : -1.0);
    b.velocity = v[static_cast<std::size_t>(k)];
  }
  SimulatorSettings settings;
  settings.dt = kDt;
  return largest_island(scene.world, settings);
}

// A settled pile of `bodies` polygons (convex model) and its largest island, with one
// post-stabilization pass (contact_island_fixtures.hpp says why). Measured with the
// simulator's default of 5 passes (pile_island(20, 3, 150), 68 contacts): the island is more
// degenerate, and PileIslandFiniteDifferences' lifted gradient at eps_abs = 1e-10 misses the
// 1e-5 bound on 29 entries (up to 3e-4 relative: the forward's tolerance, not the backward);
// at eps_abs = 1e-12 every smooth entry is within 5.5e-7 and 2 Jt kinks lie just outside
// the one-sided bracket.
ContactSystem pile_island(int bodies, std::uint64_t seed, int steps) {
  PileOptions o;
  o.bodies = bodies;
  o.seed = seed;
  o.model = ContactModel::convex;
  SimulatorSettings settings;
  settings.model = ContactModel::convex;
  settings.post_stabilization_passes = 1;
  Simulator sim = make_simulator(make_pile_scene(o), settings);
  for (int k = 0; k < steps; ++k) sim.step();
  return largest_island(sim.world(), sim.settings());
}

Vector noisy(const Vector& v, double scale, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector out = v;
  for (Index i = 0; i < out.size(); ++i) out(i) += scale * u(rng);
  return out;
}

// Target v̄ = the model's prediction (with v̄ = v*) plus noise.
Vector target_near_solution(const ContactSystem& s, const ConvexStepLossSettings& settings) {
  const StepLossResult r = convex_step_loss(s, s.v_star, kDt, settings);
  EXPECT_TRUE(has_solution(r.status)) << r.message;
  return noisy(r.v_next, 0.05, 7);
}

// A view of one data kind as an array of values, with the cotangent's matching array.
struct Kind {
  std::string name;
  std::function<double*(ContactSystem&)> data;
  std::function<const double*(const ContactSystemCotangent&)> grad;
  std::function<Index(const ContactSystem&)> size;
};

std::vector<Kind> kinds() {
  return {
      {"Jn", [](ContactSystem& s) { return s.Jn.valuePtr(); },
       [](const ContactSystemCotangent& g) { return g.Jn.valuePtr(); },
       [](const ContactSystem& s) { return static_cast<Index>(s.Jn.nonZeros()); }},
      {"Jt", [](ContactSystem& s) { return s.Jt.valuePtr(); },
       [](const ContactSystemCotangent& g) { return g.Jt.valuePtr(); },
       [](const ContactSystem& s) { return static_cast<Index>(s.Jt.nonZeros()); }},
      {"phi", [](ContactSystem& s) { return s.phi.data(); },
       [](const ContactSystemCotangent& g) { return g.phi.data(); },
       [](const ContactSystem& s) { return s.num_contacts(); }},
      {"mu", [](ContactSystem& s) { return s.mu.data(); }, [](const ContactSystemCotangent& g) { return g.mu.data(); },
       [](const ContactSystem& s) { return s.num_friction(); }},
      {"minv", [](ContactSystem& s) { return s.minv.data(); },
       [](const ContactSystemCotangent& g) { return g.minv.data(); },
       [](const ContactSystem& s) { return s.num_dofs(); }},
      {"v_star", [](ContactSystem& s) { return s.v_star.data(); },
       [](const ContactSystemCotangent& g) { return g.v_star.data(); },
       [](const ContactSystem& s) { return s.num_dofs(); }},
  };
}

// Finite differences of ℓ against the cotangent, entry by entry (every `stride`-th entry
// of each kind) of `other` if given, else of the cotangent `settings` give. With ℓ± =
// ℓ(x ± h) by `settings`, d± the one-sided differences and the denominator
// den = max(|an|, floor·max|an of the kind|, 1e-4), an entry passes when
//   smooth: |(ℓ+ − ℓ−)/2h − an| ≤ 1e-5·den, or
//   kink:   |d+ − d−| > 1e-4·den (a jump of the derivative, measured) and an lies in
//           [min(d±), max(d±)] ± 1e-5·den (the interior point's gradient interpolates the
//           one-sided derivatives there, qp_solver.hpp). When `other` (another
//           formulation's cotangent) is checked, its entries at a measured jump are only
//           counted: its interior point may pick another element of the generalized
//           gradient than the one-sided derivatives along this coordinate bracket.
// Returns the number of kinks; the caller bounds it. Gaps within 10·h of 0 (the kink of
// max(φ, 0)) are skipped.
int check_gradient(const ContactSystem& s0, const Vector& target, const ConvexStepLossSettings& settings,
                   const std::string& label, Index max_per_kind = 1 << 30, double floor = 1e-3,
                   const ContactSystemCotangent* other = nullptr) {
  const StepLossResult r0 = convex_step_loss(s0, target, kDt, settings);
  EXPECT_TRUE(has_solution(r0.status)) << label << ": " << r0.message;
  if (!has_solution(r0.status)) return 0;
  const ContactSystemCotangent& grad = other ? *other : r0.grad;
  EXPECT_EQ(grad.Jn.nonZeros(), s0.Jn.nonZeros());
  EXPECT_EQ(grad.Jt.nonZeros(), s0.Jt.nonZeros());
  int kinks_total = 0;
  for (const Kind& kind : kinds()) {
    ContactSystem s = s0;
    const Index n = kind.size(s);
    const double* an = kind.grad(grad);
    double scale = 0.0;
    for (Index i = 0; i < n; ++i) scale = std::max(scale, std::abs(an[i]));
    const Index stride = std::max<Index>(1, n / max_per_kind);
    double worst = 0.0;
    int checked = 0, kinks = 0, failed = 0, outside = 0;
    for (Index i = 0; i < n; i += stride) {
      double* x = kind.data(s) + i;
      const double x0 = *x, h = 1e-6 * std::max(1.0, std::abs(x0));
      if (kind.name == "phi" && std::abs(x0) < 10.0 * h) continue;
      *x = x0 + h;
      const StepLossResult rp = convex_step_loss(s, target, kDt, settings);
      *x = x0 - h;
      const StepLossResult rm = convex_step_loss(s, target, kDt, settings);
      *x = x0;
      EXPECT_TRUE(has_solution(rp.status) && has_solution(rm.status)) << label << " " << kind.name << i;
      const double fd = (rp.loss - rm.loss) / (2.0 * h);
      const double dp = (rp.loss - r0.loss) / h, dm = (r0.loss - rm.loss) / h;
      const double den = std::max({std::abs(an[i]), floor * scale, 1e-4});
      const double err = std::abs(fd - an[i]) / den;
      const bool smooth = err <= 1e-5;
      const bool jump = std::abs(dp - dm) > 1e-4 * den;
      const bool kink =
          !smooth && jump && an[i] >= std::min(dp, dm) - 1e-5 * den && an[i] <= std::max(dp, dm) + 1e-5 * den;
      ++checked;
      if (smooth) worst = std::max(worst, err);
      if (kink) ++kinks;
      if (!smooth && !kink && jump && other) {  // a kink, another form's element: counted only
        ++outside;
        continue;
      }
      if (!smooth && !kink) {
        ++failed;
        ADD_FAILURE() << label << " " << kind.name << "[" << i << "]: central " << fd << ", one-sided " << dm << " / "
                      << dp << ", analytic " << an[i] << " (scale " << scale << ")";
      }
    }
    kinks_total += kinks;
    std::printf("%-28s %-6s %4d checked, max|grad| %.3e, worst smooth rel. error %.2e, kinks %d (+%d outside "
                "the one-sided bracket), failed %d\n",
                label.c_str(), kind.name.c_str(), checked, scale, worst, kinks, outside, failed);
    kinks_total += outside;
  }
  return kinks_total;
}

// Same loss and gradient from the dual and the lifted formulation.
void expect_formulations_agree(const ContactSystem& s, const Vector& target, double w, const std::string& label) {
  const StepLossResult d = convex_step_loss(s, target, kDt, tight(ConvexFormulation::dual, w));
  const StepLossResult l = convex_step_loss(s, target, kDt, tight(ConvexFormulation::lifted, w));
  ASSERT_TRUE(has_solution(d.status) && has_solution(l.status)) << d.message << " / " << l.message;
  EXPECT_NEAR(d.loss, l.loss, 1e-8 * std::max(1.0, d.loss)) << label;
  EXPECT_LE((d.v_next - l.v_next).lpNorm<Eigen::Infinity>(), 1e-7) << label;
  for (const Kind& kind : kinds()) {
    const Index n = kind.size(s);
    const double *a = kind.grad(d.grad), *b = kind.grad(l.grad);
    double diff = 0.0, scale = 0.0;
    for (Index i = 0; i < n; ++i) diff = std::max(diff, std::abs(a[i] - b[i])), scale = std::max(scale, std::abs(a[i]));
    EXPECT_LE(diff, 5e-6 * std::max(scale, 1e-4)) << label << " " << kind.name << " (scale " << scale << ")";
    std::printf("%-28s %-6s dual vs lifted: max|diff| / max|grad| = %.2e\n", label.c_str(), kind.name.c_str(),
                diff / std::max(scale, 1e-300));
  }
}

struct NamedIsland {
  std::string name;
  ContactSystem s;
};

std::vector<NamedIsland> hand_made() {
  return {{"box on the ground", boxes(1, 0.5, {Vec3(0.02, -0.1, 0.05)})},
          {"two stacked boxes", boxes(2, 0.5, {Vec3(0.01, -0.1, 0.02), Vec3(-0.02, -0.2, -0.03)})},
          {"box sliding", boxes(1, 0.3, {Vec3(2.0, -0.05, 0.0)})}};
}

TEST(StepLossConvex, ZeroDeviationForwardIsTheConvexModel) {
  std::vector<NamedIsland> islands = hand_made();
  islands.push_back({"pile", pile_island(20, 3, 150)});
  for (const NamedIsland& is : islands)
    for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
      ConvexStepLossSettings settings = tight(form, 0.0);
      settings.qp.eps_abs = 1e-10;
      settings.phase1_regularization = 0.0;  // the simulator's model exactly
      const Vector target = noisy(is.s.v_star, 0.1, 3);
      const StepLossResult r = convex_step_loss(is.s, target, kDt, settings);
      const ContactSolution m = solve_convex_model(is.s, kDt, settings.qp, settings.rho, form);
      ASSERT_TRUE(has_solution(r.status)) << is.name << ": " << r.message;
      ASSERT_TRUE(has_solution(m.status)) << is.name << ": " << m.message;
      EXPECT_LE((r.v_next - m.v_next).lpNorm<Eigen::Infinity>(), 1e-7) << is.name << " " << to_string(r.status) << " " << to_string(m.status) << " " << m.residual;
      EXPECT_NEAR(r.loss, (m.v_next - target).squaredNorm(), 1e-7) << is.name;
      EXPECT_GT((r.v_next - is.s.v_star).norm(), 1e-3) << is.name << ": contacts must act";
    }
}

TEST(StepLossConvex, HandMadeIslandsFiniteDifferences) {
  for (const NamedIsland& is : hand_made()) {
    ASSERT_GT(is.s.num_friction(), 0) << is.name;
    for (double w : {1.0, 0.0})
      for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
        const ConvexStepLossSettings settings = tight(form, w);
        const Vector target = target_near_solution(is.s, settings);
        const std::string label =
            is.name + (form == ConvexFormulation::dual ? " dual" : " lifted") + " w=" + std::to_string(int(w));
        EXPECT_EQ(check_gradient(is.s, target, settings, label), 0) << label << ": no kink expected";
        if (form == ConvexFormulation::dual) expect_formulations_agree(is.s, target, w, label);
      }
  }
}

// The same with phase 2's release of open contacts (release_open_contacts). The release
// changes v⁺ in 6 of the 12 cases (measured: the sliding box in all 4, the two stacked
// boxes in 2; phase 1 leaves no other gap open by more than kOpenContactMinGap). Solved to
// eps 1e-14: at 1e-12, three entries of the stacked boxes at w = 0 (minv[0], v_star[0])
// miss the 1e-5 bound by up to 2.5e-5, the forward's tolerance. With the gap threshold set
// to 0, the loss jumps by 0.014 under a 1e-6 m change of a φ where a just-touching
// contact's release flips.
TEST(StepLossConvex, HandMadeIslandsWithReleaseFiniteDifferences) {
  int released = 0;
  for (const NamedIsland& is : hand_made())
    for (double w : {1.0, 0.0})
      for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
        ConvexStepLossSettings settings = tight(form, w, 1e-14);
        settings.release_open_contacts = true;
        const Vector target = target_near_solution(is.s, settings);
        ConvexStepLossSettings held = settings;
        held.release_open_contacts = false;
        const StepLossResult with = convex_step_loss(is.s, target, kDt, settings);
        const StepLossResult without = convex_step_loss(is.s, target, kDt, held);
        ASSERT_TRUE(has_solution(with.status) && has_solution(without.status)) << is.name;
        released += (with.v_next - without.v_next).lpNorm<Eigen::Infinity>() > 1e-6 ? 1 : 0;
        const std::string label = is.name + (form == ConvexFormulation::dual ? " dual" : " lifted") + " w=" +
                                  std::to_string(int(w)) + " released";
        EXPECT_EQ(check_gradient(is.s, target, settings, label), 0) << label << ": no kink expected";
      }
  EXPECT_GE(released, 6);
}

// A settled pile is degenerate: more active contact rows (non-penetration and sticking)
// than degrees of freedom, so λt is not unique and ℓ has kinks in the data that move the
// rows (Jn, Jt, μ); the interior point's gradient is then one element between the one-sided
// derivatives. The dual form's forward stalls there within 1e3·eps (solved_inaccurate,
// ℓ accurate to ~1e-9, too noisy for differences with h = 1e-6), so both cotangents are
// checked against the differences of the lifted form's ℓ (the same function to the QP
// tolerance). Lifted form: relative errors ≤ 1e-5 on entries ≥ 0.2·max of their kind and
// ≤ 2e-6·max below that (floor 0.2). The dual cotangent's accuracy follows its forward's
// tolerance, not the backward's (below: eps 1e-12, floor 0.5).
TEST(StepLossConvex, PileIslandFiniteDifferences) {
  const ContactSystem s = pile_island(20, 3, 150);
  std::printf("pile island: %d bodies, %d contacts, %d friction rows\n", static_cast<int>(s.bodies.size()),
              static_cast<int>(s.num_contacts()), static_cast<int>(s.num_friction()));
  ASSERT_GE(s.num_contacts(), 60);
  const ConvexStepLossSettings lifted = tight(ConvexFormulation::lifted, 1.0, 1e-10);
  const Vector target = target_near_solution(s, lifted);
  // The dual at eps_abs = 1e-12: at 1e-13 its forward stalls on some machines ("no
  // progress in the residuals", numerical_error; 2026-12-05, the same island that an earlier
  // machine solved there), and at 1e-12 its cotangent is off by up to 3e-6·max at one μ
  // entry (μ[37]: −7.1e-8 against a difference of −9.7e-9, max 0.02): the forward's
  // tolerance, as for the lifted gradient above. Hence the dual's small entries are
  // checked with a floor of 0.5·max (entries below it to 1e-5·0.5·max = 1e-7 here absolute),
  // those above it to 1e-5 relative as for the lifted form.
  const StepLossResult dual = convex_step_loss(s, target, kDt, tight(ConvexFormulation::dual, 1.0, 1e-12));
  ASSERT_TRUE(has_solution(dual.status)) << dual.message;
  const int kinks_lifted = check_gradient(s, target, lifted, "pile lifted", 40, 0.2);
  const int kinks_dual = check_gradient(s, target, lifted, "pile dual (lifted fd)", 40, 0.5, &dual.grad);
  std::printf("pile: kinks met: lifted %d, dual %d\n", kinks_lifted, kinks_dual);
  EXPECT_LE(kinks_lifted, 20);  // measured: 5 of 323 entries (all Jt)
  EXPECT_LE(kinks_dual, 20);
}

// Phase 2 with the open contacts released (ConvexStepLossSettings::release_open_contacts):
// the forward at w = 0, r = 0 is the simulator's model with the release, which differs from
// the model without it on this island (the release acts), and the gradient, with the
// released set held fixed, matches central differences as in PileIslandFiniteDifferences.
TEST(StepLossConvex, ReleasedOpenContactsForwardAndFiniteDifferences) {
  const ContactSystem s = pile_island(20, 3, 150);
  ConvexStepLossSettings model = tight(ConvexFormulation::lifted, 0.0, 1e-10);
  model.phase1_regularization = 0.0;
  model.release_open_contacts = true;
  const Vector target = noisy(s.v_star, 0.1, 3);
  const StepLossResult r = convex_step_loss(s, target, kDt, model);
  const ContactSolution released =
      solve_convex_model(s, kDt, model.qp, model.rho, ConvexFormulation::lifted, {}, nullptr, true);
  const ContactSolution plain = solve_convex_model(s, kDt, model.qp, model.rho, ConvexFormulation::lifted);
  ASSERT_TRUE(has_solution(r.status) && has_solution(released.status) && has_solution(plain.status)) << r.message;
  EXPECT_LE((r.v_next - released.v_next).lpNorm<Eigen::Infinity>(), 1e-7);
  const double effect = (released.v_next - plain.v_next).lpNorm<Eigen::Infinity>();
  std::printf("pile island: release moves v+ by %.3e m/s\n", effect);
  EXPECT_GT(effect, 1e-4) << "no contact of this island was released";

  ConvexStepLossSettings lifted = tight(ConvexFormulation::lifted, 1.0, 1e-10);
  lifted.release_open_contacts = true;
  const Vector near = target_near_solution(s, lifted);
  const int kinks = check_gradient(s, near, lifted, "pile released lifted", 40, 0.2);
  EXPECT_LE(kinks, 20);
}

TEST(StepLossConvex, FrictionlessIslandFiniteDifferences) {  // μ = 0: no friction rows
  const ContactSystem s = boxes(2, 0.0, {Vec3(0.3, -0.1, 0.02), Vec3(-0.2, -0.2, -0.03)});
  ASSERT_EQ(s.num_friction(), 0);
  for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
    const ConvexStepLossSettings settings = tight(form);
    const Vector target = target_near_solution(s, settings);
    EXPECT_EQ(check_gradient(s, target, settings, "frictionless"), 0);
    if (form == ConvexFormulation::dual) expect_formulations_agree(s, target, 1.0, "frictionless");
  }
}

// The deviation penalty only in phase 2 (phase1_deviation = false): gradients against
// central differences, and no bias on the model's own data — with the target the convex
// model's own next velocity (phase1_regularization = 0, the simulator's model), ℓ vanishes
// at the true data, while the penalty in phase 1 moves κ and leaves ℓ > 0.
TEST(StepLossConvex, DeviationInPhaseTwoOnly) {
  for (const NamedIsland& is : hand_made())
    for (ConvexFormulation form : {ConvexFormulation::dual, ConvexFormulation::lifted}) {
      ConvexStepLossSettings settings = tight(form, 1.0);
      settings.phase1_deviation = false;
      const Vector target = target_near_solution(is.s, settings);
      const std::string label = is.name + (form == ConvexFormulation::dual ? " dual" : " lifted") + " phase-2 w";
      EXPECT_EQ(check_gradient(is.s, target, settings, label), 0) << label << ": no kink expected";
    }
  std::vector<NamedIsland> islands = hand_made();
  islands.push_back({"pile", pile_island(20, 3, 150)});
  double biased = 0.0;
  for (const NamedIsland& is : islands) {
    ConvexStepLossSettings settings = tight(ConvexFormulation::lifted, 1.0, 1e-10);
    settings.phase1_regularization = 0.0;
    const ContactSolution m = solve_convex_model(is.s, kDt, settings.qp, settings.rho, ConvexFormulation::lifted);
    ASSERT_TRUE(has_solution(m.status)) << is.name << ": " << m.message;
    settings.phase1_deviation = false;
    const StepLossResult own = convex_step_loss(is.s, m.v_next, kDt, settings);
    settings.phase1_deviation = true;
    const StepLossResult both = convex_step_loss(is.s, m.v_next, kDt, settings);
    ASSERT_TRUE(has_solution(own.status) && has_solution(both.status)) << is.name;
    std::printf("%-12s loss at the model's own next velocity: deviation in phase 2 only %.3e, in both phases %.3e\n",
                is.name.c_str(), own.loss, both.loss);
    EXPECT_LE(own.loss, 1e-12) << is.name;
    biased = std::max(biased, both.loss);
  }
  EXPECT_GT(biased, 1e-6) << "the penalty in phase 1 should move kappa on some island";
}

TEST(StepLossConvex, BadInputThrows) {
  const ContactSystem s = boxes(1, 0.5, {Vec3(0.0, -0.1, 0.0)});
  ConvexStepLossSettings settings;
  EXPECT_THROW(convex_step_loss(s, Vector::Zero(2), kDt, settings), InputError);
  EXPECT_THROW(convex_step_loss(s, s.v_star, -1.0, settings), InputError);
  ContactSystem bad = s;
  bad.minv(0) = 0.0;
  EXPECT_THROW(convex_step_loss(bad, s.v_star, kDt, settings), InputError);
  bad = s;
  bad.phi(0) = std::nan("");
  EXPECT_THROW(convex_step_loss(bad, s.v_star, kDt, settings), InputError);
  settings.deviation = -1.0;
  EXPECT_NE(settings.validation_error().find("deviation"), std::string::npos);
  EXPECT_THROW(convex_step_loss(s, s.v_star, kDt, settings), InputError);
  settings = ConvexStepLossSettings{};
  settings.rho = std::nan("");
  EXPECT_NE(settings.validation_error().find("rho"), std::string::npos);
}

TEST(StepLossConvex, NoApproachingContactIsFree) {
  const ContactSystem s = boxes(1, 0.5, {Vec3(0.0, 1.0, 0.0)});  // moving away from the ground
  const Vector target = noisy(s.v_star, 0.1, 5);
  const StepLossResult r = convex_step_loss(s, target, kDt, ConvexStepLossSettings{});
  EXPECT_EQ(r.status, ContactStatus::solved);
  EXPECT_EQ(r.v_next, s.v_star);
  EXPECT_NEAR(r.loss, (s.v_star - target).squaredNorm(), 1e-15);
  EXPECT_LE((r.grad.v_star - 2.0 * (s.v_star - target)).norm(), 1e-15);
  EXPECT_EQ(r.grad.phi.norm(), 0.0);
}

}  // namespace
}  // namespace lcprelax::learn
