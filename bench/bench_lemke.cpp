// Dense vs sparse Lemke (LemkeSettings::method) on problems of growing size, to measure
// where the sparse basis (KLU + Schur-complement update) overtakes the dense explicit
// inverse: the switch point LemkeSettings::dense_max_n of `automatic`.
//
//   BM_Fc2dPile/{dense,sparse}/nc   generated fc2d-like problems (lemke_problems.hpp) with nc
//                                   contacts, as LCPs of n = 4nc unknowns (fc2d_to_lcp).
//   BM_RandomP/{dense,sparse}/n     random sparse nonsymmetric diagonally dominant
//                                   P-matrix LCPs (about 5 nonzeros per column).
//   BM_SiconosFc2d/<file>/{dense,sparse}   the Siconos fc2d test problems
//                                   (tests/data/siconos/fc2d; the granular one sparse only).
//
// Every iteration is a fresh LemkeSolver: setup() + solve() (the time per solve).
// Counters: n, nnz_M, contacts, pivots, refactorizations, solve_ms (LcpInfo::seconds,
// solve() alone, wall clock), error (max|min(z, w)| for random LCPs, the Siconos fc2d
// error otherwise), and on the sparse runs sparse_over_dense = mean process CPU time of
// setup()+solve(), sparse / dense, for the same problem measured earlier in this process
// (run the dense benchmarks first: the default order). CPU time rather than wall time,
// so that other load on the machine cancels out; run with OMP_NUM_THREADS=1 so that
// Eigen's OpenMP products in the dense path use one thread as KLU does.
#include "lemke_problems.hpp"

#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace {

using lcprelax::Index;
using lcprelax::LemkeMethod;
using lcprelax::SparseMatrix;
using lcprelax::Vector;

struct Problem {
  SparseMatrix M;
  Vector q;
  lcprelax::io::Fc2dData fc2d;  // contacts = 0 for a plain LCP
};

std::map<std::string, double>& dense_seconds() {  // problem key → mean dense time
  static std::map<std::string, double> m;
  return m;
}

std::map<std::string, Problem>& problems() {
  static std::map<std::string, Problem> m;
  return m;
}

void run(benchmark::State& state, const std::string& key, const Problem& p, LemkeMethod method) {
  lcprelax::LemkeSettings settings;
  settings.method = method;
  lcprelax::LcpResult result;
  double total = 0.0, solve_total = 0.0;
  for (auto _ : state) {
    const std::clock_t t0 = std::clock();  // process CPU time: robust to other load
    lcprelax::LemkeSolver solver(settings);
    solver.setup(p.M, p.q);
    result = solver.solve();
    benchmark::DoNotOptimize(result.z.data());
    total += static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
    solve_total += result.info.seconds;
  }
  // A failed solve keeps its time and pivots (solved = 0; the label names the status).
  const bool solved = result.info.status == lcprelax::LcpStatus::solved;
  state.counters["solved"] = solved ? 1.0 : 0.0;
  const double iterations = static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  const double mean = total / iterations;
  state.counters["n"] = static_cast<double>(p.q.size());
  state.counters["nnz_M"] = static_cast<double>(p.M.nonZeros());
  state.counters["pivots"] = static_cast<double>(result.info.pivots);
  state.counters["refactorizations"] = static_cast<double>(result.info.refactorizations);
  state.counters["solve_ms"] = 1e3 * solve_total / iterations;
  if (p.fc2d.contacts > 0) state.counters["contacts"] = static_cast<double>(p.fc2d.contacts);
  if (solved && p.fc2d.contacts > 0) {
    Vector r, u;
    lcprelax::fc2d_from_lcp(result.z, p.fc2d.W, p.fc2d.q, r, u);
    state.counters["error"] = lcprelax::io::fc2d_error(p.fc2d, r, u);
  } else if (solved) {
    state.counters["error"] = result.info.complementarity;
  }
  if (method == LemkeMethod::dense) {
    dense_seconds()[key] = mean;
  } else if (auto it = dense_seconds().find(key); it != dense_seconds().end()) {
    state.counters["sparse_over_dense"] = mean / it->second;
  }
  const std::string status = solved ? "" : std::string(" ") + lcprelax::to_string(result.info.status);
  state.SetLabel(lcprelax::to_string(result.info.method) + status);
}

