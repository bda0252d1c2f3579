// Scene datasets (learn/scene_dataset.hpp): seeded generation is bitwise reproducible,
// pushes are recorded and give the Simulator's velocity change, contact-free transitions
// are dropped by the simulator's rule, generate → write → load reproduces the transitions
// bit for bit, shape classes, and every bad input is an InputError naming the file and line.
#include <gtest/gtest.h>

#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace lcprelax::learn {
namespace {

bool same(const SceneTransition& a, const SceneTransition& b) {
  return a.step == b.step && a.pose == b.pose && a.velocity == b.velocity && a.applied == b.applied &&
         a.next_pose == b.next_pose && a.next_velocity == b.next_velocity;
}

bool same(const std::vector<SceneTransition>& a, const std::vector<SceneTransition>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!same(a[k], b[k])) return false;
  return true;
}

RigidBody box(double size, double density, const Vec3& pose) {
  const double h = 0.5 * size;
  return make_body(Polygon{{{-h, -h}, {h, -h}, {h, h}, {-h, h}}}, density, pose);
}

// Ground, one static box, a box resting on the ground and a box falling from 1 m.
Scene small_scene() {
  Scene s;
  s.world.half_planes.push_back(HalfPlane{});
  RigidBody fixed = box(0.2, 1000, Vec3(-1.0, 0.1, 0.0));
  fixed.is_static = true;
  s.world.bodies.push_back(fixed);
  s.world.bodies.push_back(box(0.1, 1000, Vec3(0.0, 0.05, 0.0)));
  s.world.bodies.push_back(box(0.1, 1000, Vec3(1.0, 1.0, 0.3)));
  s.steps = 40;
  return s;
}

std::string temp(const std::string& name) { return testing::TempDir() + "/lcprelax_scene_dataset_" + name; }

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(SceneDataset, SameSeedSameDataBitwiseOtherSeedDiffers) {
  const Scene pile = make_learning_pile(12, 3, ContactModel::lcp);
  SceneDatasetSettings st;
  st.steps = 15;
  st.seed = 7;
  st.pose_noise = 1e-4;
  st.velocity_noise = 1e-3;
  const SceneDataset a = generate_scene_dataset(pile, st), b = generate_scene_dataset(pile, st);
  ASSERT_FALSE(a.transitions.empty());
  EXPECT_TRUE(same(a.transitions, b.transitions));
  a.validate();
  st.threads = 2;  // islands in parallel: the same data
  EXPECT_TRUE(same(a.transitions, generate_scene_dataset(pile, st).transitions));
  st.seed = 8;
  const SceneDataset c = generate_scene_dataset(pile, st);
  EXPECT_FALSE(same(a.transitions, c.transitions));
  // The pile itself is seeded too.
  const Scene other = make_learning_pile(12, 4, ContactModel::lcp);
  EXPECT_EQ(write_scene(pile), write_scene(make_learning_pile(12, 3, ContactModel::lcp)));
  EXPECT_NE(write_scene(pile), write_scene(other));
}

TEST(SceneDataset, ShapeClassesByFirstAppearance) {
  const Scene pile = make_learning_pile(LearningPileOptions{20, 3, 5, ContactModel::convex, 0.4, 1e-2, 1e-2});
  const std::vector<int> cls = scene_shape_classes(pile.world);
  ASSERT_EQ(cls.size(), 20u);
  EXPECT_EQ(cls[0], 0);
  EXPECT_EQ(cls[1], 1);
  EXPECT_EQ(cls[2], 2);
  for (std::size_t i = 0; i < cls.size(); ++i) {
    ASSERT_GE(cls[i], 0);
    ASSERT_LT(cls[i], 3);
    EXPECT_EQ(pile.world.bodies[i].mass, pile.world.bodies[static_cast<std::size_t>(cls[i])].mass);
  }
  Scene s = small_scene();
  s.world.bodies.push_back(s.world.bodies[1]);  // same class as body 1
  s.world.bodies.back().pose.x() = 0.3;
  s.world.bodies.push_back(s.world.bodies[1]);
  s.world.bodies.back().pose.x() = 0.6;
  s.world.bodies.back().inertia *= 1.0 + 1e-15;  // any difference is another class
  EXPECT_EQ(scene_shape_classes(s.world), (std::vector<int>{-1, 0, 0, 0, 1}));
  const SceneDataset d = generate_scene_dataset(s, SceneDatasetSettings{});
  EXPECT_EQ(d.shape_class, scene_shape_classes(s.world));
  EXPECT_EQ(d.num_shape_classes(), 2);
}

