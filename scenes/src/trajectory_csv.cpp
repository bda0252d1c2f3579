// Trajectory CSV writer and reader (scenes/trajectory_csv.hpp).
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/core/errors.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string_view>

namespace lcprelax {
namespace {

constexpr std::array<const char*, 9> kColumns = {"step", "time", "body", "x",    "y",
                                                 "theta", "vx",  "vy",   "omega"};
enum Column { kStep, kTime, kBody, kX, kY, kTheta, kVx, kVy, kOmega };

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

TrajectoryWriter::TrajectoryWriter(std::ostream& out) : out_(&out) {
  for (std::size_t c = 0; c < kColumns.size(); ++c) *out_ << (c ? "," : "") << kColumns[c];
  *out_ << '\n';
}

TrajectoryWriter::TrajectoryWriter(const std::string& path)
    : file_(std::make_unique<std::ofstream>(path, std::ios::binary)) {
  if (!*file_) throw std::runtime_error(path + ": cannot open trajectory file for writing");
  out_ = file_.get();
  for (std::size_t c = 0; c < kColumns.size(); ++c) *out_ << (c ? "," : "") << kColumns[c];
  *out_ << '\n';
}

void TrajectoryWriter::row(int step, double time, int body, const Vec3& pose, const Vec3& velocity) {
  buffer_ = std::to_string(step);
  buffer_ += ',';
  append(buffer_, time);
  buffer_ += ',' + std::to_string(body);
  for (int k = 0; k < 3; ++k) append(buffer_ += ',', pose[k]);
  for (int k = 0; k < 3; ++k) append(buffer_ += ',', velocity[k]);
  buffer_ += '\n';
  out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
}

void TrajectoryWriter::write(int step, double time, const World& world) {
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    row(step, time, static_cast<int>(i), world.bodies[i].pose, world.bodies[i].velocity);
}

void TrajectoryWriter::write(const TrajectoryFrame& frame) {
  if (frame.pose.size() != frame.velocity.size())
    throw std::invalid_argument("TrajectoryWriter::write: pose and velocity sizes differ");
  for (std::size_t i = 0; i < frame.pose.size(); ++i)
    row(frame.step, frame.time, static_cast<int>(i), frame.pose[i], frame.velocity[i]);
}

void TrajectoryWriter::flush() {
  out_->flush();
  if (!*out_) throw std::runtime_error("TrajectoryWriter: write failed");
}

std::vector<TrajectoryFrame> read_trajectory(std::istream& in, const std::string& source_name) {
  std::size_t line_no = 0;
  auto fail = [&](const std::string& message) -> void {
    throw InputError(source_name + ":" + std::to_string(line_no) + ": " + message);
  };
  std::string line;
  auto next_line = [&]() -> bool {  // next non-blank line, without a trailing '\r'
    while (std::getline(in, line)) {
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos) return true;
    }
    return false;
  };

  // Header: each of the nine names exactly once, in any order.
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
    if (c == kColumns.size()) fail("unknown column '" + std::string(names[i]) + "'");
    if (column_of[c] >= 0) fail("column '" + std::string(names[i]) + "' appears twice");
    column_of[c] = static_cast<int>(i);
  }
  for (std::size_t c = 0; c < kColumns.size(); ++c)
    if (column_of[c] < 0) fail(std::string("missing column '") + kColumns[c] + "'");

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
    if (cells.size() != kColumns.size())
      fail("expected " + std::to_string(kColumns.size()) + " cells, got " + std::to_string(cells.size()));
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      std::string_view cell = cells[static_cast<std::size_t>(column_of[c])];
      while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
      while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t')) cell.remove_suffix(1);
      const std::string where = std::string("column '") + kColumns[c] + "': ";
      if (cell.empty()) fail(where + "empty cell");
      if (cell.size() > 1 && cell[0] == '+' && cell[1] != '-' && cell[1] != '+') cell.remove_prefix(1);
      const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v[c]);
      if (r.ec == std::errc::result_out_of_range) fail(where + "value out of range '" + std::string(cell) + "'");
      if (r.ec != std::errc() || r.ptr != cell.data() + cell.size())
        fail(where + "not a number '" + std::string(cell) + "'");
      if (!std::isfinite(v[c])) fail(where + "not finite '" + std::string(cell) + "'");
      if ((c == kStep || c == kBody) && (v[c] != std::floor(v[c]) || v[c] < 0.0 || v[c] > 2147483647.0))
        fail(where + "expected an integer >= 0, got '" + std::string(cell) + "'");
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
