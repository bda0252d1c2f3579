// libFuzzer target: a QPS problem that reads is solved by QpSolver with at most 15
// interior-point iterations and a 0.2 s time limit, so that the solver's input checks
// (convexity of P, bounds, sizes) meet fuzzed data too. Accepted outcomes: InputError from
// the reader or from setup(), or any status; a `solved` status with a non-finite x, y or z
// aborts (a solver must never report a non-finite solution as solved). Inputs with more
// than 200 variables or rows are skipped (they only slow the fuzzer down).
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lcprelax;
  std::istringstream in(fuzz::text(data, size));
  io::QpsModel model;
  if (!fuzz::read_or_input_error([&] { model = io::parse_qps(in, "fuzz.qps"); })) return 0;
  const QpProblem& p = model.problem;
  if (p.q.size() > 200 || p.G.rows() > 200) return 0;
  QpSettings settings;
  settings.max_iter = 15;
  settings.time_limit = 0.2;
  QpSolver solver(settings);
  if (!fuzz::read_or_input_error([&] { solver.setup(p); })) return 0;
  const QpResult& r = solver.solve();
  if (r.info.status == QpStatus::solved && !(r.x.allFinite() && r.y.allFinite() && r.z.allFinite())) {
    std::fprintf(stderr, "solved with a non-finite solution\n");
    std::abort();
  }
  return 0;
}
