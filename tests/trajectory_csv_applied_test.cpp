// Trajectory CSV, optional applied-force columns fx, fy, torque: written only when asked,
// read back bit for bit, all three or none, errors naming the line; files without them read
// as before (empty `applied`), and every frame records the line of its first row.
#include <gtest/gtest.h>

#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/core/errors.hpp>

#include <sstream>
#include <stdexcept>

namespace lcprelax {
namespace {

const std::string kHeader = "step,time,body,x,y,theta,vx,vy,omega";

void expect_error(const std::string& text, const std::string& part) {
  std::istringstream in(text);
  try {
    read_trajectory(in, "traj.csv");
    ADD_FAILURE() << "no error; expected: " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

std::vector<TrajectoryFrame> read(const std::string& text) {
  std::istringstream in(text);
  return read_trajectory(in, "mem");
}

TEST(TrajectoryCsvApplied, RoundTripWithForcesIsExact) {
  World w;
  w.bodies.resize(2);
  w.bodies[0].pose = Vec3(0.1, 1.0 / 3.0, -2.0);
  w.bodies[1].velocity = Vec3(1e-300, -2.5e17, 0.7);
  const std::vector<Vec3> u = {Vec3(12.5, -1.0 / 7.0, 1e-3), Vec3(-0.0, 3e200, -4.25)};
  std::ostringstream out;
  TrajectoryWriter writer(out, true);
  EXPECT_TRUE(writer.has_applied_columns());
  writer.write(0, 0.0, w, u);
  writer.write(1, 0.01, w);  // zero forces
  writer.write(TrajectoryFrame{2, 0.02, {Vec3(1, 2, 3), Vec3(4, 5, 6)}, {Vec3(0, 0, 0), Vec3(1, 1, 1)}, u});
  writer.flush();
  EXPECT_EQ(out.str().rfind(kHeader + ",fx,fy,torque\n", 0), 0u);

  const std::vector<TrajectoryFrame> frames = read(out.str());
  ASSERT_EQ(frames.size(), 3u);
  for (const TrajectoryFrame& f : frames) ASSERT_EQ(f.applied.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(frames[0].applied[i], u[i]);
    EXPECT_EQ(frames[1].applied[i], Vec3::Zero());
    EXPECT_EQ(frames[2].applied[i], u[i]);
    EXPECT_EQ(frames[0].pose[i], w.bodies[i].pose);
    EXPECT_EQ(frames[0].velocity[i], w.bodies[i].velocity);
  }
  // Lines of each frame's first row: header 1, two rows per frame.
  EXPECT_EQ(frames[0].line, 2);
  EXPECT_EQ(frames[1].line, 4);
  EXPECT_EQ(frames[2].line, 6);
}

TEST(TrajectoryCsvApplied, WithoutColumnsNothingChanges) {
  World w;
  w.bodies.resize(1);
  std::ostringstream out;
  TrajectoryWriter writer(out);  // default: no force columns
  EXPECT_FALSE(writer.has_applied_columns());
  writer.write(0, 0.0, w);
  writer.flush();
  EXPECT_EQ(out.str(), kHeader + "\n0,0,0,0,0,0,0,0,0\n");
  const auto frames = read(out.str());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(frames[0].applied.empty());
  // Forces given to a writer without the columns would be lost: refused.
  EXPECT_THROW(writer.write(1, 0.01, w, {Vec3(1, 0, 0)}), std::invalid_argument);
  TrajectoryWriter with(out, true);
  EXPECT_THROW(with.write(1, 0.01, w, {Vec3(1, 0, 0), Vec3(1, 0, 0)}), std::invalid_argument);
}

TEST(TrajectoryCsvApplied, ColumnsInAnyOrderAndBlankLinesKeepLines) {
  const auto frames = read("torque,fy,fx," + kHeader + "\n\n3,2,1,0,0,0,1,2,3,4,5,6\n");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].applied.at(0), Vec3(1, 2, 3));
  EXPECT_EQ(frames[0].pose.at(0), Vec3(1, 2, 3));
  EXPECT_EQ(frames[0].line, 3);
}

TEST(TrajectoryCsvApplied, ErrorsNameTheLine) {
  const std::string h = kHeader + ",fx,fy,torque\n";
  expect_error(kHeader + ",fx,fy\n", "traj.csv:1: missing column 'torque' (fx, fy, torque go together)");
  expect_error(kHeader + ",torque\n", "traj.csv:1: missing column 'fx'");
  expect_error(kHeader + ",fx,fy,torque,fx\n", "traj.csv:1: column 'fx' appears twice");
  expect_error(h + "0,0,0,1,2,3,4,5,6\n", "traj.csv:2: expected 12 cells, got 9");
  expect_error(h + "0,0,0,1,2,3,4,5,6,1,2,3\n1,0.1,0,1,2,3,4,5,6,nan,2,3\n", "traj.csv:3: column 'fx': not finite 'nan'");
  expect_error(h + "0,0,0,1,2,3,4,5,6,1,2,inf\n", "traj.csv:2: column 'torque': not finite 'inf'");
  expect_error(h + "0,0,0,1,2,3,4,5,6,1,,3\n", "traj.csv:2: column 'fy': empty cell");
  // The existing rules still hold with the force columns.
  expect_error(h + "0,0,0,1,2,3,4,5,6,1,2,3\n0,0,2,1,2,3,4,5,6,1,2,3\n", "traj.csv:3: step 0: expected body 1, got 2");
}

}  // namespace
}  // namespace lcprelax
