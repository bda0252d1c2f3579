// Polygon datasets (polygon_dataset.hpp) and parameters (polygon_params.hpp). Expected
// behaviour:
// - generation is deterministic for a seed; with contact_only every sample has a contact at
//   the truth (by the simulator's rule, on the one-body scene of polygon_scene.hpp); noise σ changes every recorded component by about σ (sample std within 20%);
// - a generated trajectory written as CSV loads back to the same transitions (bitwise) with
//   the same Δt;
// - bad trajectories are InputErrors naming the problem and the line: NaN, a missing
//   column, two bodies, inconsistent body counts, a varying time step, one frame only;
// - the parameter layout round-trips θ ↔ model, --learn lists parse and reject unknown
//   kinds, and learn flags set Parameter::learn.
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/polygon_scene.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace lcprelax::learn {
namespace {

PolygonModel truth_model() {
  PolygonModel m;
  Polygon p;
  p.vertices = {Vec2(-0.3, -0.2), Vec2(0.3, -0.2), Vec2(0.0, 0.3)};
  m.shape = recentred(p);
  m.mu = 0.3;
  m.mass = 2.0;
  m.inertia = 0.05;
  m.ground_angle = 0.1;
  return m;
}

std::string temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("lcprelax_polygon_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& name, const std::string& text) {
  try {
    load_polygon_dataset(temp_file(name, text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const std::string kHeader = "step,time,body,x,y,theta,vx,vy,omega\n";

TEST(LearnPolygonDataset, GenerationIsDeterministicAndHasContacts) {
  PolygonDataSettings s;
  s.trajectories = 3;
  s.steps = 40;
  const PolygonDataset a = generate_polygon_dataset(truth_model(), s), b = generate_polygon_dataset(truth_model(), s);
  ASSERT_GT(a.transitions.size(), 20u);
  ASSERT_EQ(a.transitions.size(), b.transitions.size());
  const SceneDataset as_scene = polygon_scene_dataset(truth_model(), a);  // the one-body scene
  ASSERT_EQ(as_scene.transitions.size(), a.transitions.size());
  for (std::size_t i = 0; i < a.transitions.size(); ++i) {
    EXPECT_EQ(a.transitions[i].v_next, b.transitions[i].v_next);
    EXPECT_EQ(as_scene.transitions[i].next_velocity[0], a.transitions[i].v_next);
    EXPECT_TRUE(transition_has_contact(as_scene.scene, as_scene.transitions[i])) << i;  // the simulator's rule
  }
  s.noise = 0.01;
  const PolygonDataset n = generate_polygon_dataset(truth_model(), s);
  ASSERT_EQ(n.transitions.size(), a.transitions.size());
  double sum2 = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < n.transitions.size(); ++i)
    for (int k = 0; k < 3; ++k, count += 2) {
      sum2 += std::pow(n.transitions[i].v(k) - a.transitions[i].v(k), 2);
      sum2 += std::pow(n.transitions[i].q_next(k) - a.transitions[i].q_next(k), 2);
    }
  EXPECT_NEAR(std::sqrt(sum2 / count), 0.01, 0.002);
}

TEST(LearnPolygonDataset, CsvRoundTrip) {
  PolygonDataSettings s;
  s.trajectories = 2;
  s.steps = 30;
  s.contact_only = false;
  const PolygonDataset a = generate_polygon_dataset(truth_model(), s);
  const auto path = std::filesystem::temp_directory_path() / "lcprelax_polygon_roundtrip.csv";
  write_polygon_trajectory(a, 1, path.string());
  const PolygonDataset b = load_polygon_dataset(path.string());
  ASSERT_EQ(b.transitions.size(), 30u);
  EXPECT_NEAR(b.dt, 0.01, 1e-15);
  for (std::size_t i = 0; i < 30; ++i) {
    const PolygonTransition& t = a.transitions[30 + i];
    EXPECT_EQ(b.transitions[i].q, t.q);
    EXPECT_EQ(b.transitions[i].v, t.v);
    EXPECT_EQ(b.transitions[i].v_next, t.v_next);
  }
}

TEST(LearnPolygonDataset, BadTrajectoriesNameTheProblem) {
  EXPECT_NE(error_of("nan.csv", kHeader + "0,0,0,0,1,0,0,0,0\n1,0.01,0,nan,1,0,0,0,0\n").find(":3:"), std::string::npos);
  EXPECT_NE(error_of("missing.csv", "step,time,body,x,y,theta,vx,vy\n0,0,0,0,1,0,0,0\n").find("omega"),
            std::string::npos);
  const std::string two = error_of("two.csv", kHeader + "0,0,0,0,1,0,0,0,0\n0,0,1,2,1,0,0,0,0\n1,0.01,0,0,1,0,0,0,0\n"
                                                         "1,0.01,1,2,1,0,0,0,0\n");
  EXPECT_NE(two.find("one polygon expected"), std::string::npos) << two;
  EXPECT_NE(two.find(":3:"), std::string::npos) << two;
  const std::string inconsistent =
      error_of("counts.csv", kHeader + "0,0,0,0,1,0,0,0,0\n1,0.01,0,0,1,0,0,0,0\n1,0.01,1,0,1,0,0,0,0\n");
  EXPECT_NE(inconsistent.find(":4"), std::string::npos) << inconsistent;
  const std::string dt = error_of("dt.csv", kHeader + "0,0,0,0,1,0,0,0,0\n1,0.01,0,0,1,0,0,0,0\n2,0.03,0,0,1,0,0,0,0\n");
  EXPECT_NE(dt.find(":4: step 2: time step"), std::string::npos) << dt;
  EXPECT_NE(error_of("one.csv", kHeader + "0,0,0,0,1,0,0,0,0\n").find("at least two frames"), std::string::npos);
}

TEST(LearnPolygonDataset, ParameterLayoutAndFlags) {
  const PolygonModel m = truth_model();
  const ParameterSet theta = make_polygon_parameters(m, parse_polygon_learn_flags("mu,vertices"));
  const PolygonLayout layout{3};
  ASSERT_EQ(theta.size(), layout.size());
  EXPECT_EQ(theta[layout.vertex_y(2)].name, "vertex2.y");
  EXPECT_TRUE(theta[PolygonLayout::kMu].learn);
  EXPECT_FALSE(theta[PolygonLayout::kMass].learn);
  EXPECT_FALSE(theta[layout.ground_angle()].learn);
  const PolygonModel back = polygon_model(theta);
  EXPECT_EQ(back.shape.vertices[2], m.shape.vertices[2]);
  EXPECT_EQ(back.ground_angle, m.ground_angle);
  EXPECT_THROW(parse_polygon_learn_flags("mu,friction"), InputError);
  EXPECT_THROW(parse_polygon_learn_flags("mu,mu"), InputError);
  PolygonModel bad = m;
  bad.mass = -1.0;
  EXPECT_THROW(make_polygon_parameters(bad, PolygonLearnFlags{}), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
