// Binds lcprelax.LemkeBatch: B LCPs  w = Mz + q, 0 ≤ z ⊥ w ≥ 0  with one sparsity pattern of
// M, solved by Lemke's method (lcp/lemke.hpp) in parallel with OpenMP. Each sample keeps
// its LemkeSolver, so backward() uses the final basis of its forward solve (one transposed
// solve, no refactorization). The engine of lcprelax.torch.LcpLayer.
//
// M's VALUES are passed as arrays over its stored entries in the canonical CSC order of
// `M_pattern` (None keeps the pattern's values); q is required. Batched arguments: batch.hpp.
// Each sample's result equals, bit for bit, that of a lone LemkeSolver with the same
// settings (every solve is a fresh setup(): Lemke keeps nothing across values of M).
#include "batch.hpp"

#include <lcprelax/lcp/lemke.hpp>

#include <memory>
#include <mutex>

namespace lcprelax::python {
namespace {

struct PyLcpBatchResult {
  py::array_t<double> z, w, complementarity;
  py::array_t<long> pivots;
  py::array_t<bool> has_solution;
  std::vector<std::string> status;
  long long generation = 0;
};

class PyLemkeBatch {
 public:
  PyLemkeBatch(const py::object& M, int threads, const LemkeSettings& s) : settings_(s), threads_(threads) {
    pattern_ = to_sparse(M, "M");
    if (pattern_.rows() != pattern_.cols())
      throw InputError("M is " + std::to_string(pattern_.rows()) + "x" + std::to_string(pattern_.cols()) +
                       ", must be square");
    LemkeSolver check(settings_);  // validates the settings now, not at the first solve
    check.setup(pattern_, Vector::Zero(pattern_.rows()));
  }

  PyLcpBatchResult solve(const py::object& q, const py::object& M) {
    if (q.is_none()) throw py::type_error("LemkeBatch.solve(): q is required");
    const Index n = size(), nnz = static_cast<Index>(pattern_.nonZeros());
    BatchArgs args;
    const BatchRows rq = args.add(q, "q", n), rM = args.add(M, "M", nnz);
    const Index B = args.batch_size();
    Busy busy(mutex_, "LemkeBatch");
    if (static_cast<Index>(solvers_.size()) != B) {
      matrices_.assign(static_cast<std::size_t>(B), pattern_);
      solvers_.clear();
      for (Index k = 0; k < B; ++k) solvers_.push_back(std::make_unique<LemkeSolver>(settings_));
    }
    ++generation_;
    solved_ = false;
    {
      py::gil_scoped_release nogil;
      for_each_sample(B, threads_, [&](Index k) {
        SparseMatrix& Mk = matrices_[static_cast<std::size_t>(k)];
        if (rM.given()) copy_row(rM.row(k), nnz, Mk.valuePtr());
        LemkeSolver& s = *solvers_[static_cast<std::size_t>(k)];
        s.setup(Mk, Eigen::Map<const Vector>(rq.row(k), n));
        s.solve();
      });
    }
    solved_ = true;
    PyLcpBatchResult r;
    r.z = batch_array(B, n), r.w = batch_array(B, n), r.complementarity = py::array_t<double>(B);
    r.pivots = py::array_t<long>(B), r.has_solution = py::array_t<bool>(B), r.generation = generation_;
    for (Index k = 0; k < B; ++k) {
      const LcpResult& s = solvers_[static_cast<std::size_t>(k)]->result();
      copy_or_nan(s.z, n, r.z.mutable_data() + k * n), copy_or_nan(s.w, n, r.w.mutable_data() + k * n);
      r.complementarity.mutable_data()[k] = s.info.complementarity;
      r.pivots.mutable_data()[k] = s.info.pivots;
      r.has_solution.mutable_data()[k] = has_solution(s.info.status);
      r.status.push_back(to_string(s.info.status));
    }
    return r;
  }

