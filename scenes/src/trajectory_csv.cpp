// Trajectory CSV writer and reader (scenes/trajectory_csv.hpp).
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/text_input.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string_view>

namespace lcprelax {
namespace {

// The nine required columns, then the optional force columns (all three or none).
constexpr std::array<const char*, 12> kColumns = {"step", "time", "body", "x",  "y",  "theta",
                                                  "vx",   "vy",   "omega", "fx", "fy", "torque"};
constexpr std::size_t kRequiredColumns = 9;
enum Column { kStep, kTime, kBody, kX, kY, kTheta, kVx, kVy, kOmega, kFx, kFy, kTorque };

void append(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17);
  out.append(buf, r.ptr);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

TrajectoryWriter::TrajectoryWriter(std::ostream& out, bool applied_columns)
    : out_(&out), applied_columns_(applied_columns) {
  header();
}

TrajectoryWriter::TrajectoryWriter(const std::string& path, bool applied_columns)
    : file_(std::make_unique<std::ofstream>(path, std::ios::binary)), applied_columns_(applied_columns) {
  if (!*file_) throw std::runtime_error(path + ": cannot open trajectory file for writing");
  out_ = file_.get();
  header();
}

void TrajectoryWriter::header() {
  const std::size_t n = applied_columns_ ? kColumns.size() : kRequiredColumns;
  for (std::size_t c = 0; c < n; ++c) *out_ << (c ? "," : "") << kColumns[c];
  *out_ << '\n';
}

void TrajectoryWriter::check_applied(const std::vector<Vec3>& applied, std::size_t bodies) const {
  if (applied.empty()) return;
  if (!applied_columns_)
    throw std::invalid_argument("TrajectoryWriter::write: applied forces given, but the writer has no force columns");
  if (applied.size() != bodies)
    throw std::invalid_argument("TrajectoryWriter::write: applied has " + std::to_string(applied.size()) +
                                " entries for " + std::to_string(bodies) + " bodies");
}

void TrajectoryWriter::row(int step, double time, int body, const Vec3& pose, const Vec3& velocity,
                           const Vec3& applied) {
  buffer_ = std::to_string(step);
  buffer_ += ',';
  append(buffer_, time);
  buffer_ += ',' + std::to_string(body);
  for (int k = 0; k < 3; ++k) append(buffer_ += ',', pose[k]);
  for (int k = 0; k < 3; ++k) append(buffer_ += ',', velocity[k]);
  if (applied_columns_)
    for (int k = 0; k < 3; ++k) append(buffer_ += ',', applied[k]);
  buffer_ += '\n';
  out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
}

void TrajectoryWriter::write(int step, double time, const World& world) { write(step, time, world, {}); }

void TrajectoryWriter::write(int step, double time, const World& world, const std::vector<Vec3>& applied) {
  check_applied(applied, world.bodies.size());
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    row(step, time, static_cast<int>(i), world.bodies[i].pose, world.bodies[i].velocity,
        applied.empty() ? Vec3::Zero() : applied[i]);
}

void TrajectoryWriter::write(const TrajectoryFrame& frame) {
  if (frame.pose.size() != frame.velocity.size())
    throw std::invalid_argument("TrajectoryWriter::write: pose and velocity sizes differ");
  check_applied(frame.applied, frame.pose.size());
  for (std::size_t i = 0; i < frame.pose.size(); ++i)
    row(frame.step, frame.time, static_cast<int>(i), frame.pose[i], frame.velocity[i],
        frame.applied.empty() ? Vec3::Zero() : frame.applied[i]);
}

void TrajectoryWriter::flush() {
  out_->flush();
  if (!*out_) throw std::runtime_error("TrajectoryWriter: write failed");
}

std::vector<TrajectoryFrame> read_trajectory(std::istream& in, const std::string& source_name) {
  std::size_t line_no = 0;
  auto fail = [&](const std::string& message) -> void {
    throw InputError(text::clip_message(source_name + ":" + std::to_string(line_no) + ": " + message));
  };
  std::string line;
  // Lines of at most 1 MiB, no NUL bytes, a leading UTF-8 BOM skipped (core/text_input.hpp).
  text::LineInput lines(in, source_name);
  auto next_line = [&]() -> bool {  // next non-blank line, without a trailing '\r'
    while (lines.next(line)) {
      line_no = static_cast<std::size_t>(lines.line());
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos) return true;
    }
    return false;
  };

