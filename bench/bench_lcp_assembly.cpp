// The lcp model's matrices per island and step, by the library's structured kernels against
// straightforward reference assemblies (lcp_assembly_reference.hpp; same matrices bit for
// bit, tests/models_delassus_test.cpp and models_stewart_trinkle_matrix_test.cpp), on the
// largest island of a dropped pile (make_pile_scene, seed 1, convex model, default
// settings): 200 bodies after 300 steps, 1,000 bodies after 120 steps.
//
//   BM_Delassus/{structured,eigen}/{200,1000}     W = J M⁻¹ Jᵀ: delassus() against Eigen's
//                                                 ((J·M⁻¹)·Jᵀ).pruned()
//   BM_LcpMatrix/{structured,triplets}/{200,1000} M of stewart_trinkle_lcp() (q included)
//                                                 against M by triplets, from the same W
//
// Counters: rows (nc + nf), nnz (of W or M). Compare variants of one run (same machine load).
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include "lcp_assembly_reference.hpp"

#include <benchmark/benchmark.h>

#include <map>

namespace {

using namespace lcprelax;

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
    SparseMatrix W = structured ? delassus(s) : reference::eigen_delassus(s);
    nnz = W.nonZeros();
    benchmark::DoNotOptimize(W.valuePtr());
  }
  state.counters["rows"] = static_cast<double>(s.num_contacts() + s.num_friction());
  state.counters["nnz"] = static_cast<double>(nnz);
}

void BM_LcpMatrix(benchmark::State& state, bool structured) {
  const ContactSystem& s = island(static_cast<int>(state.range(0)));
  const SparseMatrix W = delassus(s);
  Index nnz = 0;
  for (auto _ : state) {
    SparseMatrix M = structured ? stewart_trinkle_lcp(s, W, 0.01).M : reference::triplet_stewart_trinkle_matrix(s, W);
    nnz = M.nonZeros();
    benchmark::DoNotOptimize(M.valuePtr());
  }
  state.counters["rows"] = static_cast<double>(s.num_contacts() + 3 * s.num_friction());
  state.counters["nnz"] = static_cast<double>(nnz);
}

BENCHMARK_CAPTURE(BM_Delassus, structured, true)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Delassus, eigen, false)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LcpMatrix, structured, true)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LcpMatrix, triplets, false)->Arg(200)->Arg(1000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