TEST(SceneDataset, PushesGiveTheSimulatorsVelocityChange) {
  Scene s = small_scene();
  s.settings.warm_start = false;  // so that one step from a recorded state reproduces it
  SceneDatasetSettings st;
  st.steps = 20;
  st.push_fraction = 1.0;
  st.push_interval = 3;
  st.drop_without_contact = false;
  const SceneDataset d = generate_scene_dataset(s, st);
  ASSERT_EQ(d.transitions.size(), 20u);
  EXPECT_EQ(d.generation.pushed_bodies, 2);
  const Vec2 g = s.world.gravity;
  for (const SceneTransition& t : d.transitions) {
    EXPECT_EQ(t.applied[0], Vec3::Zero());  // static
    for (int i : {1, 2}) {
      const double f = t.applied[i].head<2>().norm();
      EXPECT_GE(f, st.push_force_min);
      EXPECT_LE(f, st.push_force_max);
      EXPECT_LE(std::abs(t.applied[i](2)), st.push_torque_max);
    }
    // Held for push_interval steps, then redrawn.
    if (t.step % st.push_interval != 0) {
      EXPECT_EQ(t.applied, d.transitions[t.step - 1].applied);
    } else if (t.step > 0) {
      EXPECT_NE(t.applied, d.transitions[t.step - 1].applied);
    }
    // Body 2 flies freely (it starts 1 m up; 20 steps fall < 0.3 m): v⁺ = v + Δt(g + M⁻¹u).
    const RigidBody& b = s.world.bodies[2];
    const Vec3 expected = t.velocity[2] + s.settings.dt * Vec3(g.x() + t.applied[2](0) / b.mass,
                                                               g.y() + t.applied[2](1) / b.mass,
                                                               t.applied[2](2) / b.inertia);
    EXPECT_NEAR((t.next_velocity[2] - expected).norm(), 0.0, 1e-12) << "step " << t.step;
    // One simulator step from the recorded state gives the recorded next state exactly.
    Scene at = s;
    for (std::size_t i = 0; i < at.world.bodies.size(); ++i) {
      at.world.bodies[i].pose = t.pose[i];
      at.world.bodies[i].velocity = t.velocity[i];
    }
    Simulator sim = make_simulator(at);
    sim.step(t.applied);
    for (std::size_t i = 0; i < at.world.bodies.size(); ++i) {
      EXPECT_EQ(sim.world().bodies[i].velocity, t.next_velocity[i]) << "step " << t.step << " body " << i;
      EXPECT_EQ(sim.world().bodies[i].pose, t.next_pose[i]) << "step " << t.step << " body " << i;
    }
  }
  // Body 1 rests on the ground and is pushed: its velocity changes, not by free flight.
  EXPECT_GT(d.generation.contacts, 0);
}

TEST(SceneDataset, TransitionsWithoutContactAreDropped) {
  // A box falling 0.5 m onto the ground: about 30 steps of free flight, then contact.
  Scene s;
  s.world.half_planes.push_back(HalfPlane{});
  s.world.bodies.push_back(box(0.1, 1000, Vec3(0.0, 0.55, 0.2)));
  SceneDatasetSettings st;
  st.steps = 60;
  st.push_fraction = 0.0;
  const SceneDataset kept = generate_scene_dataset(s, st);
  st.drop_without_contact = false;
  const SceneDataset all = generate_scene_dataset(s, st);
  ASSERT_EQ(all.transitions.size(), 60u);
  EXPECT_GT(kept.generation.dropped_without_contact, 10);
  EXPECT_EQ(kept.transitions.size() + static_cast<std::size_t>(kept.generation.dropped_without_contact), 60u);
  ASSERT_FALSE(kept.transitions.empty());
  // The kept ones are exactly those with a contact by the simulator's rule.
  std::vector<SceneTransition> with_contact;
  for (const SceneTransition& t : all.transitions)
    if (transition_has_contact(s, t)) with_contact.push_back(t);
  EXPECT_TRUE(same(kept.transitions, with_contact));
  EXPECT_EQ(kept.transitions.front().step, kept.generation.dropped_without_contact);
}

