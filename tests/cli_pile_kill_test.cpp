// `lcprelax pile --frames DIR --export-fc2d FILE` killed with SIGKILL at pseudo-random
// instants never leaves a half-written file where a complete one is expected: every
// frame_*.png present in DIR is a complete PNG (signature first, IEND chunk last), the fc2d
// file is absent or parses as a Siconos fc2d problem, and no file is a prefix of what the
// writer meant (core/atomic_file.hpp: temporary file, fsync, rename). Without the atomic
// writes a kill during Cairo's PNG encoding leaves a frame without its IEND chunk.
#include "cli_support.hpp"

#include <lcprelax/io/siconos_reader.hpp>

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;

bool complete_png(const std::string& path) {
  const std::string bytes = slurp(path);
  static const std::string signature("\x89PNG\r\n\x1a\n", 8);
  // The last chunk: length 0, type IEND, CRC AE 42 60 82.
  static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  return bytes.size() > signature.size() + iend.size() && bytes.compare(0, signature.size(), signature) == 0 &&
         bytes.compare(bytes.size() - iend.size(), iend.size(), iend) == 0;
}

#ifdef LCPRELAX_HAS_CAIRO
constexpr bool kFrames = true;
#else
constexpr bool kFrames = false;  // frames need Cairo: only the fc2d export is tested
#endif

TEST(CliPileKill, FramesAndFc2dExportAreNeverHalfWritten) {
  namespace fs = std::filesystem;
  const std::string dir = temp_path("kill_frames");
  const std::string fc2d = temp_path("kill_export.dat");
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> delay_ms(20, 900);
  int kills = 0, frames_checked = 0, exports_checked = 0;
  for (int run = 0; run < 8; ++run) {
    fs::remove_all(dir);
    fs::remove(fc2d);
    // The export is written before the last step is solved (after 80 steps the pile has
    // contacts); a kill lands before, during or after it.
    const std::string args = kFrames && run % 2 == 0 ? "pile --bodies 60 --steps 400 --frames " + dir + " --frame-every 1"
                                          : "pile --bodies 20 --steps 80 --export-fc2d " + fc2d;
    const pid_t pid = spawn_cli(args);
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == 0 && ::kill(pid, SIGKILL) == 0) ++kills;
    ::waitpid(pid, &status, 0);
    if (fs::exists(dir)) {
      for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("frame_", 0) != 0 || e.path().extension() != ".png") continue;  // a leftover .tmp is fine
        EXPECT_TRUE(complete_png(e.path().string())) << name << " after run " << run;
        ++frames_checked;
      }
    }
    if (fs::exists(fc2d)) {
      EXPECT_NO_THROW(io::read_siconos_fc2d(fc2d)) << "run " << run;
      ++exports_checked;
    }
  }
  std::printf("[          ] %d kills, %d frames and %d exports checked\n", kills, frames_checked, exports_checked);
  EXPECT_GT(kills, 0);
  if (kFrames) {
    EXPECT_GT(frames_checked, 0);
  }
  fs::remove_all(dir);
  fs::remove(fc2d);
}

}  // namespace
}  // namespace lcprelax
