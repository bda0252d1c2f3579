// How much of a pile island's KKT factorization two threads can share: a measured
// prototype of the two-subdomain (one-level nested dissection) split of one island over two
// cores, before any solver is built on it.
//
// The island: the largest one of a pile of --bodies polygons after --settle convex-model
// steps (the simulator's defaults). Its matrix: the convex model's phase-2 QP in the lifted
// formulation, assembled as the interior point's quasi-definite KKT matrix
//     [P + Db + ρI   Aᵀ    Gᵀ  ]
//     [A             −δI   0   ]
//     [G             0    −D_g ]     (values as at a mid-run iterate: Db = 1 on the bounded
//                                     λn, D_g = 1, ρ = δ = 1e-9; LDLᵀ without pivoting does
//                                     the same work for any values)
// Split: METIS' vertex separator of K's graph (CHOLMOD's cholmod_bisect) into parts A, B and
// separator S. Then, each part on its own thread: numeric LDLᵀ of K_XX (CHOLMOD, AMD, the
// analysis done beforehand as the interior point would reuse it), the solves
// K_XX⁻¹ K_XS (|S| right-hand sides) and C_X = K_SX K_XX⁻¹ K_XS; then, on one thread, the
// dense Schur complement K_SS − C_A − C_B and its dense LU (Eigen's PartialPivLU: an upper
// bound of the LDLᵀ's cost). Baseline: the whole K by CholmodLdlt (AMD, and the best of
// AMD/METIS/NESDIS) on one thread. Times are medians of --repeat runs (wall clock).
//   run_kkt_split --bodies 1000 --settle 150 --seed 1 --repeat 5
#include <lcprelax/models/convex_phase_qp.hpp>
#include <lcprelax/models/normal_softening.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>
#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <CLI/CLI.hpp>
#include <Eigen/LU>
#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace lcprelax;

