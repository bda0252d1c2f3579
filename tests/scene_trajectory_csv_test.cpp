// Trajectory CSV: written frames read back bit for bit (17 significant digits), and every
// malformed file throws InputError "SOURCE:LINE: ..." at the offending line.
#include <gtest/gtest.h>

#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace lcprelax {
namespace {

const char* const kHeader = "step,time,body,x,y,theta,vx,vy,omega\n";

// read_trajectory(text) throws InputError whose message contains `part`.
void expect_error(const std::string& text, const std::string& part) {
  std::istringstream in(text);
  try {
    read_trajectory(in, "traj.csv");
    ADD_FAILURE() << "no error; expected: " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

World two_bodies() {
  World w;
  w.bodies.resize(2);
  w.bodies[0].pose = Vec3(0.1, 1.0 / 3.0, -std::acos(-1.0));
  w.bodies[0].velocity = Vec3(1e-300, -2.5e17, std::sqrt(2.0));
  w.bodies[1].pose = Vec3(-0.0, 123456.789, 1e-7);
  w.bodies[1].velocity = Vec3(0, 0, 0);
  return w;
}

TEST(TrajectoryCsv, RoundTripIsExact) {
  World w = two_bodies();
  std::ostringstream out;
  TrajectoryWriter writer(out);
  writer.write(0, 0.0, w);
  w.bodies[1].pose.y() += 0.01;
  writer.write(1, 0.01, w);
  TrajectoryFrame f{7, 0.07, {Vec3(1, 2, 3), Vec3(4, 5, 6)}, {Vec3(-1, -2, -3), Vec3(0.1, 0.2, 0.3)}};
  writer.write(f);
  writer.flush();
  EXPECT_EQ(out.str().rfind(kHeader, 0), 0u);

  std::istringstream in(out.str());
  const std::vector<TrajectoryFrame> frames = read_trajectory(in, "mem");
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].step, 0);
  EXPECT_EQ(frames[1].time, 0.01);
  EXPECT_EQ(frames[2].step, 7);
  ASSERT_EQ(frames[1].pose.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(frames[1].pose[i], w.bodies[i].pose);
    EXPECT_EQ(frames[1].velocity[i], w.bodies[i].velocity);
    EXPECT_EQ(frames[2].pose[i], f.pose[i]);
    EXPECT_EQ(frames[2].velocity[i], f.velocity[i]);
  }
}

TEST(TrajectoryCsv, FileRoundTripAndLenientFormatting) {
  const std::string path = testing::TempDir() + "/lcprelax_trajectory_test.csv";
  {
    TrajectoryWriter writer(path);
    writer.write(0, 0.0, two_bodies());
  }
  EXPECT_EQ(load_trajectory(path).at(0).pose.at(1), two_bodies().bodies[1].pose);
  std::remove(path.c_str());
  // Columns in another order, CRLF line ends, spaces around cells, blank lines, '+' signs.
  std::istringstream in("body,step,time,omega,vy,vx,theta,y,x\r\n\r\n 0 , 3, 0.5,+1,2,3,4,5,6\r\n");
  const auto frames = read_trajectory(in, "mem");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].step, 3);
  EXPECT_EQ(frames[0].pose[0], Vec3(6, 5, 4));
  EXPECT_EQ(frames[0].velocity[0], Vec3(3, 2, 1));
  std::istringstream header_only(kHeader);
  EXPECT_TRUE(read_trajectory(header_only, "mem").empty());
}

TEST(TrajectoryCsv, HeaderErrors) {
  expect_error("", "traj.csv:1: missing header line");
  expect_error("step,time,body,x,y,theta,vx,vy\n", "traj.csv:1: missing column 'omega'");
  expect_error("step,time,body,x,y,theta,vx,vy,omega,z\n", "traj.csv:1: unknown column 'z'");
  expect_error("step,time,body,x,x,theta,vx,vy,omega\n", "traj.csv:1: column 'x' appears twice");
}

TEST(TrajectoryCsv, CellErrorsNameTheLine) {
  const std::string ok = std::string(kHeader) + "0,0,0,1,2,3,4,5,6\n";
  expect_error(ok + "1,0.1,0,1,2,3,4,5\n", "traj.csv:3: expected 9 cells, got 8");
  expect_error(ok + "1,0.1,0,1,abc,3,4,5,6\n", "traj.csv:3: column 'y': not a number 'abc'");
  expect_error(ok + "1,0.1,0,1,2,3,4,5,6x\n", "traj.csv:3: column 'omega': not a number '6x'");
  expect_error(ok + "1,0.1,0,1,2,nan,4,5,6\n", "traj.csv:3: column 'theta': not finite 'nan'");
  expect_error(ok + "1,0.1,0,1,2,3,-inf,5,6\n", "traj.csv:3: column 'vx': not finite '-inf'");
  expect_error(ok + "1,0.1,0,1,2,3,4,,6\n", "traj.csv:3: column 'vy': empty cell");
  expect_error(ok + "1,0.1,0,1e999,2,3,4,5,6\n", "traj.csv:3: column 'x': value out of range");
  expect_error(ok + "1.5,0.1,0,1,2,3,4,5,6\n", "traj.csv:3: column 'step': expected an integer");
  expect_error(ok + "1,0.1,-1,1,2,3,4,5,6\n", "traj.csv:3: column 'body': expected an integer");
}

TEST(TrajectoryCsv, FrameStructureErrorsNameTheLine) {
  const std::string h = kHeader;
  const std::string s0 = "0,0,0,1,2,3,4,5,6\n0,0,1,1,2,3,4,5,6\n";  // lines 2-3: step 0, two bodies
  // Step 1 has one body: detected when step 2 starts; reported at the frame's last line (4).
  expect_error(h + s0 + "1,0.1,0,1,2,3,4,5,6\n2,0.2,0,1,2,3,4,5,6\n",
               "traj.csv:4: step 1 ends after 1 bodies, but step 0 has 2");
  // ... or at the end of the file.
  expect_error(h + s0 + "1,0.1,0,1,2,3,4,5,6\n\n", "traj.csv:4: step 1 ends after 1 bodies");
  // Step 1 has three bodies.
  expect_error(h + s0 + "1,0.1,0,1,2,3,4,5,6\n1,0.1,1,1,2,3,4,5,6\n1,0.1,2,1,2,3,4,5,6\n",
               "traj.csv:6: step 1 has more bodies than step 0 (2)");
  expect_error(h + s0 + "1,0.1,1,1,2,3,4,5,6\n", "traj.csv:4: step 1: expected body 0, got 1");
  expect_error(h + "0,0,0,1,2,3,4,5,6\n0,0,0,1,2,3,4,5,6\n", "traj.csv:3: step 0: expected body 1, got 0");
  expect_error(h + "0,0,0,1,2,3,4,5,6\n0,0.5,1,1,2,3,4,5,6\n", "traj.csv:3: step 0: time differs");
  expect_error(h + s0 + "1,0.1,0,1,2,3,4,5,6\n1,0.1,1,1,2,3,4,5,6\n0,0.2,0,1,2,3,4,5,6\n",
               "traj.csv:6: step 0 after step 1");
}

}  // namespace
}  // namespace lcprelax
