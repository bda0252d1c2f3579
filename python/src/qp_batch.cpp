// Binds lcprelax.QpBatch: B QPs with one sparsity pattern, solved in parallel with OpenMP,
// each sample keeping its own QpSolver (and so its final KKT factorization) until the next
// solve(), so that backward() reuses the forward factorizations. The engine of
// lcprelax.torch.QpLayer (python/lcprelax/torch.py); usable from NumPy alone.
//
// Problem of sample k (conventions of QpSolver, kkt/qp_solver.hpp, docs/python.md):
//   minimize ½xᵀPx + qᵀx  s.t.  Ax = b,  l ≤ Gx ≤ u,  xl ≤ x ≤ xu
// with the patterns of P (UPPER triangle), A, G fixed at construction. Matrix VALUES are
// passed as arrays over the stored entries in the order of the canonical CSC pattern
// (`P_pattern.data`, column by column, rows sorted, duplicates summed); None keeps the
// pattern matrix's own values. Vectors: None means q = 0 (q is required), l, xl = −∞,
// u, xu = +∞; b is required when A has rows. Batched arguments: batch.hpp.
// engine: "sparse" solves every sample with QpSolver, "dense" with DenseQpSolver (tiny
// problems, kkt/dense_qp_solver.hpp: hands a sample it cannot solve to QpSolver), "auto"
// (default) picks dense when DenseQpSolver::suits the pattern. Every sample is solved the way
// its solver solves it alone (setup() the first time, update() afterwards: the values equal
// those of a fresh setup), so its result equals, bit for bit, that of a lone solver of the
// same kind with the same settings.
// generation counts solve() calls; backward() applies to the latest one.
#include "batch.hpp"

#include <lcprelax/kkt/dense_qp_solver.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <array>
#include <limits>
#include <memory>
#include <mutex>

namespace lcprelax::python {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct PyQpBatchResult {
  py::array_t<double> x, y, z, z_bounds, objective, primal_residual, dual_residual, duality_gap;
  py::array_t<int> iterations;
  py::array_t<bool> has_solution;
  std::vector<std::string> status;
  long long generation = 0;
};

class PyQpBatch {
 public:
  PyQpBatch(const py::object& P, const py::object& A, const py::object& G, int threads, const std::string& engine,
            const QpSettings& s)
      : settings_(s), threads_(threads) {
    if (engine != "auto" && engine != "dense" && engine != "sparse")
      throw InputError("QpBatch: engine must be \"auto\", \"dense\" or \"sparse\", got \"" + engine + "\"");
    if (std::string e = s.validation_error(); !e.empty()) throw InputError("QpSettings: " + e);
    pattern_.P = to_sparse(P, "P");
    const Index n = static_cast<Index>(pattern_.P.cols());
    if (pattern_.P.rows() != n) throw InputError("P must be square, got " + std::to_string(pattern_.P.rows()) + "×" + std::to_string(n));
    pattern_.A = A.is_none() ? SparseMatrix(0, n) : to_sparse(A, "A");
    pattern_.G = G.is_none() ? SparseMatrix(0, n) : to_sparse(G, "G");
    if (pattern_.A.cols() != n || pattern_.G.cols() != n)
      throw InputError("A and G must have as many columns as P (" + std::to_string(n) + ")");
    pattern_.q = Vector::Zero(n);
    pattern_.b = Vector::Zero(pattern_.A.rows());
    pattern_.l = Vector::Constant(pattern_.G.rows(), -kInf);
    pattern_.u = Vector::Constant(pattern_.G.rows(), kInf);
    pattern_.xl = Vector::Constant(n, -kInf);
    pattern_.xu = Vector::Constant(n, kInf);
    dense_ = engine == "dense" || (engine == "auto" && DenseQpSolver::suits(pattern_));
    if (engine == "dense" && !DenseQpSolver::suits(pattern_))
      throw InputError("QpBatch: engine \"dense\" is for problems with n + rows of A + 2·rows of G + 2n <= " +
                       std::to_string(DenseQpSolver::kMaxDimension) + "; use \"sparse\" or \"auto\"");
  }

