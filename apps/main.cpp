// lcprelax command line (docs/cli.md). Each subcommand registers itself through an
// add_<name>_command() declared in cli_common.hpp; main() parses, runs the selected one and
// maps failures to exit codes: 0 solved, 1 solve failed, 2 bad input (message on stderr).
#include "cli_common.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <vector>

namespace {

// Whether this process was started by mpiexec/mpirun (Open MPI, MPICH/PMI, PMIx).
bool launched_by_mpiexec() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lcprelax::cli;
  // Under mpiexec: one MPI session for the whole run (data-parallel learning, the
  // distributed KKT backend); only rank 0 writes to stdout, so the JSON is printed once.
  std::unique_ptr<lcprelax::mpi::MpiSession> mpi;
  if (launched_by_mpiexec() && lcprelax::mpi::petsc_available()) {
    mpi = std::make_unique<lcprelax::mpi::MpiSession>(&argc, &argv);
    if (lcprelax::mpi::mpi_rank() != 0 && !std::freopen("/dev/null", "w", stdout)) return kExitBadInput;
  }
  CLI::App app{"lcprelax: sparse QP / LCP solvers for many-contact systems"};
  app.require_subcommand(1);
  const std::vector<Command> commands = {
      add_qp_command(app),
      add_lcp_command(app),
      add_fc2d_command(app),
      add_pile_command(app),
      add_learn_command(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help (stdout) or the error (stderr)
    return code == 0 ? kExitSuccess : kExitBadInput;
  }

  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      return command.run();
    } catch (const lcprelax::InputError& e) {
      std::cerr << "lcprelax " << command.app->get_name() << ": " << e.what() << '\n';
      return kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "lcprelax " << command.app->get_name() << ": internal error: " << e.what() << '\n';
      return kExitSolveFailed;
    }
  }
  std::cerr << "lcprelax: no subcommand given\n";
  return kExitBadInput;
}
