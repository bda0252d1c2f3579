// lcprelax command line (docs/cli.md). Each subcommand registers itself through an
// add_<name>_command() declared in cli_common.hpp; main() parses, runs the selected one and
// maps failures to exit codes: 0 solved, 1 solve failed, 2 bad input (message on stderr; with
// --json also {"status": "invalid_input", "message": ...} on stdout). An unknown subcommand is
// named, with the valid ones.
#include "cli_common.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace {

// The first word of argv that names no subcommand where one is expected ("lcprelax foo",
// "lcprelax learn foo"), with the valid names; empty when there is none. CLI11 would say
// "A subcommand is required" or "arguments were not expected".
std::string unknown_subcommand(CLI::App& app, int argc, char** argv) {
  CLI::App* at = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::vector<CLI::App*> subs = at->get_subcommands([](CLI::App*) { return true; });
    if (subs.empty() || arg.empty() || arg[0] == '-') return {};
    CLI::App* next = nullptr;
    for (CLI::App* s : subs)
      if (s->check_name(arg)) next = s;
    if (next == nullptr) {
      std::string names;
      for (CLI::App* s : subs) names += (names.empty() ? "" : ", ") + s->get_name();
      const std::string where = at == &app ? std::string("lcprelax") : "lcprelax " + at->get_name();
      return where + ": unknown subcommand '" + arg.substr(0, 64) + "' (valid: " + names + ")";
    }
    at = next;
  }
  return {};
}

// Whether --json was asked for anywhere on the command line.
bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--json") return true;
  return false;
}

// A failure: the message on stderr, and with --json also {"status", "message"} on stdout
// (docs/cli.md: --json always prints exactly one object).
int fail(bool json, const char* status, const std::string& message, int code) {
  std::cerr << message << '\n';
  if (json) lcprelax::cli::print_json({{"status", status}, {"message", message}});
  return code;
}

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
  CLI::App app{
      "lcprelax: solvers for convex QPs and contact problems (LCP, 2-D friction), a simulator of\n"
      "piles of polygons, and learning of contact parameters from motion data.\n"
      "Run 'lcprelax SUBCOMMAND --help' for a subcommand's options; docs/cli.md describes every\n"
      "output field, docs/formats.md every file format."};
  app.require_subcommand(1);
  app.footer(exit_codes_help() +
             "\nEvery subcommand prints a short report, or with --json exactly one JSON object on stdout.\n");
  const std::vector<Command> commands = {
      add_qp_command(app),
      add_lcp_command(app),
      add_fc2d_command(app),
      add_pile_command(app),
      add_learn_command(app),
  };

  const bool json = wants_json(argc, argv);
  if (const std::string unknown = unknown_subcommand(app, argc, argv); !unknown.empty())
    return fail(json, "invalid_input", unknown, kExitBadInput);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? kExitSuccess : kExitBadInput;  // --help
    if (!json) return app.exit(e) == 0 ? kExitSuccess : kExitBadInput;  // the error and a hint (stderr)
    return fail(json, "invalid_input", std::string("lcprelax: ") + e.what(), kExitBadInput);
  }

  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    const std::string name = "lcprelax " + command.app->get_name() + ": ";
    try {
      return command.run();
    } catch (const lcprelax::InputError& e) {
      return fail(json, "invalid_input", name + e.what(), kExitBadInput);
    } catch (const std::bad_alloc&) {
      return fail(json, "out_of_memory", name + "out of memory", kExitSolveFailed);
    } catch (const std::exception& e) {
      return fail(json, "internal_error", name + "internal error: " + e.what(), kExitSolveFailed);
    }
  }
  return fail(json, "invalid_input", "lcprelax: no subcommand given", kExitBadInput);
}