TEST(SceneDataset, WriteThenLoadGivesTheSameTransitions) {
  Scene s = small_scene();
  s.settings.model = ContactModel::convex;
  SceneDatasetSettings st;
  st.steps = 25;
  st.drop_without_contact = false;
  st.pose_noise = 1e-3;
  st.velocity_noise = 1e-2;
  const SceneDataset d = generate_scene_dataset(s, st);
  const std::string json = temp("rt.json"), csv = temp("rt.csv");
  write_scene_dataset(d, json, csv);
  EXPECT_EQ(read_text(csv).rfind("step,time,body,x,y,theta,vx,vy,omega,fx,fy,torque\n", 0), 0u);
  const SceneDataset back = load_scene_dataset(json, csv);
  EXPECT_TRUE(same(d.transitions, back.transitions));
  EXPECT_EQ(back.shape_class, d.shape_class);
  EXPECT_EQ(back.scene.settings.dt, s.settings.dt);
  EXPECT_EQ(back.scene.settings.model, ContactModel::convex);
  EXPECT_EQ(back.scene.steps, 25);
  EXPECT_EQ(write_scene(back.scene), write_scene(d.scene));

  // Without noise, loading with the contact filter gives what generation kept.
  Scene fall;
  fall.world.half_planes.push_back(HalfPlane{});
  fall.world.bodies.push_back(box(0.1, 1000, Vec3(0.0, 0.3, 0.2)));
  fall.world.bodies.push_back(box(0.1, 1000, Vec3(0.5, 0.2, 0.0)));
  st.pose_noise = st.velocity_noise = 0.0;
  st.steps = 40;
  write_scene_dataset(generate_scene_dataset(fall, st), json, csv);
  st.drop_without_contact = true;
  const SceneDataset kept = generate_scene_dataset(fall, st);
  EXPECT_GT(kept.generation.dropped_without_contact, 0);
  EXPECT_TRUE(same(kept.transitions, load_scene_dataset(json, csv, true).transitions));
  // A dataset with a gap cannot be written as one trajectory.
  SceneDataset gap = kept;
  ASSERT_GE(gap.transitions.size(), 3u);
  gap.transitions.erase(gap.transitions.begin() + 1);
  EXPECT_THROW(write_scene_dataset(gap, json, csv), InputError);
  // Nor one whose states do not chain.
  SceneDataset broken = kept;
  broken.transitions[1].pose[0].x() += 1e-9;
  EXPECT_THROW(write_scene_dataset(broken, json, csv), InputError);
  std::remove(json.c_str());
  std::remove(csv.c_str());
}

// load_scene_dataset of `scene` and the CSV text throws InputError containing `part`.
void expect_load_error(const Scene& scene, const std::string& csv_text, const std::string& part) {
  const std::string json = temp("bad.json"), csv = temp("bad.csv");
  save_scene(json, scene);
  write_text(csv, csv_text);
  try {
    load_scene_dataset(json, csv);
    ADD_FAILURE() << "no error; expected: " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
  std::remove(json.c_str());
  std::remove(csv.c_str());
}

TEST(SceneDataset, BadInputNamesFileAndLine) {
  const Scene s = small_scene();  // 3 bodies, body 0 static at (-1, 0.1, 0), dt 0.01, 40 steps
  const std::string csv = temp("bad.csv");
  const std::string h = "step,time,body,x,y,theta,vx,vy,omega\n";
  const std::string hf = "step,time,body,x,y,theta,vx,vy,omega,fx,fy,torque\n";
  auto frame = [](int step, double time, const std::string& static_row = "-1,0.1,0,0,0,0") {
    std::ostringstream os;
    os.precision(17);
    os << step << "," << time << ",0," << static_row << "\n"
       << step << "," << time << ",1,0,0.05,0,0,0,0\n"
       << step << "," << time << ",2,1,1,0.3,0,0,0\n";
    return os.str();
  };
  // A valid file loads: 2 transitions, zero forces.
  {
    const std::string json = temp("ok.json");
    save_scene(json, s);
    write_text(csv, h + frame(0, 0.0) + frame(1, 0.01) + frame(2, 0.02));
    const SceneDataset d = load_scene_dataset(json, csv);
    ASSERT_EQ(d.transitions.size(), 2u);
    EXPECT_EQ(d.transitions[1].applied, std::vector<Vec3>(3, Vec3::Zero()));
    std::remove(json.c_str());
  }
  Scene five = s;
  five.world.bodies.push_back(s.world.bodies[1]);
  five.world.bodies.push_back(s.world.bodies[1]);
  expect_load_error(five, h + frame(0, 0.0) + frame(1, 0.01), csv + ":2: frame has 3 bodies, the scene has 5");
  expect_load_error(s, h + frame(0, 0.0), csv + ": 1 frame(s); at least two");
  expect_load_error(s, h, csv + ": 0 frame(s)");
  expect_load_error(s, h + frame(0, 0.0) + frame(1, 0.01) + frame(3, 0.03),
                    csv + ":8: step 3 follows step 1 (steps must be consecutive)");
  expect_load_error(s, h + frame(0, 0.0) + frame(1, 0.02), csv + ":5: step 1: time difference");
  expect_load_error(s, h + frame(40, 0.4) + frame(41, 0.41), csv + ":5: step 41 is beyond the scene's 40 steps");
  expect_load_error(s, h + frame(0, 0.0) + frame(1, 0.01, "-1,0.1,1e-3,0,0,0"),
                    csv + ":5: step 1, body 0: static body moves");
  expect_load_error(s, h + frame(0, 0.0) + frame(1, 0.01, "-1,0.1,0,0,0.5,0"),
                    csv + ":5: step 1, body 0: static body has velocity");
  expect_load_error(s, h + frame(0, 0.0) + "1,0.01,0,-1,0.1,0,0,0,0\n1,0.01,1,0,nan,0,0,0,0\n",
                    csv + ":6: column 'y': not finite 'nan'");
  // Force columns: a force on the static body, NaN in a force.
  std::string withf;
  for (int k = 0; k < 2; ++k)
    withf += std::to_string(k) + ",0.0" + std::to_string(k) + ",0,-1,0.1,0,0,0,0,0,0," + (k ? "2" : "0") + "\n" +
             std::to_string(k) + ",0.0" + std::to_string(k) + ",1,0,0.05,0,0,0,0,1,2,3\n" + std::to_string(k) +
             ",0.0" + std::to_string(k) + ",2,1,1,0.3,0,0,0,0,0,0\n";
  expect_load_error(s, hf + withf, csv + ":5: step 1, body 0: static body has an applied force");
  expect_load_error(s, hf + "0,0,0,-1,0.1,0,0,0,0,0,0,0\n0,0,1,0,0.05,0,0,0,0,-nan,0,0\n",
                    csv + ":3: column 'fx': not finite");
  // Files that do not exist or do not parse name their path.
  try {
    load_scene_dataset(temp("missing.json"), csv);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos) << e.what();
  }
  const std::string json = temp("ok.json");
  save_scene(json, s);
  try {
    load_scene_dataset(json, temp("missing.csv"));
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.csv: cannot open file"), std::string::npos) << e.what();
  }
  std::remove(json.c_str());
}

