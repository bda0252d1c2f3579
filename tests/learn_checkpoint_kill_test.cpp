// Kill-and-resume through the command line (`lcprelax learn ... --checkpoint F`, `--resume
// F`, apps/cmd_learn_checkpoint.hpp). Expected behaviour: for `learn block`, `learn polygon`
// and `learn scene`, a run killed with SIGKILL at several points — right after the first
// checkpoint appears, after the checkpoint has been replaced a few times, and after short
// pseudo-random delays (which land anywhere: before the first checkpoint, inside an epoch,
// during a checkpoint write) — and then resumed (or restarted when no checkpoint exists
// yet), possibly killed again, ends with learned parameters BITWISE equal to those of an
// uninterrupted run without --checkpoint (the JSON numbers are printed in their shortest
// round-trip form, so equal doubles print equal text and parse to the same bits). The
// epoch count and stop reason agree too, and no temporary file is left behind. After every
// kill the checkpoint is either absent or complete and valid (read_checkpoint accepts it).
#include "cli_support.hpp"

#include <lcprelax/learn/checkpoint.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Clock = std::chrono::steady_clock;

// The inode of `path` (0 if absent): every atomic checkpoint write replaces it.
ino_t inode_of(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

// When to kill: after `replacements` checkpoint writes (0: none needed), then `delay_ms`.
struct KillPoint {
  int replacements = 0;
  int delay_ms = 0;
};

// Runs the command with the checkpoint and kills it at `point`; returns false when the run
// ended by itself first.
bool run_and_kill(const std::string& args, const std::string& checkpoint, const KillPoint& point) {
  const pid_t pid = spawn_cli(args);
  EXPECT_GT(pid, 0);
  int status = 0;
  ino_t last = inode_of(checkpoint);
  int seen = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  while (seen < point.replacements && Clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    const ino_t now = inode_of(checkpoint);
    if (now != 0 && now != last) ++seen, last = now;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(point.delay_ms));
  const bool killed = ::waitpid(pid, &status, WNOHANG) == 0 && ::kill(pid, SIGKILL) == 0;
  ::waitpid(pid, &status, 0);
  return killed && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

// Kills at each point in turn (resuming when a checkpoint exists), then lets the run finish.
nlohmann::json killed_and_resumed(const std::string& args, const std::vector<KillPoint>& points, int& kills) {
  const std::string checkpoint = temp_path("kill.ckpt");
  fs::remove(checkpoint);
  auto with_checkpoint = [&] {
    return args + (fs::exists(checkpoint) ? " --resume " : " --checkpoint ") + checkpoint;
  };
  std::string epochs_at_kills;
  for (const KillPoint& p : points) {
    if (!run_and_kill(with_checkpoint() + " --json", checkpoint, p)) continue;
    ++kills;
    // Whatever the instant of the kill, the checkpoint is absent or complete and valid.
    int epoch = 0;
    if (fs::exists(checkpoint)) {
      EXPECT_NO_THROW(epoch = learn::read_checkpoint(checkpoint).epoch);
    }
    epochs_at_kills += " " + std::to_string(epoch);
  }
  std::cout << "[          ] killed after epochs" << epochs_at_kills << " (0: before the first checkpoint)\n";
  const CliRun r = run_cli(with_checkpoint() + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(checkpoint + ".tmp"));
  fs::remove(checkpoint);
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

void expect_same_learned(const nlohmann::json& a, const nlohmann::json& b) {
  ASSERT_TRUE(a.contains("learned") && b.contains("learned"));
  ASSERT_EQ(a["learned"].size(), b["learned"].size());
  for (auto it = a["learned"].begin(); it != a["learned"].end(); ++it) {
    const double x = it.value().get<double>(), y = b["learned"][it.key()].get<double>();
    EXPECT_EQ(std::memcmp(&x, &y, sizeof x), 0) << it.key() << ": " << it.value().dump() << " vs "
                                                 << b["learned"][it.key()].dump();
  }
  EXPECT_EQ(a["epochs"], b["epochs"]);
  EXPECT_EQ(a["stop_reason"], b["stop_reason"]);
  EXPECT_EQ(a["final_loss"], b["final_loss"]);
}

void check_kill_and_resume(const std::string& args, unsigned seed) {
  const CliRun reference = run_cli(args + " --json");
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  const nlohmann::json expected = nlohmann::json::parse(reference.out);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> delay(0, 120);
  // Right after the first checkpoint; after 3 more; then three random delays (which may fall
  // before the first checkpoint of a restart, inside an epoch or during a write).
  const std::vector<KillPoint> points = {{1, 0}, {3, 0}, {0, delay(rng)}, {1, delay(rng)}, {0, delay(rng)}};
  int kills = 0;
  const nlohmann::json got = killed_and_resumed(args, points, kills);
  EXPECT_GE(kills, 3) << "the run is too short to be killed at several points";
  expect_same_learned(expected, got);
}

TEST(LearnCheckpointKill, Block) {
  check_kill_and_resume("learn block --samples 100 --epochs 40 --batch 20 --patience 0 --threads 1", 1);
}

TEST(LearnCheckpointKill, Polygon) {
  check_kill_and_resume("learn polygon --method relaxed --samples 30 --epochs 12 --batch 8 --threads 2", 2);
}

TEST(LearnCheckpointKill, Scene) {
  check_kill_and_resume("learn scene --bodies 4 --classes 2 --steps 15 --method relaxed --epochs 8 --batch 8 --threads 2", 3);
}

}  // namespace
}  // namespace lcprelax
