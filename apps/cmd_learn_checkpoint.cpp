// `--checkpoint` and `--resume` of the learn commands (cmd_learn_checkpoint.hpp).
#include "cmd_learn_checkpoint.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/checkpoint.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>

namespace lcprelax::cli {

namespace {

// Options that do not change the parameters a run ends with (or are the checkpoint itself).
constexpr std::array<const char*, 9> kNotIdentifying = {
    "--help", "--epochs", "--threads", "--json", "--log", "--plot", "--landscape", "--checkpoint", "--resume"};

bool identifies_the_run(const CLI::Option* option) {
  const std::string name = option->get_name();
  return std::none_of(kNotIdentifying.begin(), kNotIdentifying.end(), [&](const char* n) { return name == n; });
}

// Input files whose contents (not only names) identify the run.
constexpr std::array<const char*, 2> kInputFiles = {"--data", "--scene"};

// " (N bytes, FNV-1a H)" of the file at `path`, or " (unreadable)".
std::string describe_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return " (unreadable)";
  std::uint64_t h = 0xcbf29ce484222325ull, n = 0;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buffer[i]);
      h *= 0x100000001b3ull;
    }
    n += static_cast<std::uint64_t>(in.gcount());
  }
  char text[80];
  std::snprintf(text, sizeof text, " (%llu bytes, FNV-1a %016llx)", static_cast<unsigned long long>(n),
                static_cast<unsigned long long>(h));
  return text;
}

// One line per identifying option: "--name=value" (the value as typed, or its default; for
// an input file also its size and hash).
std::string describe_run(const CLI::App& command) {
  std::string out = "lcprelax learn " + command.get_name() + "\n";
  for (const CLI::Option* option : command.get_options()) {
    if (!identifies_the_run(option)) continue;
    std::string value;
    if (option->count() > 0) {
      for (const std::string& r : option->results()) value += (value.empty() ? "" : " ") + r;
    } else {
      value = option->get_default_str();
    }
    const bool input = std::any_of(kInputFiles.begin(), kInputFiles.end(), [&](const char* n) { return option->get_name() == n; });
    if (input && !value.empty()) value += describe_contents(value);
    out += option->get_name() + "=" + value + "\n";
  }
  return out;
}

}  // namespace

void add_learn_checkpoint_options(CLI::App& command, LearnCheckpointOptions& o) {
  command.add_option("--checkpoint", o.checkpoint,
                     "write the run's state to this file atomically after every epoch (see --resume)");
  command.add_option("--resume", o.resume,
                     "continue the run saved in this checkpoint (same options; keeps checkpointing to it)");
}

void apply_learn_checkpoint_options(const CLI::App& command, const LearnCheckpointOptions& o,
                                    learn::TrainSettings& t) {
  if (o.checkpoint.empty() && o.resume.empty()) return;
  if (t.epochs == 0) throw InputError("--checkpoint, --resume: need --epochs > 0 (nothing is trained with --epochs 0)");
  t.checkpoint = o.checkpoint.empty() ? o.resume : o.checkpoint;
  t.resume = o.resume;
  t.problem = describe_run(command);
  // Before any data are generated: an unwritable checkpoint or a corrupt one to resume from.
  const int rank = t.distributed ? mpi::mpi_rank() : 0;
  learn::check_checkpoint_writable(learn::checkpoint_path_for_rank(t.checkpoint, rank));
  if (!t.resume.empty()) (void)learn::read_checkpoint(learn::checkpoint_path_for_rank(t.resume, rank));
}

}  // namespace lcprelax::cli