TEST(SceneDataset, SettingsErrorsNameTheField) {
  const Scene s = small_scene();
  auto expect_field = [&](SceneDatasetSettings st, const std::string& field) {
    EXPECT_EQ(st.validation_error().rfind(field, 0), 0u) << st.validation_error();
    try {
      generate_scene_dataset(s, st);
      ADD_FAILURE() << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  SceneDatasetSettings st;
  EXPECT_EQ(st.validation_error(), "");
  st.steps = 0;
  expect_field(st, "steps");
  st = {};
  st.push_fraction = 1.5;
  expect_field(st, "push_fraction");
  st = {};
  st.push_interval = 0;
  expect_field(st, "push_interval");
  st = {};
  st.push_force_max = 1.0;  // < push_force_min
  expect_field(st, "push_force_max");
  st = {};
  st.push_torque_max = -1.0;
  expect_field(st, "push_torque_max");
  st = {};
  st.pose_noise = NAN;
  expect_field(st, "pose_noise");
  st = {};
  st.velocity_noise = -1.0;
  expect_field(st, "velocity_noise");
  EXPECT_THROW(make_learning_pile(0, 1, ContactModel::lcp), InputError);
  EXPECT_THROW(make_learning_pile(LearningPileOptions{10, 5, 1, ContactModel::lcp, 0.5, 1e-2, 1e-2}), InputError);
}

TEST(SceneDataset, LargePileGenerates) {
  const Scene pile = make_learning_pile(200, 1, ContactModel::lcp);
  ASSERT_EQ(pile.world.bodies.size(), 200u);
  SceneDatasetSettings st;
  st.steps = 5;
  const auto t0 = std::chrono::steady_clock::now();
  const SceneDataset d = generate_scene_dataset(pile, st);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(d.transitions.size(), 5u);  // the bottom row touches the ground from step 0
  EXPECT_EQ(d.generation.pushed_bodies, 50);
  EXPECT_EQ(d.num_shape_classes(), 3);
  d.validate();
  std::printf("200-body learning pile, 5 steps: %.3f s, %ld contacts over the transitions\n", seconds,
              d.generation.contacts);
}

}  // namespace
}  // namespace lcprelax::learn