  PyQpBatchResult solve(const py::object& q, const py::object& P, const py::object& A, const py::object& b,
                        const py::object& G, const py::object& l, const py::object& u, const py::object& xl,
                        const py::object& xu) {
    if (q.is_none()) throw py::type_error("QpBatch.solve(): q is required");
    const Index n = num_variables(), me = num_equalities(), mi = num_inequalities();
    if (me > 0 && b.is_none()) throw InputError("QpBatch.solve(): b is required (A has " + std::to_string(me) + " rows)");
    BatchArgs args;
    const BatchRows rq = args.add(q, "q", n), rP = args.add(P, "P", nnz(pattern_.P)), rA = args.add(A, "A", nnz(pattern_.A));
    const BatchRows rb = args.add(b, "b", me), rG = args.add(G, "G", nnz(pattern_.G));
    const BatchRows rl = args.add(l, "l", mi), ru = args.add(u, "u", mi), rxl = args.add(xl, "xl", n), rxu = args.add(xu, "xu", n);
    const Index B = args.batch_size();
    Busy busy(mutex_, "QpBatch");
    resize(B);
    ++generation_;
    solved_ = false;
    {
      py::gil_scoped_release nogil;
      for_each_sample(B, threads_, [&](Index k) {
        QpProblem& p = problems_[static_cast<std::size_t>(k)];
        auto fill = [k](const BatchRows& r, double* dst, Index len) {
          if (r.given()) copy_row(r.row(k), len, dst);
        };
        fill(rq, p.q.data(), n), fill(rP, p.P.valuePtr(), nnz(p.P)), fill(rA, p.A.valuePtr(), nnz(p.A));
        fill(rb, p.b.data(), me), fill(rG, p.G.valuePtr(), nnz(p.G)), fill(rl, p.l.data(), mi);
        fill(ru, p.u.data(), mi), fill(rxl, p.xl.data(), n), fill(rxu, p.xu.data(), n);
        char& ready = set_up_[static_cast<std::size_t>(k)];
        try {
          if (dense_) {
            DenseQpSolver& s = *dense_solvers_[static_cast<std::size_t>(k)];
            ready ? s.update(p) : s.setup(p);
            ready = 1;
            s.solve();
          } else {
            QpSolver& s = *solvers_[static_cast<std::size_t>(k)];
            ready ? s.update(p) : s.setup(p);
            ready = 1;
            s.solve();
          }
        } catch (...) {
          ready = 0;  // the next solve() starts this sample from setup()
          throw;
        }
      });
    }
    solved_ = true;
    return result();
  }

  py::dict backward(const py::object& dl_dx, const py::object& dl_dy, const py::object& dl_dz) {
    if (!solved_) throw std::logic_error("QpBatch.backward() before solve()");
    const Index n = num_variables(), me = num_equalities(), mi = num_inequalities();
    const Index B = static_cast<Index>(problems_.size());
    BatchArgs args;
    const BatchRows rx = args.add(dl_dx, "dl_dx", n), ry = args.add(dl_dy, "dl_dy", me), rz = args.add(dl_dz, "dl_dz", mi);
    if (!rx.given()) throw py::type_error("QpBatch.backward(): dl_dx is required");
    if (args.batch_size() != 1 && args.batch_size() != B)
      throw InputError("QpBatch.backward(): batch size " + std::to_string(args.batch_size()) + ", the last solve() had " +
                       std::to_string(B));
    for (Index k = 0; k < B; ++k) {
      const QpStatus st = result_of(k).info.status;
      if (!has_solution(st))
        throw std::logic_error("QpBatch.backward(): sample " + std::to_string(k) + " has status " + to_string(st) +
                               ", no solution to differentiate");
    }
    const Index nP = nnz(pattern_.P), nA = nnz(pattern_.A), nG = nnz(pattern_.G);
    py::array_t<double> dP = batch_array(B, nP), dq = batch_array(B, n), dA = batch_array(B, nA), db = batch_array(B, me);
    py::array_t<double> dG = batch_array(B, nG), dl = batch_array(B, mi), du = batch_array(B, mi);
    py::array_t<double> dxl = batch_array(B, n), dxu = batch_array(B, n), res = batch_array(B, 1);
    double *pP = dP.mutable_data(), *pq = dq.mutable_data(), *pA = dA.mutable_data(), *pb = db.mutable_data();
    double *pG = dG.mutable_data(), *pl = dl.mutable_data(), *pu = du.mutable_data(), *pxl = dxl.mutable_data();
    double *pxu = dxu.mutable_data(), *pres = res.mutable_data();
    Busy busy(mutex_, "QpBatch");
    {
      py::gil_scoped_release nogil;
      for_each_sample(B, threads_, [&](Index k) {
        // Per-sample buffers, reused from call to call (the dense engine then allocates nothing).
        Vector& gx = grad_in_[static_cast<std::size_t>(k)][0];
        Vector& gy = grad_in_[static_cast<std::size_t>(k)][1];
        Vector& gz = grad_in_[static_cast<std::size_t>(k)][2];
        gx = Eigen::Map<const Vector>(rx.row(k), n);
        if (ry.given()) gy = Eigen::Map<const Vector>(ry.row(k), me); else gy.resize(0);
        if (rz.given()) gz = Eigen::Map<const Vector>(rz.row(k), mi); else gz.resize(0);
        QpGradient& g = grads_[static_cast<std::size_t>(k)];
        if (dense_)
          dense_solvers_[static_cast<std::size_t>(k)]->backward(gx, gy, gz, g);
        else
          g = solvers_[static_cast<std::size_t>(k)]->backward(gx, gy, gz);
        if (nnz(g.dP) != nP || nnz(g.dA) != nA || nnz(g.dG) != nG)
          throw std::runtime_error("QpBatch.backward(): a gradient left the input's sparsity pattern");
        copy_row(g.dP.valuePtr(), nP, pP + k * nP), copy_or_nan(g.dq, n, pq + k * n);
        copy_row(g.dA.valuePtr(), nA, pA + k * nA), copy_or_nan(g.db, me, pb + k * me);
        copy_row(g.dG.valuePtr(), nG, pG + k * nG), copy_or_nan(g.dl, mi, pl + k * mi);
        copy_or_nan(g.du, mi, pu + k * mi), copy_or_nan(g.dxl, n, pxl + k * n);
        copy_or_nan(g.dxu, n, pxu + k * n);
        pres[k] = g.adjoint_residual;
      });
    }
    py::dict d;
    d["P"] = dP, d["q"] = dq, d["A"] = dA, d["b"] = db, d["G"] = dG, d["l"] = dl, d["u"] = du;
    d["xl"] = dxl, d["xu"] = dxu, d["adjoint_residual"] = res.attr("reshape")(B);
    return d;
  }

