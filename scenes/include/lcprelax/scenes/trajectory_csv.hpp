#pragma once
// Trajectories as CSV (docs/formats.md): a header line, then one row per body per step.
//
//   step,time,body,x,y,theta,vx,vy,omega
//   0,0,0,0,0.5,0,0,0,0
//   0,0,1,1.5,0.5,0,0,0,0
//   1,0.01,0,...
//
// Units SI: time s; x, y m (centre of mass); theta rad (counter-clockwise); vx, vy m/s;
// omega rad/s. `step` and `body` are integers ≥ 0. Numbers are written locale-independently
// with 17 significant digits (printf "%.17g"), so a written trajectory reads back exactly.
//
// Reader rules (violations throw lcprelax::InputError "SOURCE:LINE: message"; line 1 is the
// header):
// - the header holds exactly the nine column names above, in any order (missing, unknown or
//   repeated names are errors); cells are separated by ',' without quoting; a trailing '\r'
//   is ignored and blank lines are skipped;
// - every row has nine cells, each a finite decimal number (no NaN/Inf, no empty cells),
//   step and body integers;
// - consecutive rows with the same step form one frame; steps strictly increase; within a
//   frame the bodies are 0, 1, 2, ... in order and the time is the same in every row;
// - every frame has as many bodies as the first one.
#include <lcprelax/world/world.hpp>

#include <fstream>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace lcprelax {

/// The state of every body at one step.
struct TrajectoryFrame {
  int step = 0;
  double time = 0.0;             ///< s
  std::vector<Vec3> pose;        ///< per body (x, y, θ)
  std::vector<Vec3> velocity;    ///< per body (vx, vy, ω)
};

/// Streams frames as CSV rows; writes the header line on construction.
class TrajectoryWriter {
 public:
  /// Writes to `out`, which must outlive the writer.
  explicit TrajectoryWriter(std::ostream& out);
  /// Creates (truncates) the file `path`; throws std::runtime_error if it cannot be opened.
  explicit TrajectoryWriter(const std::string& path);

  /// One row per body of `world` (pose and velocity), for the given step and time.
  void write(int step, double time, const World& world);
  /// One row per body of `frame` (pose and velocity must have the same size).
  void write(const TrajectoryFrame& frame);
  /// Flushes; throws std::runtime_error if the stream is in a failed state.
  void flush();

 private:
  void row(int step, double time, int body, const Vec3& pose, const Vec3& velocity);

  std::unique_ptr<std::ofstream> file_;
  std::ostream* out_ = nullptr;
  std::string buffer_;
};

/// Reads a trajectory; `source_name` prefixes error messages.
std::vector<TrajectoryFrame> read_trajectory(std::istream& in, const std::string& source_name);
/// Reads the trajectory file `path` (InputError "PATH: cannot open file" if missing).
std::vector<TrajectoryFrame> load_trajectory(const std::string& path);

}  // namespace lcprelax