namespace {

double seconds_of(const std::function<void()>& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

ContactSystem largest_island(const World& world, const SimulatorSettings& settings) {
  const StepContacts sc = find_step_contacts(world, settings);
  if (sc.islands.empty()) throw std::runtime_error("no contact island");
  std::size_t best = 0;
  for (std::size_t i = 1; i < sc.islands.size(); ++i)
    if (sc.islands[i].contacts.size() > sc.islands[best].contacts.size()) best = i;
  return assemble_contact_system(world, sc.contacts, sc.islands[best], settings.dt);
}

// Upper triangle of the KKT matrix of `p` (header comment).
SparseMatrix kkt_upper(const QpProblem& p) {
  const Index n = p.num_variables(), me = p.num_equalities(), mi = p.num_inequalities();
  std::vector<Triplet> t;
  append_triplets(t, p.P, 0, 0, 1.0);
  for (Index j = 0; j < n; ++j) t.emplace_back(j, j, 1e-9 + (std::isfinite(p.xl(j)) || std::isfinite(p.xu(j)) ? 1.0 : 0.0));
  append_triplets(t, p.A, 0, n, 1.0, /*transpose=*/true);
  append_triplets(t, p.G, 0, n + me, 1.0, /*transpose=*/true);
  for (Index i = 0; i < me; ++i) t.emplace_back(n + i, n + i, -1e-9);
  for (Index i = 0; i < mi; ++i) t.emplace_back(n + me + i, n + me + i, -1.0);
  const Index N = n + me + mi;
  SparseMatrix K = from_triplets(N, N, t);
  return SparseMatrix(K.triangularView<Eigen::Upper>());
}

// METIS vertex separator of the graph of the symmetric matrix whose upper triangle is K:
// 0 / 1 the parts, 2 the separator.
std::vector<Index> bisect(const SparseMatrix& K) {
  cholmod_common c;
  cholmod_start(&c);
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<std::size_t>(K.rows());
  A.nzmax = static_cast<std::size_t>(K.nonZeros());
  A.p = const_cast<int*>(K.outerIndexPtr());
  A.i = const_cast<int*>(K.innerIndexPtr());
  A.x = const_cast<double*>(K.valuePtr());
  A.stype = 1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  std::vector<int> part(static_cast<std::size_t>(K.rows()));
  const long sep = cholmod_bisect(&A, nullptr, 0, /*compress=*/1, part.data(), &c);
  const int status = c.status;
  cholmod_finish(&c);
  if (sep < 0 || status < CHOLMOD_OK) throw std::runtime_error("cholmod_bisect failed");
  return std::vector<Index>(part.begin(), part.end());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Two-subdomain split of a pile island's KKT factorization (measured prototype)"};
  int bodies = 1000, settle = 150, repeat = 5;
  std::uint64_t seed = 1;
  app.add_option("--bodies", bodies, "Pile bodies")->check(CLI::Range(2, 100000))->capture_default_str();
  app.add_option("--settle", settle, "Convex-model steps before the island is taken")->capture_default_str();
  app.add_option("--seed", seed, "Pile seed")->capture_default_str();
  app.add_option("--repeat", repeat, "Timed repetitions (median reported)")->check(CLI::Range(1, 1000))->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  PileOptions o;
  o.bodies = bodies;
  o.seed = seed;
  o.model = ContactModel::convex;
  Scene scene = make_pile_scene(o);
  scene.settings.model = ContactModel::convex;
  Simulator sim = make_simulator(scene);
  for (int k = 0; k < settle; ++k) sim.step();
  const ContactSystem s = largest_island(sim.world(), sim.settings());
  const double dt = sim.settings().dt;
  const Vector vn = s.Jn * s.v_star;
  const Vector bn = vn + s.phi.cwiseMax(0.0) / dt;
  const NormalSofteningTerms soft =
      normal_softening_terms(sim.settings().convex_softening, sim.settings().convex_rho, dt, s.phi, vn);
  const detail::ConvexModelData data(s, bn, ConvexFormulation::lifted);
  detail::ConvexPhaseQp p2 = detail::convex_phase2_qp(data, soft);
  p2.problem.u(s.num_contacts()) = 1.0;  // eᵀλn ≤ κ: a finite bound, the row is kept
  const SparseMatrix K = kkt_upper(p2.problem);
  const Index N = K.rows();
  std::printf("island: %zu bodies, %d contacts, %d friction rows; KKT %d rows, %ld nonzeros (upper)\n",
              s.bodies.size(), static_cast<int>(s.num_contacts()), static_cast<int>(s.num_friction()),
              static_cast<int>(N), static_cast<long>(K.nonZeros()));

  // Baseline: the whole matrix, one thread.
  for (sparse::CholmodOrdering ord : {sparse::CholmodOrdering::amd, sparse::CholmodOrdering::best}) {
    sparse::CholmodLdlt full(0.0, ord);
    if (!full.analyze(K).ok()) throw std::runtime_error("analyze failed");
    std::vector<double> t;
    for (int r = 0; r < repeat; ++r) t.push_back(seconds_of([&] {
      if (!full.factorize(K).ok()) throw std::runtime_error("factorize failed");
    }));
    std::printf("whole K, %-6s ordering: nnz(L) %ld, %.3g flops, factorize %.4f s\n", full.ordering_name(),
                full.factor_nnz(), full.factor_flops(), median(t));
  }

  // Split.
  const std::vector<Index> part = bisect(K);
  std::vector<Index> order, where(static_cast<std::size_t>(N));
  Index sizes[3] = {0, 0, 0};
  for (int side = 0; side < 3; ++side)
    for (Index i = 0; i < N; ++i)
      if (part[i] == side) where[i] = static_cast<Index>(order.size()), order.push_back(i), ++sizes[side];
  const SparseMatrix Kfull = SparseMatrix(K.selfadjointView<Eigen::Upper>());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, Index> perm(N);
  for (Index i = 0; i < N; ++i) perm.indices()(i) = where[i];
  const SparseMatrix Kp = SparseMatrix(perm * Kfull * perm.transpose());
  const Index na = sizes[0], nb = sizes[1], ns = sizes[2];
  std::printf("split: |A| %d, |B| %d, |S| %d\n", static_cast<int>(na), static_cast<int>(nb), static_cast<int>(ns));
  struct Side {
    SparseMatrix Kxx, Kxs;
    sparse::CholmodLdlt ldlt{0.0, sparse::CholmodOrdering::amd};
    DenseMatrix Y, C;
    std::vector<double> t_factor, t_schur;
  };
  Side sides[2];
  sides[0].Kxx = SparseMatrix(Kp.block(0, 0, na, na).triangularView<Eigen::Upper>());
  sides[0].Kxs = Kp.block(0, na + nb, na, ns);
  sides[1].Kxx = SparseMatrix(Kp.block(na, na, nb, nb).triangularView<Eigen::Upper>());
  sides[1].Kxs = Kp.block(na, na + nb, nb, ns);
  const DenseMatrix Kss = DenseMatrix(Kp.block(na + nb, na + nb, ns, ns));
  for (Side& x : sides)
    if (!x.ldlt.analyze(x.Kxx).ok()) throw std::runtime_error("part analyze failed");
  auto work = [](Side& x) {
    x.t_factor.push_back(seconds_of([&] {
      if (!x.ldlt.factorize(x.Kxx).ok()) throw std::runtime_error("part factorize failed");
    }));
    x.t_schur.push_back(seconds_of([&] {
      x.Y = DenseMatrix(x.Kxs);
      x.ldlt.solve(x.Y);
      x.C.noalias() = x.Kxs.transpose() * x.Y;
    }));
  };
  std::vector<double> t_sequential, t_parallel, t_dense;
  for (int r = 0; r < repeat; ++r) {
    t_sequential.push_back(seconds_of([&] {
      work(sides[0]);
      work(sides[1]);
    }));
    t_parallel.push_back(seconds_of([&] {
      std::thread other([&] { work(sides[1]); });
      work(sides[0]);
      other.join();
    }));
    t_dense.push_back(seconds_of([&] {
      const DenseMatrix S = Kss - sides[0].C - sides[1].C;
      Eigen::PartialPivLU<DenseMatrix> lu(S);
      if (!lu.matrixLU().allFinite()) throw std::runtime_error("dense Schur LU failed");
    }));
  }
  for (int k = 0; k < 2; ++k)
    std::printf("part %c: nnz(L) %ld, %.3g flops; factorize %.4f s, K_XX⁻¹K_XS and K_SX(·) %.4f s (medians of both "
                "runs)\n",
                k ? 'B' : 'A', sides[k].ldlt.factor_nnz(), sides[k].ldlt.factor_flops(), median(sides[k].t_factor),
                median(sides[k].t_schur));
  std::printf("parts one after the other %.4f s, on two threads %.4f s; dense Schur complement (|S| = %d) %.4f s\n",
              median(t_sequential), median(t_parallel), static_cast<int>(ns), median(t_dense));
  std::printf("split total: one thread %.4f s, two threads %.4f s\n", median(t_sequential) + median(t_dense),
              median(t_parallel) + median(t_dense));
  return 0;
}
