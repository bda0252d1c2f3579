// The lcp model's per-contact LCP correction (World::lcp_block, world.hpp) and its learning
// on the scene path (flags block and block_tied, learn/scene_params.hpp):
// - stewart_trinkle_lcp adds B and d to every contact's own block (λn, β⁺, β⁻, γ), only the
//   normal entries where a contact has no friction row; an enabled zero block gives the
//   physical LCP's values (all 16 entries stored) and the Simulator's trajectory;
// - block maps θ entry by entry; block_tied keeps the friction rows' antisymmetry
//   (row and column β⁻ = −β⁺ on the impulse entries, d₂ = −d₁) and touches nothing else;
// - ∂ℓ/∂(B, d) of the hard loss against central differences of the whole pipeline, free and
//   tied, on steps of a small generated pile at a nonzero block;
// - refusals: the relaxed and convex losses (SceneObjective and the step losses themselves),
//   the convex Simulator (the lcp one falls back to the physical convex model), both flags at once,
//   the polygon CLI's flags, a non-finite block.
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

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lcprelax::learn {
namespace {

using test::parameters_named;

SceneDataset block_pile(std::size_t keep = 40) {
  return test::last_transitions(make_learning_pile(test::learning_pile_options(6, 2, ContactModel::lcp)), 60, keep);
}

SceneParameterSettings learn(const std::string& flags) {
  SceneParameterSettings ps;
  ps.learn = parse_scene_learn_flags(flags);
  return ps;
}

TEST(SceneLcpBlock, AddsTheBlockToEveryContactAndZeroChangesNothing) {
  const Scene scene = make_learning_pile(LearningPileOptions{});
  World w = scene.world;
  const StepContacts found = find_step_contacts(w, scene.settings);
  ASSERT_FALSE(found.islands.empty());
  const double dt = scene.settings.dt;
  const ContactSystem s0 = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  ASSERT_GT(s0.num_friction(), 0);
  const StewartTrinkleLcp l0 = stewart_trinkle_lcp(s0, delassus(s0), dt);
  w.lcp_block.enabled = true;
  const ContactSystem s1 = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  const StewartTrinkleLcp l1 = stewart_trinkle_lcp(s1, delassus(s1), dt);
  EXPECT_TRUE(DenseMatrix(l1.M).isApprox(DenseMatrix(l0.M), 0.0));
  EXPECT_EQ(l1.q, l0.q);
  const Index nc = s0.num_contacts(), nf = s0.num_friction();
  auto stored = [&](Index i, Index j) {
    for (SparseMatrix::InnerIterator it(l1.M, j); it; ++it)
      if (it.row() == i) return true;
    return false;
  };
  for (Index f = 0; f < nf; ++f) {
    const Index c = s0.friction_rows[f];
    const Index idx[4] = {c, nc + f, nc + nf + f, nc + 2 * nf + f};
    for (Index i : idx)
      for (Index j : idx) EXPECT_TRUE(stored(i, j)) << "entry (" << i << ", " << j << ") of contact " << c;
  }

  // A block with distinct entries lands on each contact's indices.
  for (int k = 0; k < 4; ++k) {
    for (int l = 0; l < 4; ++l) w.lcp_block.M(k, l) = 0.01 * (4 * k + l + 1);
    w.lcp_block.q(k) = -0.1 * (k + 1);
  }
  const ContactSystem s2 = assemble_contact_system(w, found.contacts, found.islands[0], dt);
  const StewartTrinkleLcp l2 = stewart_trinkle_lcp(s2, delassus(s2), dt);
  const DenseMatrix dM = DenseMatrix(l2.M) - DenseMatrix(l0.M);
  const Vector dq = l2.q - l0.q;
  std::vector<Index> friction_of(static_cast<std::size_t>(nc), -1);
  for (Index f = 0; f < nf; ++f) friction_of[static_cast<std::size_t>(s0.friction_rows[f])] = f;
  DenseMatrix expected = DenseMatrix::Zero(dM.rows(), dM.cols());
  Vector expected_q = Vector::Zero(dq.size());
  for (Index c = 0; c < nc; ++c) {
    const Index f = friction_of[static_cast<std::size_t>(c)];
    const Index idx[4] = {c, f >= 0 ? nc + f : -1, f >= 0 ? nc + nf + f : -1, f >= 0 ? nc + 2 * nf + f : -1};
    for (int k = 0; k < 4; ++k) {
      if (idx[k] < 0) continue;
      expected_q(idx[k]) += w.lcp_block.q(k);
      for (int l = 0; l < 4; ++l)
        if (idx[l] >= 0) expected(idx[k], idx[l]) += w.lcp_block.M(k, l);
    }
  }
  EXPECT_LE((dM - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((dq - expected_q).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(SceneLcpBlock, EnabledZeroBlockKeepsTheTrajectory) {
  LearningPileOptions po;
  po.bodies = 6;
  const Scene scene = make_learning_pile(po);
  World with = scene.world;
  with.lcp_block.enabled = true;
  SimulatorSettings s = scene.settings;
  s.model = ContactModel::lcp;
  s.threads = 1;
  Simulator a(scene.world, s), b(with, s);
  for (int i = 0; i < 40; ++i) a.step(), b.step();
  for (std::size_t i = 0; i < scene.world.bodies.size(); ++i) {
    EXPECT_LE((a.world().bodies[i].pose - b.world().bodies[i].pose).cwiseAbs().maxCoeff(), 1e-9) << "body " << i;
    EXPECT_LE((a.world().bodies[i].velocity - b.world().bodies[i].velocity).cwiseAbs().maxCoeff(), 1e-7) << "body " << i;
  }
}

TEST(SceneLcpBlock, FreeAndTiedLayouts) {
  const Scene scene = make_learning_pile(LearningPileOptions{});
  const SceneParameterMap plain(scene.world, learn("mu"));
  const SceneParameterMap free_map(scene.world, learn("mu,block"));
  const SceneParameterMap tied_map(scene.world, learn("mu,block_tied"));
  ASSERT_EQ(free_map.size(), plain.size() + 20);
  ASSERT_EQ(tied_map.size(), plain.size() + 7);
  EXPECT_EQ(free_map.kind(plain.size()), SceneParameterMap::Kind::lcp_block);
  ParameterSet theta = free_map.parameters(scene.world);
  EXPECT_EQ(theta[plain.size()].name, "lcp_block.M00");
  EXPECT_EQ(theta[plain.size() + 19].name, "lcp_block.q3");
  Vector v = theta.values();
  for (Index k = 0; k < 20; ++k) v(plain.size() + k) = 0.5 + k;
  theta.set_values(v);
  World w = scene.world;
  free_map.apply(theta, w);
  EXPECT_TRUE(w.lcp_block.enabled);
  EXPECT_EQ(w.lcp_block.M(1, 2), 0.5 + 6);
  EXPECT_EQ(w.lcp_block.q(3), 0.5 + 19);
  const ParameterSet back = free_map.parameters(w);
  for (Index k = 0; k < free_map.size(); ++k) EXPECT_EQ(back[k].value, theta[k].value) << back[k].name;

  ParameterSet tied = tied_map.parameters(scene.world);
  const char* names[7] = {"lcp_block.Wnn", "lcp_block.Wnt", "lcp_block.Wtn", "lcp_block.Wtt",
                          "lcp_block.mu",  "lcp_block.qn",  "lcp_block.qt"};
  for (int k = 0; k < 7; ++k) {
    EXPECT_EQ(tied[plain.size() + k].name, names[k]);
    tied.set_value(names[k], 0.1 * (k + 1));
  }
  World wt = scene.world;
  tied_map.apply(tied, wt);
  const auto& B = wt.lcp_block.M;
  const auto& d = wt.lcp_block.q;
  for (int l = 0; l < 3; ++l) EXPECT_EQ(B(2, l), -B(1, l)) << "row beta- = -row beta+";
  for (int k = 0; k < 3; ++k) EXPECT_EQ(B(k, 2), -B(k, 1)) << "column beta- = -column beta+";
  EXPECT_DOUBLE_EQ(B(0, 0), 0.1);
  EXPECT_DOUBLE_EQ(B(0, 1), 0.2);
  EXPECT_DOUBLE_EQ(B(1, 0), 0.3);
  EXPECT_DOUBLE_EQ(B(1, 1), 0.4);
  EXPECT_DOUBLE_EQ(B(3, 0), 0.5);
  EXPECT_EQ(B.col(3).norm(), 0.0) << "the gamma column is not touched";
  EXPECT_EQ(B(3, 1), 0.0);
  EXPECT_EQ(B(3, 2), 0.0);
  EXPECT_DOUBLE_EQ(d(0), 0.6);
  EXPECT_DOUBLE_EQ(d(1), 0.7);
  EXPECT_DOUBLE_EQ(d(2), -0.7);
  EXPECT_EQ(d(3), 0.0);
  const ParameterSet tied_back = tied_map.parameters(wt);
  for (Index k = 0; k < tied_map.size(); ++k) EXPECT_NEAR(tied_back[k].value, tied[k].value, 1e-15) << tied[k].name;
}

// The block at small nonzero values (so that the LCP differs from the physical one), μ and
// the masses perturbed too; steps with the most block gradient, the first without kinks.
void check_block_gradient(const std::string& flags, double value) {
  const SceneDataset data = block_pile();
  const SceneParameterMap map(data.scene.world, learn("mu,mass," + flags));
  ParameterSet theta = perturb_scene_parameters(map.parameters(data.scene.world), map, 0.05, 3);
  const std::vector<Index> block = parameters_named(theta, "lcp_block.");
  ASSERT_EQ(block.size(), flags == "block" ? 20u : 7u);
  Vector v = theta.values();
  if (flags == "block_tied") {
    for (std::size_t i = 0; i < block.size(); ++i) v(block[i]) = value * ((i % 3) - 1.0) * (1.0 + 0.1 * i);
  } else {
    // A free block of the same kind (so that the LCPs stay solvable: an arbitrary one of this
    // size ends Lemke on rays, as the fragility analysis predicts) plus every other entry at
    // a small value, so that each has its own effect.
    for (std::size_t i = 0; i < block.size(); ++i) v(block[i]) = 0.004 * value * ((i % 3) - 1.0) * (1.0 + 0.1 * i);
    v(block[0]) += value;                     // M00 (Wnn)
    v(block[5]) += value, v(block[10]) += value;  // M11, M22 (Wtt)
    v(block[6]) -= value, v(block[9]) -= value;   // M12, M21 (−Wtt)
    v(block[15]) += 0.2 * value;              // M33: γ's own diagonal
  }
  theta.set_values(v);
  SceneObjective objective(data, map, test::fd_loss_settings(LossMethod::hard));
  std::vector<Index> nonzero;  // the entries that act: every contact here has friction
  for (Index k : block) nonzero.push_back(k);
  const std::vector<Index> samples = test::samples_by_gradient(objective, theta, {block[0]}, 4);

  ASSERT_FALSE(samples.empty()) << "no step where the block acts";
  test::check_first_smooth_sample(objective, map, theta, samples, nonzero, "hard " + flags,
                                  [&](const test::FdReport& r) { return r.checked >= static_cast<int>(nonzero.size()) - 3; });
}

TEST(SceneLcpBlock, FreeBlockGradientMatchesCentralDifferences) { check_block_gradient("block", 0.05); }
TEST(SceneLcpBlock, TiedBlockGradientMatchesCentralDifferences) { check_block_gradient("block_tied", 0.05); }

TEST(SceneLcpBlock, RefusedWhereThereIsNoLcp) {
  const SceneDataset data = block_pile(5);
  const SceneParameterMap map(data.scene.world, learn("mu,block"));
  for (LossMethod m : {LossMethod::relaxed, LossMethod::convex}) {
    SceneLossSettings ls;
    ls.method = m;
    EXPECT_THROW(SceneObjective(data, map, ls), InputError) << to_string(m);
  }
  World w = data.scene.world;
  w.lcp_block.enabled = true;
  {  // the step losses themselves, on an island of the world with the block
    const StepContacts found = find_step_contacts(w, data.scene.settings);
    ASSERT_FALSE(found.islands.empty());
    const ContactSystem s = assemble_contact_system(w, found.contacts, found.islands[0], data.scene.settings.dt);
    const Vector target = s.v_star;
    EXPECT_THROW(relaxed_step_loss(s, target, data.scene.settings.dt), InputError);
    EXPECT_THROW(relaxed_dual_step_loss(s, target, data.scene.settings.dt), InputError);
    EXPECT_THROW(convex_step_loss(s, target, data.scene.settings.dt, ConvexStepLossSettings{}), InputError);
    EXPECT_NO_THROW(hard_step_loss(s, target, data.scene.settings.dt));
  }
  SimulatorSettings convex = data.scene.settings;
  convex.model = ContactModel::convex;
  EXPECT_THROW(Simulator(w, convex), InputError);
  {  // an LCP the block makes unsolvable: the lcp Simulator falls back to the physical convex
     // model and reports the island failed (no exception)
    World bad = w;
    bad.lcp_block.M(0, 0) = -1e3;
    bad.lcp_block.q(0) = -1.0;
    SimulatorSettings lcp = data.scene.settings;
    lcp.model = ContactModel::lcp;
    lcp.threads = 1;
    Simulator sim(bad, lcp);
    long failed = 0;
    for (int i = 0; i < 3; ++i) failed += sim.step().failed_islands;
    EXPECT_GT(failed, 0);
  }
  w.lcp_block.q(1) = std::numeric_limits<double>::quiet_NaN();
  SimulatorSettings lcp = data.scene.settings;
  lcp.model = ContactModel::lcp;
  EXPECT_THROW(Simulator(w, lcp), InputError);
  EXPECT_THROW(parse_scene_learn_flags("block,block_tied"), InputError);
  EXPECT_THROW(parse_polygon_learn_flags("mu,block"), InputError);
  EXPECT_TRUE(parse_scene_learn_flags("mu,block_tied").block_tied);
}

}  // namespace
}  // namespace lcprelax::learn
