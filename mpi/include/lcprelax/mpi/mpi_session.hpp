#pragma once
// MPI and PETSc for lcprelax (optional: CMake option LCPRELAX_WITH_PETSC, which defines
// LCPRELAX_HAS_PETSC).
//
// A program that uses MPI (`mpiexec -n R lcprelax ...`, data-parallel learning, the
// distributed KKT backend) creates one MpiSession at the start of main(); it initializes
// PETSc (and with it MPI) and finalizes both when it is destroyed. Without a session, the
// PETSc factorization initializes PETSc itself on first use and finalizes it at exit.
// Built without PETSc, every function here still exists and describes one process
// (rank 0 of 1), so callers need no #ifdef.
#include <vector>

namespace lcprelax::mpi {

/// Whether this build has PETSc and MPI.
bool petsc_available();

class MpiSession {
 public:
  /// Initializes PETSc/MPI (argc/argv may be null). Throws std::runtime_error on failure.
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

/// Initializes PETSc (and MPI) unless it already is (registers finalization at exit).
void ensure_petsc_initialized();

/// Rank of this process in MPI_COMM_WORLD (0 without MPI or before initialization).
int mpi_rank();
/// Number of processes in MPI_COMM_WORLD (1 without MPI or before initialization).
int mpi_size();

/// Every rank contributes `local` (all ranks the same length); returns the concatenation
/// in rank order, identical on every rank (MPI_Allgather). Without MPI: `local`.
std::vector<double> allgather(const std::vector<double>& local);

/// Barrier over MPI_COMM_WORLD (no-op without MPI).
void mpi_barrier();

}  // namespace lcprelax::mpi