const Problem& pile(Index nc) {
  const std::string key = "pile" + std::to_string(nc);
  auto it = problems().find(key);
  if (it != problems().end()) return it->second;
  Problem p;
  p.fc2d = lcprelax::bench::make_pile(nc, 2024);
  const lcprelax::Fc2dLcp lcp = lcprelax::fc2d_to_lcp(p.fc2d.W, p.fc2d.q, p.fc2d.mu);
  p.M = lcp.M;
  p.q = lcp.q;
  return problems().emplace(key, std::move(p)).first->second;
}

const Problem& random_p(Index n) {
  const std::string key = "randp" + std::to_string(n);
  auto it = problems().find(key);
  if (it != problems().end()) return it->second;
  Problem p;
  lcprelax::bench::make_random_p(n, 7, p.M, p.q);
  return problems().emplace(key, std::move(p)).first->second;
}

void BM_Fc2dPile(benchmark::State& state, LemkeMethod method) {
  const Index nc = static_cast<Index>(state.range(0));
  run(state, "pile" + std::to_string(nc), pile(nc), method);
}

void BM_RandomP(benchmark::State& state, LemkeMethod method) {
  const Index n = static_cast<Index>(state.range(0));
  run(state, "randp" + std::to_string(n), random_p(n), method);
}

// Contacts 5 … 1280, with intermediate sizes near the crossover. Dense stops at 160
// contacts (n = 640, ~2 s per solve, growing like n⁴: its O(n³) refactorizations every
// refactor_interval pivots dominate); random LCPs: dense up to n = 512 (~2 s).
const std::vector<long> kPileContacts = {5, 10, 15, 20, 25, 30, 40, 60, 80, 160, 320, 640, 1280};
constexpr long kPileDenseMax = 160;
const std::vector<long> kRandomN = {8, 16, 24, 32, 48, 64, 96, 128, 256, 512, 1024, 2048};
constexpr long kRandomDenseMax = 512;

void register_sweeps() {
  const auto ms = benchmark::kMillisecond;
  for (long nc : kPileContacts) {
    if (nc <= kPileDenseMax)
      benchmark::RegisterBenchmark("BM_Fc2dPile/dense", BM_Fc2dPile, LemkeMethod::dense)->Arg(nc)->Unit(ms);
    benchmark::RegisterBenchmark("BM_Fc2dPile/sparse", BM_Fc2dPile, LemkeMethod::sparse)->Arg(nc)->Unit(ms);
  }
  for (long n : kRandomN) {
    if (n <= kRandomDenseMax)
      benchmark::RegisterBenchmark("BM_RandomP/dense", BM_RandomP, LemkeMethod::dense)->Arg(n)->Unit(ms);
    benchmark::RegisterBenchmark("BM_RandomP/sparse", BM_RandomP, LemkeMethod::sparse)->Arg(n)->Unit(ms);
  }
}

void register_siconos_files() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(LCPRELAX_SICONOS_DATA_DIR) / "fc2d";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".dat") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const std::string name = f.stem().string(), key = "file:" + name;
    Problem p;
    p.fc2d = lcprelax::io::read_siconos_fc2d(f.string());
    const lcprelax::Fc2dLcp lcp = lcprelax::fc2d_to_lcp(p.fc2d.W, p.fc2d.q, p.fc2d.mu);
    p.M = lcp.M;
    p.q = lcp.q;
    const Problem& stored = problems().emplace(key, std::move(p)).first->second;
    // The 667-contact granular problem (n = 2668) is far beyond the dense range: sparse only.
    if (stored.fc2d.contacts <= kPileDenseMax)
      benchmark::RegisterBenchmark(("BM_SiconosFc2d/" + name + "/dense").c_str(),
                                   [key](benchmark::State& s) { run(s, key, problems().at(key), LemkeMethod::dense); })
          ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_SiconosFc2d/" + name + "/sparse").c_str(),
                                 [key](benchmark::State& s) { run(s, key, problems().at(key), LemkeMethod::sparse); })
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_sweeps();
  register_siconos_files();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