  Index num_variables() const { return static_cast<Index>(pattern_.P.cols()); }
  Index num_equalities() const { return static_cast<Index>(pattern_.A.rows()); }
  Index num_inequalities() const { return static_cast<Index>(pattern_.G.rows()); }
  Index batch_size() const { return static_cast<Index>(problems_.size()); }
  long long generation() const { return generation_; }
  int threads() const { return threads_; }
  std::string engine() const { return dense_ ? "dense" : "sparse"; }
  const QpProblem& pattern() const { return pattern_; }

 private:
  static Index nnz(const SparseMatrix& M) { return static_cast<Index>(M.nonZeros()); }

  const QpResult& result_of(Index k) const {
    return dense_ ? dense_solvers_[static_cast<std::size_t>(k)]->result() : solvers_[static_cast<std::size_t>(k)]->result();
  }

  // B samples, each starting from the pattern problem; a new B restarts every sample.
  void resize(Index B) {
    if (static_cast<Index>(problems_.size()) == B) return;
    problems_.assign(static_cast<std::size_t>(B), pattern_);
    solvers_.clear();
    dense_solvers_.clear();
    for (Index k = 0; k < B; ++k) {
      if (dense_)
        dense_solvers_.push_back(std::make_unique<DenseQpSolver>(settings_));
      else
        solvers_.push_back(std::make_unique<QpSolver>(settings_));
    }
    set_up_.assign(static_cast<std::size_t>(B), 0);
    grads_.assign(static_cast<std::size_t>(B), QpGradient{});
    grad_in_.assign(static_cast<std::size_t>(B), {});
    solved_ = false;
  }

  PyQpBatchResult result() const {
    const Index B = batch_size(), n = num_variables(), me = num_equalities(), mi = num_inequalities();
    PyQpBatchResult r;
    r.x = batch_array(B, n), r.y = batch_array(B, me), r.z = batch_array(B, mi), r.z_bounds = batch_array(B, n);
    r.objective = py::array_t<double>(B), r.primal_residual = py::array_t<double>(B);
    r.dual_residual = py::array_t<double>(B), r.duality_gap = py::array_t<double>(B);
    r.iterations = py::array_t<int>(B), r.has_solution = py::array_t<bool>(B);
    r.generation = generation_;
    for (Index k = 0; k < B; ++k) {
      const QpResult& s = result_of(k);
      copy_or_nan(s.x, n, r.x.mutable_data() + k * n), copy_or_nan(s.y, me, r.y.mutable_data() + k * me);
      copy_or_nan(s.z, mi, r.z.mutable_data() + k * mi), copy_or_nan(s.z_bounds, n, r.z_bounds.mutable_data() + k * n);
      r.objective.mutable_data()[k] = s.info.objective;
      r.primal_residual.mutable_data()[k] = s.info.primal_residual;
      r.dual_residual.mutable_data()[k] = s.info.dual_residual;
      r.duality_gap.mutable_data()[k] = s.info.duality_gap;
      r.iterations.mutable_data()[k] = s.info.iterations;
      r.has_solution.mutable_data()[k] = has_solution(s.info.status);
      r.status.push_back(to_string(s.info.status));
    }
    return r;
  }

