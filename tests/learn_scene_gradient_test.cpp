// Scene learning end to end (learn/scene_objective.hpp): on one transition of a settled
// 20-body pile with ≥ 60 contacts, ∂ℓ/∂θ of every parameter kind (μ, each class's mass,
// inertia and vertices, the ground's angle and offset, the walls' end points) for the hard,
// relaxed and convex losses against central differences of the whole pipeline (θ → world →
// collision → islands → assembly → loss), relative error ≤ 1e-5 away from kinks.
#include <lcprelax/learn/scene_objective.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lcprelax::learn {
namespace {

struct Pile {
  SceneDataset data;
  Index sample = 0;
};

// A settled 20-body pile; the transition with the most contacts among the last ones.
const Pile& settled_pile(ContactModel model) {
  static Pile piles[2];
  static bool made[2] = {false, false};
  const int k = model == ContactModel::lcp ? 0 : 1;
  if (!made[k]) {
    LearningPileOptions po;
    po.bodies = 20;
    po.classes = 4;
    po.model = model;
    SceneDatasetSettings ds;
    ds.steps = 90;
    ds.drop_without_contact = false;
    piles[k].data = generate_scene_dataset(make_learning_pile(po), ds);
    auto& tr = piles[k].data.transitions;
    tr.erase(tr.begin(), tr.end() - 40);
    made[k] = true;
  }
  return piles[k];
}

// tolerance: 1e-5 relative for all three. The convex loss's adjoint runs through two
// interior-point solves and the κ coupling: at the QP tolerance 1e-12 it agrees to 1.3e-5
// (the solves' own error), at 1e-14 to 1.0e-6, so its solves run at 1e-14.
void check_gradient(LossMethod method, ContactModel data_model, double tolerance = 1e-5) {
  const Pile& pile = settled_pile(data_model);
  SceneParameterSettings ps;
  ps.learn.ground = true;
  const SceneParameterMap map(pile.data.scene.world, ps);
  const ParameterSet truth = map.parameters(pile.data.scene.world);
  // Away from the truth (where the hard loss and its gradient vanish): 5% off.
  const ParameterSet theta = perturb_scene_parameters(truth, map, 0.05, 11);
  SceneLossSettings ls;
  ls.method = method;
  ls.relaxed.qp.eps_abs = ls.convex.qp.eps_abs = 1e-12;
  ls.relaxed.qp.eps_rel = ls.convex.qp.eps_rel = 0.0;
  ls.convex.qp.eps_abs = 1e-14;
  // Every probe centred at 0 (a stored centre would make ℓ depend on the previous probe);
  // the centred shift's gradient is checked in learn_step_loss_relaxed_test.
  ls.relaxed_warm_center = false;
  SceneObjective objective(pile.data, map, ls);
  auto eval = [&](const ParameterSet& at, Index sample) {
    objective.prepare(at, 1);
    return objective.evaluate(sample, at, 0);
  };
  // The transition with the most contacts.
  Index sample = 0;
  long most = -1;
  for (Index i = 0; i < objective.num_samples(); ++i) {
    objective.reset_stats();
    eval(theta, i);
    if (objective.stats().contacts > most) most = objective.stats().contacts, sample = i;
  }
  ASSERT_GE(most, 60) << "the pile should rest on >= 60 contacts";
  const SampleResult r = eval(theta, sample);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(r.gradient.size(), theta.size());
  const double gmax = r.gradient.cwiseAbs().maxCoeff();
  ASSERT_GT(gmax, 0.0);
  // One-sided differences at h and h/2. On a smooth stretch forward − backward = O(h) and
  // halves with h; where it does not, θ sits on a kink (a degenerate contact: λ = 0 and
  // w = 0, or two exactly parallel faces whose incident edge flips), which settled piles
  // have. There the adjoint must equal one of the one-sided derivatives (it is the
  // derivative of the final active set). At most 20% of the parameters may be on kinks.
  auto loss_at = [&](Index k, double step) {
    Vector v = theta.values();
    v(k) += step;
    ParameterSet at = theta;
    at.set_values(v);
    const SampleResult rs = eval(at, sample);
    EXPECT_TRUE(rs.ok) << theta[k].name << ": " << rs.message;
    return rs.loss;
  };
  int checked = 0, kinks = 0;
  double worst = 0.0;
  for (Index k = 0; k < theta.size(); ++k) {
    const double h = 1e-5 * (map.kind(k) == SceneParameterMap::Kind::angle ? 1.0 : std::max(map.length_scale(k), std::abs(theta[k].value)));
    const double p1 = loss_at(k, h), m1 = loss_at(k, -h), p2 = loss_at(k, h / 2), m2 = loss_at(k, -h / 2);
    const double fwd1 = (p1 - r.loss) / h, bwd1 = (r.loss - m1) / h, fwd2 = (p2 - r.loss) / (h / 2), bwd2 = (r.loss - m2) / (h / 2);
    const double fd = (p2 - m2) / h, fd_h = (p1 - m1) / (2 * h);
    // Relative to the parameter's own derivative, with a floor of 1e-3 of the largest one
    // (a parameter that barely acts, e.g. a wall a body only grazes, is compared in
    // absolute terms, to 1e-8 of the largest derivative).
    const double scale = std::max(std::abs(fd), 1e-3 * gmax);
    const double jump1 = std::abs(fwd1 - bwd1), jump2 = std::abs(fwd2 - bwd2);
    if (jump2 > 1e-4 * scale && jump2 > 0.75 * jump1) {
      ++kinks;
      const double one_sided = std::min(std::abs(r.gradient(k) - fwd2), std::abs(r.gradient(k) - bwd2));
      std::printf("kink at θ: %s %s one-sided %.9g / %.9g, adjoint %.9g\n", to_string(method), theta[k].name.c_str(),
                  fwd2, bwd2, r.gradient(k));
      EXPECT_LE(one_sided, 1e-3 * std::max(std::abs(fwd2), std::abs(bwd2)) + 1e-6 * gmax)
          << to_string(method) << " " << theta[k].name << ": the adjoint is neither one-sided derivative";
      continue;
    }
    EXPECT_LE(std::abs(fd - fd_h), 1e-4 * scale) << theta[k].name << ": a kink within ±h";
    // The differences' own error (roundoff of the solves over h, truncation) is estimated by
    // how much they move from h to h/2 and allowed on top of the 1e-5 relative tolerance.
    const double noise = 2.0 * std::abs(fd - fd_h);
    EXPECT_LE(std::abs(r.gradient(k) - fd), tolerance * scale + noise)
        << to_string(method) << " " << theta[k].name << ": adjoint " << r.gradient(k) << ", central difference " << fd;
    worst = std::max(worst, std::abs(r.gradient(k) - fd) / scale);
    ++checked;
  }
  std::printf("%s: %d parameters compared (largest relative error %.2e), %d on kinks, %ld contacts\n",
              to_string(method), checked, worst, kinks, most);
  EXPECT_LE(kinks * 5, static_cast<int>(theta.size()));
}

// A settled pile without pushes sticks everywhere; from μ₀ = 10× the truth every contact
// still sticks, the LCP's basis does not change with μ, and the hard loss's ∂ℓ/∂μ is zero
// (the weakness the relaxed loss removes: its ∂ℓ/∂μ is not zero there). Zero up to the
// roundoff of the final basis' solution, which Lemke returns unclipped where clipping
// would move w more (6.7e-31 here): required below 1e-12 of the relaxed loss's.
TEST(SceneGradient, HardHasZeroMuGradientFromTenTimesTheTruthOnStickingData) {
  LearningPileOptions po;
  po.bodies = 20;
  SceneDatasetSettings ds;
  ds.steps = 120;
  ds.push_fraction = 0.0;
  SceneDataset data = generate_scene_dataset(make_learning_pile(po), ds);
  data.transitions.erase(data.transitions.begin(), data.transitions.end() - 5);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  ParameterSet theta = map.parameters(data.scene.world);
  theta.set_value("mu", 10 * theta.value("mu"));
  double hard_gradient = 0.0;
  for (LossMethod method : {LossMethod::hard, LossMethod::relaxed}) {
    SceneLossSettings ls;
    ls.method = method;
    SceneObjective objective(data, map, ls);
    objective.prepare(theta, 1);
    double mu_gradient = 0.0;
    for (Index i = 0; i < objective.num_samples(); ++i) {
      const SampleResult r = objective.evaluate(i, theta, 0);
      ASSERT_TRUE(r.ok) << r.message;
      mu_gradient += std::abs(r.gradient(0));
    }
    if (method == LossMethod::hard) {
      hard_gradient = mu_gradient;
    } else {
      EXPECT_GT(mu_gradient, 0.0);
      EXPECT_LE(hard_gradient, 1e-12 * mu_gradient);
    }
  }
}

TEST(SceneGradient, RelaxedMatchesCentralDifferences) { check_gradient(LossMethod::relaxed, ContactModel::lcp); }
TEST(SceneGradient, HardMatchesCentralDifferences) { check_gradient(LossMethod::hard, ContactModel::lcp); }
TEST(SceneGradient, ConvexMatchesCentralDifferences) { check_gradient(LossMethod::convex, ContactModel::convex); }

}  // namespace
}  // namespace lcprelax::learn
