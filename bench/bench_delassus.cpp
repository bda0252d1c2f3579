// delassus() (W = J M⁻¹ Jᵀ from J's rows and columns, models/src/delassus.cpp) against the
// expression it replaced, Eigen's ((J·M⁻¹)·Jᵀ).pruned() with J stacked from Jn and Jt by
// triplets, on the largest island of a dropped pile (make_pile_scene, seed 1, convex model,
// default settings): 200 bodies after 300 steps, 1,000 bodies after 120 steps. Both give
// the same W bit for bit (tests/models_delassus_test.cpp).
//
//   BM_Delassus/{structured,eigen}/{200,1000}
//
// Counters: rows (nc + nf), nnz_W. Compare the two in one run (same machine load).
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <benchmark/benchmark.h>

#include <map>

namespace {

using namespace lcprelax;

SparseMatrix eigen_delassus(const ContactSystem& s) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(s.Jn.nonZeros() + s.Jt.nonZeros()));
  for (Index j = 0; j < s.Jn.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (Index j = 0; j < s.Jt.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jt, j); it; ++it) t.emplace_back(nc + it.row(), j, it.value());
  SparseMatrix J(nc + nf, s.num_dofs());
  J.setFromTriplets(t.begin(), t.end());
  const SparseMatrix JMinv = J * s.minv.asDiagonal();
  SparseMatrix W = (JMinv * J.transpose()).pruned();
  W.makeCompressed();
  return W;
}

const ContactSystem& island(int bodies) {
  static std::map<int, ContactSystem> cache;
  auto it = cache.find(bodies);
  if (it != cache.end()) return it->second;
  PileOptions o;
  o.bodies = bodies;
  o.model = ContactModel::convex;
  Scene scene = make_pile_scene(o);
  Simulator sim = make_simulator(scene);
  for (int k = 0; k < (bodies <= 200 ? 300 : 120); ++k) sim.step();
  const StepContacts sc = find_step_contacts(sim.world(), sim.settings());
  std::size_t best = 0;
  for (std::size_t i = 1; i < sc.islands.size(); ++i)
    if (sc.islands[i].contacts.size() > sc.islands[best].contacts.size()) best = i;
  return cache[bodies] = assemble_contact_system(sim.world(), sc.contacts, sc.islands.at(best), sim.settings().dt);
}

void BM_Delassus(benchmark::State& state, bool structured) {
  const ContactSystem& s = island(static_cast<int>(state.range(0)));
  Index nnz = 0;
  for (auto _ : state) {
    SparseMatrix W = structured ? delassus(s) : eigen_delassus(s);
    nnz = W.nonZeros();
    benchmark::DoNotOptimize(W.valuePtr());
  }
  state.counters["rows"] = static_cast<double>(s.num_contacts() + s.num_friction());
  state.counters["nnz_W"] = static_cast<double>(nnz);
}

BENCHMARK_CAPTURE(BM_Delassus, structured, true)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Delassus, eigen, false)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
