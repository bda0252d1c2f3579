// Bad checkpoints are never resumed silently (learn/checkpoint.hpp, docs/formats.md).
// Expected behaviour:
// - decode_checkpoint round-trips every field bit for bit (NaN, −0.0, subnormal included);
//   any single flipped byte, any truncation and an appended byte are rejected with
//   InputError ("checksum mismatch", "truncated", "not an lcprelax training checkpoint",
//   "format version");
// - through the CLI, `--resume F` with a corrupted, truncated, foreign or missing F, or with
//   F written by another problem (other --seed, other parameter count via --learn-mass,
//   another command), exits 2 with a message naming the file and the reason on stderr and
//   no result on stdout; an unwritable --checkpoint exits 2 before any work; --checkpoint
//   with --epochs 0 exits 2.
#include "cli_support.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/checkpoint.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace lcprelax {
namespace {

using namespace testing_support;
using learn::TrainCheckpoint;

TrainCheckpoint sample_checkpoint() {
  TrainCheckpoint c;
  c.identity = {{"problem", "lcprelax learn block\n--seed=1\n"}, {"parameter count", "2"}};
  c.epoch = 2;
  c.streak = 1;
  c.previous_full_loss = std::numeric_limits<double>::quiet_NaN();
  c.evaluated_total = 80;
  c.first_failure = "sample 3: failed";
  c.theta = Vector(2);
  c.theta << -0.0, std::numeric_limits<double>::denorm_min();
  c.optimizer.m = Vector::Constant(2, 0.1);
  c.optimizer.s = Vector::Constant(2, 1e-300);
  c.optimizer.steps = 8;
  c.rng = "1 2 3";
  c.order = {3, 1, 2, 0};
  for (int e = 1; e <= 2; ++e) {
    learn::EpochRecord r;
    r.epoch = e;
    r.loss = 1.0 / 3.0 * e;
    r.validation_loss = std::nan("");
    r.theta = c.theta;
    c.history.push_back(r);
  }
  c.objective_state = std::string("\0\1\2binary", 9);
  return c;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(LearnCheckpointCorrupt, RoundTripIsExact) {
  const TrainCheckpoint c = sample_checkpoint();
  const TrainCheckpoint d = learn::decode_checkpoint(learn::encode_checkpoint(c), "x");
  EXPECT_EQ(d.identity, c.identity);
  EXPECT_EQ(d.epoch, 2);
  EXPECT_TRUE(same_bits(d.previous_full_loss, c.previous_full_loss));
  EXPECT_TRUE(same_bits(d.theta(0), -0.0));
  EXPECT_TRUE(same_bits(d.theta(1), std::numeric_limits<double>::denorm_min()));
  EXPECT_TRUE(same_bits(d.optimizer.s(1), 1e-300));
  EXPECT_EQ(d.optimizer.steps, 8);
  EXPECT_EQ(d.rng, c.rng);
  EXPECT_EQ(d.order, c.order);
  EXPECT_EQ(d.first_failure, c.first_failure);
  ASSERT_EQ(d.history.size(), 2u);
  EXPECT_TRUE(same_bits(d.history[1].loss, 2.0 / 3.0));
  EXPECT_TRUE(std::isnan(d.history[0].validation_loss));
  EXPECT_EQ(d.objective_state, c.objective_state);
}

std::string decode_error(const std::string& bytes) {
  try {
    learn::decode_checkpoint(bytes, "F");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(LearnCheckpointCorrupt, EveryFlippedByteTruncationAndExtensionIsRejected) {
  const std::string good = learn::encode_checkpoint(sample_checkpoint());
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    EXPECT_NE(decode_error(bad), "(accepted)") << "byte " << i;
  }
  for (std::size_t n = 0; n < good.size(); ++n) EXPECT_NE(decode_error(good.substr(0, n)), "(accepted)") << n;
  EXPECT_NE(decode_error(good + "x").find("truncated or extended"), std::string::npos);
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 1);
  EXPECT_NE(decode_error(flipped).find("checkpoint 'F': checksum mismatch"), std::string::npos) << decode_error(flipped);
  EXPECT_NE(decode_error("epoch,loss\n1,2\n").find("not an lcprelax training checkpoint"), std::string::npos);
  std::string version = good;
  version[8] = 7;
  EXPECT_NE(decode_error(version).find("format version 7"), std::string::npos) << decode_error(version);
}

const std::string kBlock = "learn block --samples 40 --patience 0 --batch 10";

void expect_bad_input(const CliRun& r, const std::string& needle) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out.find("learned"), std::string::npos) << r.out;  // no result (at most an error object)
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

TEST(LearnCheckpointCorrupt, CliRejectsBadCheckpointsWithExit2) {
  const std::string f = temp_path("corrupt.ckpt");
  ASSERT_EQ(run_cli(kBlock + " --epochs 2 --json --checkpoint " + f).exit_code, 0);
  const std::string good = slurp(f);
  auto write = [&](const std::string& bytes) { std::ofstream(f, std::ios::binary) << bytes; };
  const std::string resume = kBlock + " --epochs 4 --json --resume " + f;

  std::string bad = good;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x40);
  write(bad);
  expect_bad_input(run_cli(resume), "checkpoint '" + f + "': checksum mismatch");
  write(good.substr(0, good.size() - 5));
  expect_bad_input(run_cli(resume), "truncated");
  write("");
  expect_bad_input(run_cli(resume), "not an lcprelax training checkpoint");

  write(good);
  expect_bad_input(run_cli(kBlock + " --epochs 4 --seed 2 --json --resume " + f), "belongs to another run: problem (line ");
  expect_bad_input(run_cli(kBlock + " --epochs 4 --seed 2 --json --resume " + f), "'--seed=1' in the checkpoint but '--seed=2'");
  expect_bad_input(run_cli(kBlock + " --epochs 4 --learn-mass --json --resume " + f), "--learn-mass");
  expect_bad_input(run_cli("learn polygon --epochs 3 --samples 20 --json --resume " + f),
                   "'lcprelax learn block' in the checkpoint but 'lcprelax learn polygon'");
  // The resumed run of the right problem still works from the intact file.
  EXPECT_EQ(run_cli(resume).exit_code, 0);

  fs::remove(f);
  expect_bad_input(run_cli(resume), "checkpoint: cannot read '" + f + "'");
  expect_bad_input(run_cli(kBlock + " --epochs 4 --json --checkpoint /nonexistent-dir/x.ckpt"), "checkpoint: cannot write");
  expect_bad_input(run_cli("learn block --epochs 0 --json --checkpoint " + f), "need --epochs > 0");
  EXPECT_FALSE(fs::exists(f));
}

}  // namespace
}  // namespace lcprelax
