// The interior-point QP with the distributed MUMPS KKT backend (kkt_backend =
// mumps_distributed) on 2 MPI ranks. Expected: on CVXQP1_S, DUAL1, QAFIRO, HS118 and
// PRIMAL1 (tests/data/maros_meszaros) every rank reaches status solved with residuals and
// gap ≤ 1e-9, the same iterate on both ranks (objective bitwise equal across ranks) and
// the objective of the CHOLMOD backend to 1e-8 relative; backward() adds no numeric
// factorization and its ∂ℓ/∂q for ℓ = Σx matches CHOLMOD's to 1e-6 relative on all five.
//
// Both solvers start from the regularization ρ = δ = 1e-8 here and must end there. Reason
// (QAFIRO, measured): its optimum is not unique (x4, x13, x14, x20, x29, x30 move along an
// optimal face: q4 ± 1e-7 moves Σx* from 242 to 74 or 306 at the same objective), so Σx*
// has no derivative and the final KKT matrix is singular to working precision; the
// adjoint along that face is ∝ 1/ρ with either backend (‖∂ℓ/∂q‖ = 2.04e6, 2.04e7, 2.04e8
// at final ρ = 1e-7, 1e-8, 1e-9). At the default 1e-9 CHOLMOD's LDLᵀ finds a wrong-signed
// pivot once and raises ρ to 1e-8 while MUMPS (another ordering) accepts 1e-9: that was
// the "1e8 discrepancy", not an error of the MUMPS solve (with the same final ρ the two
// agree to 2e-18 relative). Where QAFIRO's ℓ is differentiable the MUMPS adjoint matches
// central finite differences (tests/qp_mumps_backend_test.cpp).
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include "mpi_main.hpp"

#include <cmath>
#include <string>

namespace {

using namespace lcprelax;

io::QpsModel read(const char* name) {
  return io::read_qps(std::string(LCPRELAX_TEST_DATA_DIR) + "/maros_meszaros/" + name + ".qps");
}

TEST(DistributedMumpsQp, MarosMeszarosProblemsMatchCholmod) {
  ASSERT_EQ(mpi::mpi_size(), 2) << "run under mpiexec -n 2";
  for (const char* name : {"CVXQP1_S", "DUAL1", "QAFIRO", "HS118", "PRIMAL1"}) {
    SCOPED_TRACE(name);
    const io::QpsModel model = read(name);
    QpSettings sc;
    sc.kkt_backend = KktBackend::cholmod;
    sc.reg_primal = sc.reg_dual = 1e-8;  // see the header comment
    QpSettings sd = sc;
    sd.kkt_backend = KktBackend::mumps_distributed;
    QpSolver distributed(sd), cholmod(sc);
    distributed.setup(model.problem);
    cholmod.setup(model.problem);
    const QpResult& a = distributed.solve();
    const QpResult& b = cholmod.solve();
    ASSERT_EQ(a.info.status, QpStatus::solved) << a.info.message;
    ASSERT_EQ(b.info.status, QpStatus::solved) << b.info.message;
    EXPECT_LE(a.info.primal_residual, 1e-9);
    EXPECT_LE(a.info.dual_residual, 1e-9);
    EXPECT_LE(a.info.duality_gap, 1e-9);
    const double fa = model.problem.objective(a.x), fb = model.problem.objective(b.x);
    EXPECT_NEAR(fa, fb, 1e-8 * std::max(1.0, std::abs(fb)));
    const std::vector<double> both = mpi::allgather({fa});
    EXPECT_EQ(both[0], both[1]);
    EXPECT_EQ(a.info.reg_primal, b.info.reg_primal);

    const Vector dl_dx = Vector::Ones(model.problem.num_variables());
    const int before = distributed.numeric_factorizations();
    const QpGradient ga = distributed.backward(dl_dx);
    EXPECT_EQ(distributed.numeric_factorizations(), before);
    const QpGradient gb = cholmod.backward(dl_dx);
    EXPECT_LE((ga.dq - gb.dq).lpNorm<Eigen::Infinity>(), 1e-6 * std::max(1.0, gb.dq.lpNorm<Eigen::Infinity>()));
  }
}

}  // namespace

LCPRELAX_MPI_TEST_MAIN()
