// MPI and PETSc session (mpi_session.hpp).
#include <lcprelax/mpi/mpi_session.hpp>

#include <cstdlib>
#include <stdexcept>

#ifdef LCPRELAX_HAS_PETSC
#include <mpi.h>
#include <petscsys.h>
#endif

namespace lcprelax::mpi {

#ifdef LCPRELAX_HAS_PETSC

namespace {

bool petsc_is_initialized() {
  PetscBool on = PETSC_FALSE;
  PetscInitialized(&on);
  return on == PETSC_TRUE;
}

void initialize(int* argc, char*** argv) {
  if (petsc_is_initialized()) return;
  // lcprelax reports failures as statuses: PETSc must neither print tracebacks nor take
  // over the process's signal handlers.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  PetscErrorCode e = argc ? PetscInitialize(argc, argv, nullptr, nullptr) : PetscInitializeNoArguments();
  if (e) throw std::runtime_error("PETSc initialization failed (error " + std::to_string(static_cast<int>(e)) + ")");
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
}

bool mpi_on() {
  int on = 0, off = 0;
  MPI_Initialized(&on);
  MPI_Finalized(&off);
  return on && !off;
}

}  // namespace

bool petsc_available() { return true; }

MpiSession::MpiSession(int* argc, char*** argv) { initialize(argc, argv); }

MpiSession::~MpiSession() {
  if (petsc_is_initialized()) PetscFinalize();
}

void ensure_petsc_initialized() {
  if (petsc_is_initialized()) return;
  initialize(nullptr, nullptr);
  std::atexit([] {
    if (petsc_is_initialized()) PetscFinalize();
  });
}

int mpi_rank() {
  if (!mpi_on()) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int mpi_size() {
  if (!mpi_on()) return 1;
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

std::vector<double> allgather(const std::vector<double>& local) {
  if (!mpi_on()) return local;
  std::vector<double> all(local.size() * static_cast<std::size_t>(mpi_size()));
  MPI_Allgather(local.data(), static_cast<int>(local.size()), MPI_DOUBLE, all.data(), static_cast<int>(local.size()),
                MPI_DOUBLE, MPI_COMM_WORLD);
  return all;
}

void mpi_barrier() {
  if (mpi_on()) MPI_Barrier(MPI_COMM_WORLD);
}

#else  // one process, no MPI

bool petsc_available() { return false; }
MpiSession::MpiSession(int*, char***) {}
MpiSession::~MpiSession() = default;
void ensure_petsc_initialized() {}
int mpi_rank() { return 0; }
int mpi_size() { return 1; }
std::vector<double> allgather(const std::vector<double>& local) { return local; }
void mpi_barrier() {}

#endif

}  // namespace lcprelax::mpi
