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
// Optional applied-force columns fx, fy, torque (N, N, N·m): the generalized force applied
// to the body during the step from this frame to the next (the `applied` argument of
// Simulator::step), gravity acting in addition. A file has all three or none; without them
// the forces are zero (TrajectoryFrame::applied is then empty). The writer writes them only
// when constructed with `applied_columns = true`.
//
// Reader rules (violations throw lcprelax::InputError "SOURCE:LINE: message"; line 1 is the
// header):
// - the header holds exactly the nine column names above, or those and fx, fy, torque, in
//   any order (missing, unknown or repeated names are errors, and so is a header with only
//   some of fx, fy, torque); cells are separated by ',' without quoting; a trailing '\r'
//   is ignored and blank lines are skipped;
// - every row has as many cells as the header (9 or 12), each a finite decimal number (no
//   NaN/Inf, no empty cells), step and body integers;
// - consecutive rows with the same step form one frame; steps strictly increase; within a
//   frame the bodies are 0, 1, 2, ... in order and the time is the same in every row;
// - every frame has as many bodies as the first one;
// - limits (core/text_input.hpp): lines of at most 1 MiB, no NUL bytes, a leading UTF-8 BOM
//   skipped, cells echoed in messages cut to 64 characters.
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
  /// Per body (fx, fy, τ) (N, N, N·m) applied during the step to the next frame; empty when
  /// the file has no force columns (zero forces) or the frame was built without them.
  std::vector<Vec3> applied{};
  /// Line of the frame's first row in the file read (1 = header), 0 when not read from a file.
  int line = 0;
};

/// Streams frames as CSV rows; writes the header line on construction.
class TrajectoryWriter {
 public:
  /// Writes to `out`, which must outlive the writer; with `applied_columns` the header and
  /// every row also have fx, fy, torque.
  explicit TrajectoryWriter(std::ostream& out, bool applied_columns = false);
  /// Creates (truncates) the file `path`; throws std::runtime_error if it cannot be opened.
  explicit TrajectoryWriter(const std::string& path, bool applied_columns = false);

  /// One row per body of `world` (pose and velocity), for the given step and time; zero
  /// applied forces when the writer has the force columns.
  void write(int step, double time, const World& world);
  /// As above with the forces applied during the step: `applied` is empty (zero) or has one
  /// (fx, fy, τ) per body. Throws std::invalid_argument for another size, or for non-empty
  /// `applied` on a writer without force columns (they would be lost).
  void write(int step, double time, const World& world, const std::vector<Vec3>& applied);
  /// One row per body of `frame` (pose and velocity must have the same size; applied empty
  /// or the same size, and empty unless the writer has the force columns: std::invalid_argument).
  void write(const TrajectoryFrame& frame);
  bool has_applied_columns() const { return applied_columns_; }
  /// Flushes; throws std::runtime_error if the stream is in a failed state.
  void flush();

 private:
  void header();
  void check_applied(const std::vector<Vec3>& applied, std::size_t bodies) const;
  void row(int step, double time, int body, const Vec3& pose, const Vec3& velocity, const Vec3& applied);

  std::unique_ptr<std::ofstream> file_;
  std::ostream* out_ = nullptr;
  bool applied_columns_ = false;
  std::string buffer_;
};

/// Reads a trajectory; `source_name` prefixes error messages.
std::vector<TrajectoryFrame> read_trajectory(std::istream& in, const std::string& source_name);
/// Reads the trajectory file `path` (InputError "PATH: cannot open file" if missing).
std::vector<TrajectoryFrame> load_trajectory(const std::string& path);

}  // namespace lcprelax