  py::dict backward(const py::object& dl_dz) {
    if (!solved_) throw std::logic_error("LemkeBatch.backward() before solve()");
    const Index n = size(), nnz = static_cast<Index>(pattern_.nonZeros());
    const Index B = static_cast<Index>(solvers_.size());
    BatchArgs args;
    const BatchRows rz = args.add(dl_dz, "dl_dz", n);
    if (!rz.given()) throw py::type_error("LemkeBatch.backward(): dl_dz is required");
    if (args.batch_size() != 1 && args.batch_size() != B)
      throw InputError("LemkeBatch.backward(): batch size " + std::to_string(args.batch_size()) +
                       ", the last solve() had " + std::to_string(B));
    for (Index k = 0; k < B; ++k) {
      const LcpStatus st = solvers_[static_cast<std::size_t>(k)]->result().info.status;
      if (st != LcpStatus::solved)
        throw std::logic_error("LemkeBatch.backward(): sample " + std::to_string(k) + " has status " + to_string(st) +
                               ", no solution to differentiate");
    }
    py::array_t<double> dM = batch_array(B, nnz), dq = batch_array(B, n);
    double *pM = dM.mutable_data(), *pq = dq.mutable_data();
    Busy busy(mutex_, "LemkeBatch");
    {
      py::gil_scoped_release nogil;
      for_each_sample(B, threads_, [&](Index k) {
        const LcpGradient g = solvers_[static_cast<std::size_t>(k)]->backward(Eigen::Map<const Vector>(rz.row(k), n));
        if (g.dM.nonZeros() != nnz) throw std::runtime_error("LemkeBatch.backward(): dM left M's sparsity pattern");
        copy_row(g.dM.valuePtr(), nnz, pM + k * nnz), copy_or_nan(g.dq, n, pq + k * n);
      });
    }
    py::dict d;
    d["M"] = dM, d["q"] = dq;
    return d;
  }

  Index size() const { return static_cast<Index>(pattern_.rows()); }
  Index batch_size() const { return static_cast<Index>(solvers_.size()); }
  long long generation() const { return generation_; }
  const SparseMatrix& pattern() const { return pattern_; }

 private:
  LemkeSettings settings_;
  int threads_;
  SparseMatrix pattern_;
  std::vector<SparseMatrix> matrices_;
  std::vector<std::unique_ptr<LemkeSolver>> solvers_;
  bool solved_ = false;
  long long generation_ = 0;
  std::mutex mutex_;
};

}  // namespace

void bind_lcp_batch(py::module_& m) {
  py::class_<PyLcpBatchResult>(m, "LcpBatchResult", "Result of LemkeBatch.solve(): arrays with one row per sample")
      .def_readonly("z", &PyLcpBatchResult::z).def_readonly("w", &PyLcpBatchResult::w, "Mz + q")
      .def_readonly("complementarity", &PyLcpBatchResult::complementarity, "max_i |min(z_i, w_i)| per sample")
      .def_readonly("pivots", &PyLcpBatchResult::pivots)
      .def_readonly("has_solution", &PyLcpBatchResult::has_solution)
      .def_readonly("status", &PyLcpBatchResult::status, "list of status names, one per sample")
      .def_readonly("generation", &PyLcpBatchResult::generation);

  py::class_<PyLemkeBatch>(m, "LemkeBatch",
                           "B LCPs with one pattern of M, solved by Lemke in parallel (OpenMP); each sample keeps\n"
                           "its final basis for backward(). See docs/python.md.")
      .def(py::init([](const py::object& M, int threads, const py::kwargs& kw) {
             LemkeSettings s;
             apply_settings(s, lemke_fields(), kw, "LemkeBatch()");
             return std::make_unique<PyLemkeBatch>(M, threads, s);
           }),
           py::arg("M"), py::kw_only(), py::arg("threads") = 0,
           "LemkeBatch(M, *, threads=0, **settings): M's pattern (scipy.sparse, n x n) and LemkeSettings keywords")
      .def("solve", &PyLemkeBatch::solve, py::arg("q"), py::kw_only(), py::arg("M") = py::none(),
           "Solves every sample: q of shape (n,) or (B, n); M the VALUES on M_pattern's entries, (nnz,)\n"
           "or (B, nnz), None keeps the pattern's values. Returns an LcpBatchResult.")
      .def("backward", &PyLemkeBatch::backward, py::arg("dl_dz"),
           "dl/dz of shape (n,) or (B, n) -> dict of dl/dM (B, nnz) and dl/dq (B, n); UsageError when a\n"
           "sample is not solved")
      .def_property_readonly("n", &PyLemkeBatch::size)
      .def_property_readonly("batch_size", &PyLemkeBatch::batch_size)
      .def_property_readonly("generation", &PyLemkeBatch::generation)
      .def_property_readonly("M_pattern", [](const PyLemkeBatch& b) { return to_scipy(b.pattern()); });
}

}  // namespace lcprelax::python