  // Header: each of the nine names exactly once, in any order, and fx, fy, torque all or none.
  std::array<int, kColumns.size()> column_of;  // Column -> cell index
  column_of.fill(-1);
  if (!next_line()) {
    line_no = 1;
    fail("missing header line (expected step,time,body,x,y,theta,vx,vy,omega)");
  }
  const std::vector<std::string_view> names = split(line);
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::size_t c = 0;
    while (c < kColumns.size() && names[i] != kColumns[c]) ++c;
    if (c == kColumns.size()) fail("unknown column " + text::quote(names[i]));
    if (column_of[c] >= 0) fail("column " + text::quote(names[i]) + " appears twice");
    column_of[c] = static_cast<int>(i);
  }
  for (std::size_t c = 0; c < kRequiredColumns; ++c)
    if (column_of[c] < 0) fail(std::string("missing column '") + kColumns[c] + "'");
  const bool has_applied = column_of[kFx] >= 0 || column_of[kFy] >= 0 || column_of[kTorque] >= 0;
  for (std::size_t c = kRequiredColumns; c < kColumns.size() && has_applied; ++c)
    if (column_of[c] < 0)
      fail(std::string("missing column '") + kColumns[c] + "' (fx, fy, torque go together)");
  const std::size_t columns = has_applied ? kColumns.size() : kRequiredColumns;

  std::vector<TrajectoryFrame> frames;
  std::size_t frame_last_line = 0;  // last line of the current frame
  auto check_complete = [&](const TrajectoryFrame& f) {
    if (frames.size() > 1 && f.pose.size() != frames.front().pose.size()) {
      line_no = frame_last_line;
      fail("step " + std::to_string(f.step) + " ends after " + std::to_string(f.pose.size()) +
           " bodies, but step " + std::to_string(frames.front().step) + " has " +
           std::to_string(frames.front().pose.size()));
    }
  };
  std::array<double, kColumns.size()> v{};
  while (next_line()) {
    const std::vector<std::string_view> cells = split(line);
    if (cells.size() != columns)
      fail("expected " + std::to_string(columns) + " cells, got " + std::to_string(cells.size()));
    for (std::size_t c = 0; c < columns; ++c) {
      std::string_view cell = cells[static_cast<std::size_t>(column_of[c])];
      while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
      while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t')) cell.remove_suffix(1);
      const std::string where = std::string("column '") + kColumns[c] + "': ";
      if (cell.empty()) fail(where + "empty cell");
      if (cell.size() > 1 && cell[0] == '+' && cell[1] != '-' && cell[1] != '+') cell.remove_prefix(1);
      const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v[c]);
      if (r.ec == std::errc::result_out_of_range) fail(where + "value out of range " + text::quote(cell));
      if (r.ec != std::errc() || r.ptr != cell.data() + cell.size())
        fail(where + "not a number " + text::quote(cell));
      if (!std::isfinite(v[c])) fail(where + "not finite " + text::quote(cell));
      if ((c == kStep || c == kBody) && (v[c] != std::floor(v[c]) || v[c] < 0.0 || v[c] > 2147483647.0))
        fail(where + "expected an integer >= 0, got " + text::quote(cell));
    }
    const int step = static_cast<int>(v[kStep]), body = static_cast<int>(v[kBody]);
    if (frames.empty() || step != frames.back().step) {
      if (!frames.empty()) {
        if (step < frames.back().step)
          fail("step " + std::to_string(step) + " after step " + std::to_string(frames.back().step) +
               " (steps must increase)");
        check_complete(frames.back());
      }
      frames.emplace_back();
      frames.back().step = step;
      frames.back().time = v[kTime];
      frames.back().line = static_cast<int>(line_no);
    }
    TrajectoryFrame& f = frames.back();
    if (body != static_cast<int>(f.pose.size()))
      fail("step " + std::to_string(step) + ": expected body " + std::to_string(f.pose.size()) +
           ", got " + std::to_string(body));
    if (frames.size() > 1 && f.pose.size() == frames.front().pose.size())
      fail("step " + std::to_string(step) + " has more bodies than step " +
           std::to_string(frames.front().step) + " (" + std::to_string(frames.front().pose.size()) + ")");
    if (v[kTime] != f.time)
      fail("step " + std::to_string(step) + ": time differs from the step's first row");
    f.pose.emplace_back(v[kX], v[kY], v[kTheta]);
    f.velocity.emplace_back(v[kVx], v[kVy], v[kOmega]);
    if (has_applied) f.applied.emplace_back(v[kFx], v[kFy], v[kTorque]);
    frame_last_line = line_no;
  }
  if (in.bad()) fail("read error");
  if (!frames.empty()) check_complete(frames.back());
  return frames;
}

std::vector<TrajectoryFrame> load_trajectory(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  return read_trajectory(in, path);
}

}  // namespace lcprelax