  QpSettings settings_;
  int threads_;
  QpProblem pattern_;
  std::vector<QpProblem> problems_;
  std::vector<std::unique_ptr<QpSolver>> solvers_;
  std::vector<std::unique_ptr<DenseQpSolver>> dense_solvers_;
  bool dense_ = false;
  std::vector<char> set_up_;
  std::vector<QpGradient> grads_;               // backward()'s output per sample
  std::vector<std::array<Vector, 3>> grad_in_;  // backward()'s dl_dx, dl_dy, dl_dz per sample
  bool solved_ = false;
  long long generation_ = 0;
  std::mutex mutex_;
};

}  // namespace

void bind_qp_batch(py::module_& m) {
  py::class_<PyQpBatchResult>(m, "QpBatchResult", "Result of QpBatch.solve(): arrays with one row per sample")
      .def_readonly("x", &PyQpBatchResult::x).def_readonly("y", &PyQpBatchResult::y)
      .def_readonly("z", &PyQpBatchResult::z).def_readonly("z_bounds", &PyQpBatchResult::z_bounds)
      .def_readonly("objective", &PyQpBatchResult::objective)
      .def_readonly("primal_residual", &PyQpBatchResult::primal_residual)
      .def_readonly("dual_residual", &PyQpBatchResult::dual_residual)
      .def_readonly("duality_gap", &PyQpBatchResult::duality_gap)
      .def_readonly("iterations", &PyQpBatchResult::iterations)
      .def_readonly("has_solution", &PyQpBatchResult::has_solution, "status is solved or solved_inaccurate")
      .def_readonly("status", &PyQpBatchResult::status, "list of status names, one per sample")
      .def_readonly("generation", &PyQpBatchResult::generation, "QpBatch.generation of this solve");

  py::class_<PyQpBatch>(m, "QpBatch",
                        "B QPs with one sparsity pattern, solved in parallel (OpenMP); each sample keeps its\n"
                        "factorization for backward(). See docs/python.md.")
      .def(py::init([](const py::object& P, const py::object& A, const py::object& G, int threads,
                       const std::string& engine, const py::kwargs& kw) {
             QpSettings s;
             apply_settings(s, qp_fields(), kw, "QpBatch()");
             return std::make_unique<PyQpBatch>(P, A, G, threads, engine, s);
           }),
           py::arg("P"), py::arg("A") = py::none(), py::arg("G") = py::none(), py::kw_only(), py::arg("threads") = 0,
           py::arg("engine") = "auto",
           "QpBatch(P, A=None, G=None, *, threads=0, engine=\"auto\", **settings): the patterns (scipy.sparse;\n"
           "P its UPPER triangle) and QpSettings keywords; threads <= 0 means OpenMP's default; engine\n"
           "\"sparse\" (QpSolver), \"dense\" (DenseQpSolver, tiny problems) or \"auto\" (dense when it suits)")
      .def("solve", &PyQpBatch::solve, py::arg("q"), py::kw_only(), py::arg("P") = py::none(),
           py::arg("A") = py::none(), py::arg("b") = py::none(), py::arg("G") = py::none(), py::arg("l") = py::none(),
           py::arg("u") = py::none(), py::arg("xl") = py::none(), py::arg("xu") = py::none(),
           "Solves every sample. Each argument: shape (k,) shared or (B, k) per sample; P, A, G are\n"
           "the VALUES on the pattern's stored entries (CSC order of P_pattern etc.), None keeps the\n"
           "pattern's values. Returns a QpBatchResult.")
      .def("backward", &PyQpBatch::backward, py::arg("dl_dx"), py::arg("dl_dy") = py::none(),
           py::arg("dl_dz") = py::none(),
           "Adjoint of the last solve for every sample with the final factorizations; returns a dict\n"
           "of arrays dl/d(P, q, A, b, G, l, u, xl, xu) (matrix gradients on the pattern's entries)\n"
           "and adjoint_residual. UsageError when a sample has no solution.")
      .def_property_readonly("n", &PyQpBatch::num_variables)
      .def_property_readonly("num_equalities", &PyQpBatch::num_equalities)
      .def_property_readonly("num_inequalities", &PyQpBatch::num_inequalities)
      .def_property_readonly("batch_size", &PyQpBatch::batch_size, "B of the last solve (0 before)")
      .def_property_readonly("generation", &PyQpBatch::generation, "number of solve() calls so far")
      .def_property_readonly("threads", &PyQpBatch::threads)
      .def_property_readonly("engine", &PyQpBatch::engine, "\"dense\" or \"sparse\": the solver of every sample")
      .def_property_readonly("P_pattern", [](const PyQpBatch& b) { return to_scipy(b.pattern().P); })
      .def_property_readonly("A_pattern", [](const PyQpBatch& b) { return to_scipy(b.pattern().A); })
      .def_property_readonly("G_pattern", [](const PyQpBatch& b) { return to_scipy(b.pattern().G); });
}

}  // namespace lcprelax::python
