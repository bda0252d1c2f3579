#pragma once
// main() for the tests that run under `mpiexec -n 2` (tests/CMakeLists.txt): PETSc/MPI
// are initialized around GoogleTest, and only rank 0 prints the test report (a failure
// on any rank still fails the process, hence the ctest test).
#include <lcprelax/mpi/mpi_session.hpp>

#include <gtest/gtest.h>

#define LCPRELAX_MPI_TEST_MAIN()                                                             \
  int main(int argc, char** argv) {                                                          \
    lcprelax::mpi::MpiSession session(&argc, &argv);                                      \
    ::testing::InitGoogleTest(&argc, argv);                                                  \
    if (lcprelax::mpi::mpi_rank() != 0) {                                                 \
      auto& listeners = ::testing::UnitTest::GetInstance()->listeners();                     \
      delete listeners.Release(listeners.default_result_printer());                          \
    }                                                                                        \
    const int failed = RUN_ALL_TESTS();                                                      \
    const std::vector<double> all = lcprelax::mpi::allgather({static_cast<double>(failed)}); \
    for (double f : all)                                                                     \
      if (f != 0.0) return 1;                                                                \
    return 0;                                                                                \
  }
