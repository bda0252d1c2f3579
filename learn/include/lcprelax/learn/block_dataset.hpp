#pragma once
// Transitions (v, u, v_next) of the 1-D frictional block (models/block1d.hpp): generated
// from a true block, or read from CSV in the layout of the seeds' data (Parmar, Halm &
// Posa, IROS 2021: columns v, v_next, u; unit mass and m·g = 1).
//
// Generation (generate_block_dataset), portable and reproducible: a std::mt19937_64 seeded
// with `seed` and our own draws (uniform U[0,1) from the top 53 bits; normal by
// Box–Muller), so the same seed gives the same data on every standard library.
// With s = μ·mg/m (the largest velocity change friction can cause in one step, m/s), sample
// i draws v ~ U(−2s, 2s) and the push-free velocity v* = v + u/m:
//   - even i (sticking):  v* ~ U(−stick_max·s, stick_max·s)              → v_next = 0;
//   - odd i (slipping):   |v*| ~ U(slip_min·s, slip_max·s), random sign  → v_next = v* ∓ s;
// then u = m (v* − v). So exactly half stick (⌈n/2⌉) and half slip, with a margin from the
// stick/slip boundary |v*| = s (defaults 0.9 and 1.1: 10%).
// The slip range decides which priors the losses can recover from (learn/block_losses.hpp):
// every sample sticks for μ > slip_max·μ_true, so the hard loss has an exactly zero
// gradient there (default 9: at 10× the truth), and the relaxed loss is flat beyond
// μ ≈ (2a1 + 1)·slip_max·μ_true (≈ 25× with a1 = 1 and the default 9).
// Noise on v_next (optional, σ ≥ 0):
//   - NoiseKind::relative (default): ε ~ N(0, (σ·r)²), r = RMS of the noise-free v_next over
//     the dataset (so σ = 0.01 is "1% noise"), the same r for every sample;
//   - NoiseKind::absolute: ε ~ N(0, σ²) in m/s.
#include <lcprelax/models/block1d.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax::learn {

struct BlockTransition {
  double v = 0.0;       ///< m/s
  double u = 0.0;       ///< N·s
  double v_next = 0.0;  ///< m/s (observed)
};

struct BlockDataset {
  std::vector<BlockTransition> samples;
  double mass = 1.0;  ///< kg, used by the losses for every sample
  double mg = 1.0;    ///< N·s per step
  Index size() const { return static_cast<Index>(samples.size()); }
};

enum class NoiseKind { relative, absolute };

struct BlockDataSettings {
  Block1d truth;          ///< the true block (μ, m, mg)
  Index samples = 200;    ///< ≥ 1
  std::uint64_t seed = 1;
  double noise = 0.0;     ///< σ ≥ 0 (see NoiseKind)
  NoiseKind noise_kind = NoiseKind::relative;
  double stick_max = 0.9;  ///< |v*|/s of sticking samples below this, ∈ (0, 1)
  double slip_min = 1.1;   ///< |v*|/s of slipping samples in [slip_min, slip_max], 1 < min < max
  double slip_max = 9.0;
};

/// Throws InputError on invalid settings (names the field).
BlockDataset generate_block_dataset(const BlockDataSettings& settings);

/// Reads a CSV file: a header line naming the columns v, v_next and u (any order, each
/// exactly once, surrounding spaces ignored, case-sensitive), then one row of numbers per
/// transition; blank lines are skipped. InputError (naming the file, the line and the
/// column) for a missing or duplicated column, an unknown extra column, a row with the
/// wrong number of cells, a non-numeric cell, NaN or ±∞, or a file without data rows.
/// mass and mg of the result are set from the arguments (validated > 0).
BlockDataset read_block_csv(const std::string& path, double mass = 1.0, double mg = 1.0);

/// Writes the dataset as CSV with the header "v,v_next,u" (17 significant digits).
void write_block_csv(const std::string& path, const BlockDataset& data);

/// Samples that stick under `block` (|v*| ≤ μmg/m) — for reports and tests.
Index count_sticking(const BlockDataset& data, const Block1d& block);

}  // namespace lcprelax::learn
