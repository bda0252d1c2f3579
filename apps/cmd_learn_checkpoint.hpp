#pragma once
// `--checkpoint FILE` and `--resume FILE` of the learn commands (docs/cli.md): a learning
// run that survives a kill.
//
//   --checkpoint FILE  after every epoch, write the run's complete state (θ, optimizer
//                      moments, shuffle state, convergence test, epoch history, the loss's
//                      warm starts) to FILE atomically (learn/checkpoint.hpp);
//   --resume FILE      continue the run saved in FILE (and keep checkpointing to FILE unless
//                      --checkpoint names another file). The final parameters are bitwise
//                      those of the uninterrupted run.
// The run is identified by the command's options (and the contents of the --data and
// --scene files): a resume must repeat them, except --epochs (the cap, counted from the
// run's start), --threads, --json, --log, --plot, --landscape, --checkpoint and --resume;
// another value of any other option is bad input (exit 2) naming it, as are an unreadable,
// truncated or corrupt FILE.
#include "cli_common.hpp"

#include <string>

namespace lcprelax::cli {

struct LearnCheckpointOptions {
  std::string checkpoint, resume;
};

/// Adds --checkpoint and --resume to a learn command.
void add_learn_checkpoint_options(CLI::App& command, LearnCheckpointOptions& o);

/// Sets t.checkpoint, t.resume and t.problem (the command's name and every option that
/// identifies the run, one "--name=value" per line). Throws InputError when --checkpoint or
/// --resume is given with --epochs 0.
void apply_learn_checkpoint_options(const CLI::App& command, const LearnCheckpointOptions& o,
                                    learn::TrainSettings& t);

}  // namespace lcprelax::cli
