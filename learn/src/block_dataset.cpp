// Block transitions: generation and CSV input/output (learn/block_dataset.hpp).
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/text_input.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

namespace lcprelax::learn {

namespace {

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& rng, double a, double b) { return a + (b - a) * uniform01(rng); }

double normal(std::mt19937_64& rng) {  // Box–Muller (one of the pair)
  double u1 = uniform01(rng);
  while (u1 <= 0.0) u1 = uniform01(rng);
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

}  // namespace

BlockDataset generate_block_dataset(const BlockDataSettings& s) {
  s.truth.validate();
  if (s.samples < 1) throw InputError("block data: samples must be ≥ 1");
  if (!std::isfinite(s.noise) || s.noise < 0.0) throw InputError("block data: noise must be finite and ≥ 0");
  if (!(s.stick_max > 0.0 && s.stick_max < 1.0)) throw InputError("block data: stick_max must be in (0, 1)");
  if (!(s.slip_min > 1.0 && s.slip_max > s.slip_min && std::isfinite(s.slip_max)))
    throw InputError("block data: need 1 < slip_min < slip_max < inf");
  if (!(s.truth.mu > 0.0)) throw InputError("block data: the true mu must be positive (else nothing sticks)");
  std::mt19937_64 rng(s.seed);
  const Block1d& b = s.truth;
  const double scale = b.mu * b.mg / b.mass;
  BlockDataset d;
  d.mass = b.mass;
  d.mg = b.mg;
  d.samples.resize(static_cast<std::size_t>(s.samples));
  double sum_sq = 0.0;
  for (Index i = 0; i < s.samples; ++i) {
    BlockTransition& t = d.samples[static_cast<std::size_t>(i)];
    t.v = uniform(rng, -2.0 * scale, 2.0 * scale);
    double vstar = 0.0;
    if (i % 2 == 0) {
      vstar = uniform(rng, -s.stick_max * scale, s.stick_max * scale);
    } else {
      const double mag = uniform(rng, s.slip_min * scale, s.slip_max * scale);
      vstar = uniform01(rng) < 0.5 ? -mag : mag;
    }
    t.u = b.mass * (vstar - t.v);
    t.v_next = block1d_next_velocity(b, t.v, t.u, block1d_exact_impulse(b, t.v, t.u));
    sum_sq += t.v_next * t.v_next;
  }
  if (s.noise > 0.0) {
    const double sd = s.noise_kind == NoiseKind::absolute ? s.noise : s.noise * std::sqrt(sum_sq / s.samples);
    for (BlockTransition& t : d.samples) t.v_next += sd * normal(rng);
  }
  return d;
}

BlockDataset read_block_csv(const std::string& path, double mass, double mg) {
  if (!std::isfinite(mass) || !(mass > 0.0)) throw InputError("block data: mass must be positive and finite");
  if (!std::isfinite(mg) || !(mg > 0.0)) throw InputError("block data: mg must be positive and finite");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::string line;
  long lineno = 0;
  auto where = [&](long l) { return path + ":" + std::to_string(l) + ": "; };
  // Lines of at most 1 MiB, no NUL bytes, a leading UTF-8 BOM skipped (core/text_input.hpp).
  text::LineInput lines(in, path);
  // Header.
  std::vector<std::string> header;
  while (lines.next(line)) {
    lineno = lines.line();
    if (!trim(line).empty()) {
      header = split(line);
      break;
    }
  }
  if (header.empty()) throw InputError(path + ": empty file (expected a header with columns v, v_next, u)");
  int col_v = -1, col_vn = -1, col_u = -1;
  for (std::size_t c = 0; c < header.size(); ++c) {
    int* slot = header[c] == "v" ? &col_v : header[c] == "v_next" ? &col_vn : header[c] == "u" ? &col_u : nullptr;
    if (slot == nullptr)
      throw InputError(where(lineno) + "unknown column " + text::quote(header[c]) + " (column " + std::to_string(c + 1) +
                       "; expected exactly v, v_next, u)");
    if (*slot >= 0) throw InputError(where(lineno) + "column " + text::quote(header[c]) + " appears twice");
    *slot = static_cast<int>(c);
  }
  for (auto [col, name] : {std::pair{col_v, "v"}, std::pair{col_vn, "v_next"}, std::pair{col_u, "u"}})
    if (col < 0) throw InputError(where(lineno) + "missing column '" + std::string(name) + "'");
  BlockDataset d;
  d.mass = mass;
  d.mg = mg;
  while (lines.next(line)) {
    lineno = lines.line();
    if (trim(line).empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size())
      throw InputError(where(lineno) + "expected " + std::to_string(header.size()) + " cells, found " +
                       std::to_string(cells.size()));
    double values[3] = {0, 0, 0};
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string& cell = cells[c];
      char* end = nullptr;
      errno = 0;
      const double x = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size())
        throw InputError(where(lineno) + "column '" + header[c] + "': " + text::quote(cell) + " is not a number");
      if (!std::isfinite(x)) throw InputError(where(lineno) + "column '" + header[c] + "': value is NaN or infinite");
      const int k = static_cast<int>(c) == col_v ? 0 : static_cast<int>(c) == col_vn ? 1 : 2;
      values[k] = x;
    }
    d.samples.push_back(BlockTransition{values[0], values[2], values[1]});
  }
  if (d.samples.empty()) throw InputError(path + ": no data rows after the header");
  return d;
}

void write_block_csv(const std::string& path, const BlockDataset& data) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the file");
  out.precision(17);
  out << "v,v_next,u\n";
  for (const BlockTransition& t : data.samples) out << t.v << ',' << t.v_next << ',' << t.u << '\n';
  if (!out) throw InputError(path + ": write failed");
}

Index count_sticking(const BlockDataset& data, const Block1d& block) {
  Index n = 0;
  for (const BlockTransition& t : data.samples)
    if (std::abs(t.v + t.u / block.mass) <= block.mu * block.mg / block.mass) ++n;
  return n;
}

}  // namespace lcprelax::learn
