// Block transitions (learn/block_dataset.hpp): generation is reproducible (same seed, same
// bits; another seed, other data), exactly half the samples stick under the true block and
// the noise-free v_next is the model's; relative noise has the requested size (sample RMS
// of the added noise within 20% of σ·RMS(v_next) over 2,000 samples); CSV round-trips; the
// seeds' layout with columns in any order reads; bad files are InputErrors that name the
// line and the column.
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace lcprelax::learn {
namespace {

const std::string kData = std::string(LCPRELAX_TEST_DATA_DIR) + "/block/";

TEST(BlockDataset, GenerationIsReproducibleAndHalfSticks) {
  BlockDataSettings s;
  s.truth = Block1d{2.0, 3.0, 0.4};
  s.samples = 101;
  const BlockDataset a = generate_block_dataset(s), b = generate_block_dataset(s);
  ASSERT_EQ(a.size(), 101);
  EXPECT_EQ(std::memcmp(a.samples.data(), b.samples.data(), sizeof(BlockTransition) * a.samples.size()), 0);
  s.seed = 2;
  EXPECT_NE(generate_block_dataset(s).samples[0].v, a.samples[0].v);
  EXPECT_EQ(count_sticking(a, s.truth), 51);
  for (const BlockTransition& t : a.samples)
    EXPECT_DOUBLE_EQ(t.v_next, block1d_next_velocity(s.truth, t.v, t.u, block1d_exact_impulse(s.truth, t.v, t.u)));
}

TEST(BlockDataset, RelativeNoiseHasTheRequestedSize) {
  BlockDataSettings s;
  s.samples = 2000;
  const BlockDataset clean = generate_block_dataset(s);
  s.noise = 0.01;
  const BlockDataset noisy = generate_block_dataset(s);
  double rms = 0.0, added = 0.0;
  for (Index i = 0; i < clean.size(); ++i) {
    rms += std::pow(clean.samples[i].v_next, 2);
    added += std::pow(noisy.samples[i].v_next - clean.samples[i].v_next, 2);
  }
  EXPECT_NEAR(std::sqrt(added / rms), 0.01, 0.002);
}

TEST(BlockDataset, CsvRoundTripAndColumnOrder) {
  BlockDataSettings s;
  s.samples = 7;
  const BlockDataset a = generate_block_dataset(s);
  const std::string path = (std::filesystem::temp_directory_path() / ("block_" + std::to_string(::getpid()) + ".csv")).string();
  write_block_csv(path, a);
  const BlockDataset b = read_block_csv(path);
  ASSERT_EQ(b.size(), 7);
  for (Index i = 0; i < 7; ++i) {
    EXPECT_EQ(a.samples[i].v, b.samples[i].v);
    EXPECT_EQ(a.samples[i].u, b.samples[i].u);
    EXPECT_EQ(a.samples[i].v_next, b.samples[i].v_next);
  }
  std::filesystem::remove(path);
  const BlockDataset g = read_block_csv(kData + "good.csv", 2.0, 0.5);  // header "u,v, v_next", a blank line
  ASSERT_EQ(g.size(), 3);
  EXPECT_EQ(g.samples[1].u, -2.0);
  EXPECT_EQ(g.samples[1].v, 0.3);
  EXPECT_EQ(g.samples[1].v_next, -0.7);
  EXPECT_EQ(g.mass, 2.0);
  EXPECT_EQ(g.mg, 0.5);
}

void expect_error(const std::string& file, const std::string& needle) {
  try {
    read_block_csv(kData + file);
    ADD_FAILURE() << file << ": no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << file << ": " << e.what();
  }
}

TEST(BlockDataset, BadFilesNameLineAndColumn) {
  expect_error("extra_column.csv", "unknown column 'w'");
  expect_error("missing_column.csv", "missing column 'v_next'");
  expect_error("nan.csv", ":3: column 'v_next': value is NaN");
  expect_error("non_numeric.csv", ":3: column 'v_next': 'abc' is not a number");
  expect_error("short_row.csv", ":2: expected 3 cells, found 2");
  expect_error("no_rows.csv", "no data rows");
  expect_error("does_not_exist.csv", "cannot open");
  EXPECT_THROW(read_block_csv(kData + "good.csv", 0.0), InputError);
  BlockDataSettings s;
  s.samples = 0;
  EXPECT_THROW(generate_block_dataset(s), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
