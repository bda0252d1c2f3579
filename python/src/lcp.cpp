// Binds lcprelax::LemkeSolver (lcp/lemke.hpp) as lcprelax.LemkeSolver, with LcpResult and
// LcpGradient as read-only result objects holding copies.
//
// Conventions (lcp/lcp_types.hpp, docs/conventions.md): find z, w with w = Mz + q,
// 0 ≤ z ⊥ w ≥ 0 (M n×n scipy.sparse, any format; q a 1-D float array); the reported
// residual `complementarity` is max_i |min(z_i, w_i)| with w recomputed from z. Settings are
// keyword arguments named as the LemkeSettings fields (method as 'automatic', 'dense' or
// 'sparse'; covering as a 1-D array). solve() and backward() release the GIL; one solver
// must not be used from two threads at once (UsageError).
#include "bindings.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <memory>
#include <mutex>
#include <stdexcept>

namespace lcprelax::python {
const std::vector<SettingField<LemkeSettings>>& lemke_fields() {
  using S = LemkeSettings;
  static const std::vector<SettingField<S>> fields = {
      enum_field("method", &S::method, {LemkeMethod::automatic, LemkeMethod::dense, LemkeMethod::sparse}),
      int_field("dense_max_n", &S::dense_max_n),
      int_field("max_pivots", &S::max_pivots),
      double_field("pivot_tolerance", &S::pivot_tolerance),
      double_field("residual_tolerance", &S::residual_tolerance),
      int_field("refactor_interval", &S::refactor_interval),
      double_field("lu_pivot_tolerance", &S::lu_pivot_tolerance),
      enum_field("lu_ordering", &S::lu_ordering, {LuOrdering::amd, LuOrdering::colamd}),
      bool_field("sparse_tie_rows", &S::sparse_tie_rows),
      bool_field("sparse_columns", &S::sparse_columns),
      bool_field("lifted_basis", &S::lifted_basis),
      int_field("covering_retries", &S::covering_retries),
      int_field("regularization_retries", &S::regularization_retries),
      double_field("regularization", &S::regularization),
      SettingField<S>{"covering", [](S& s, py::handle v) { s.covering = to_vector(v, "covering"); },
                      [](const S& s) { return py::object(to_numpy(s.covering)); }},
      bool_field("crash_start", &S::crash_start),
      bool_field("crash_cold_fallback", &S::crash_cold_fallback),
      bool_field("crash_covering_from_basis", &S::crash_covering_from_basis),
      int_field("crash_flip_rounds", &S::crash_flip_rounds)};
  return fields;
}

namespace {

struct PyLcpResult {
  std::string status, message, method;
  py::array_t<double> z, w;
  py::array_t<bool> z_basic;
  long pivots;
  double complementarity, seconds;
  bool has_solution, warm_started;
  // LcpInfo's diagnostics of how the pivots went
  bool crash_started;
  long crash_pivots, tie_breaks, refactorizations, ray_rechecks;
  int repair_rounds;
  double regularization;
  long purification_steps;
};

struct PyLcpGradient {
  py::object dM;
  py::array_t<double> dq;
};

class PyLemkeSolver {
 public:
  explicit PyLemkeSolver(const LemkeSettings& s) : settings_(s), solver_(s) {}

  // lifted: None, or (J, d, H) with M = J diag(d) Jᵀ + H (lcp_types.hpp LcpLiftedForm).
  void setup(const py::object& M, const py::object& q, const py::object& lifted) {
    const SparseMatrix Ms = to_sparse(M, "M");
    if (Ms.rows() != Ms.cols())
      throw InputError("M is " + std::to_string(Ms.rows()) + "x" + std::to_string(Ms.cols()) + ", must be square");
    const Vector qv = to_vector(q, "q", static_cast<Index>(Ms.rows()), "rows of M");
    LcpLiftedForm form;
    const bool has_form = !lifted.is_none();
    if (has_form) {
      const py::tuple t = py::cast<py::tuple>(lifted);
      if (t.size() != 3) throw InputError("lifted must be a tuple (J, d, H)");
      form.J = to_sparse(t[0], "J");
      form.d = to_vector(t[1], "d", static_cast<Index>(form.J.cols()), "columns of J");
      form.H = to_sparse(t[2], "H");
    }
    Busy busy(mutex_, "LemkeSolver");
    py::gil_scoped_release nogil;
    if (has_form) solver_.setup(Ms, qv, form);
    else solver_.setup(Ms, qv);
    n_ = static_cast<Index>(qv.size());
  }

  void update_q(const py::object& q) {
    if (n_ < 0) throw std::logic_error("LemkeSolver.update_q() before setup()");
    const Vector qv = to_vector(q, "q", n_, "rows of M");
    Busy busy(mutex_, "LemkeSolver");
    solver_.update_q(qv);
  }

  void warm_start(const py::object& z_basic) {
    if (n_ < 0) throw std::logic_error("LemkeSolver.warm_start() before setup()");
    const std::vector<bool> basis = to_bool_vector(z_basic, "z_basic");
    if (static_cast<Index>(basis.size()) != n_)
      throw InputError("z_basic has length " + std::to_string(basis.size()) + ", expected " + std::to_string(n_));
    Busy busy(mutex_, "LemkeSolver");
    solver_.warm_start(basis);
  }

  void warm_start_point(const py::object& z, const py::object& fallback) {
    if (n_ < 0) throw std::logic_error("LemkeSolver.warm_start_point() before setup()");
    const Vector zv = to_vector(z, "z", n_, "rows of M");
    std::vector<bool> basis;
    if (!fallback.is_none()) {
      basis = to_bool_vector(fallback, "fallback");
      if (static_cast<Index>(basis.size()) != n_)
        throw InputError("fallback has length " + std::to_string(basis.size()) + ", expected " + std::to_string(n_));
    }
    Busy busy(mutex_, "LemkeSolver");
    solver_.warm_start_point(zv, basis);
  }

  PyLcpResult solve() {
    Busy busy(mutex_, "LemkeSolver");
    const LcpResult* r = nullptr;
    {
      py::gil_scoped_release nogil;
      r = &solver_.solve();
    }
    const LcpInfo& i = r->info;
    py::array_t<bool> basic(static_cast<py::ssize_t>(r->z_basic.size()));
    for (std::size_t k = 0; k < r->z_basic.size(); ++k) basic.mutable_data()[k] = r->z_basic[k];
    return {to_string(i.status), i.message,   to_string(i.method), to_numpy(r->z),     to_numpy(r->w),
            basic,           i.pivots,    i.complementarity,   i.seconds,          has_solution(i.status),
            i.warm_started,  i.crash_started, i.crash_pivots,  i.tie_breaks,       i.refactorizations,
            i.ray_rechecks,  i.repair_rounds, i.regularization,   i.purification_steps};
  }

  PyLcpGradient backward(const py::object& dl_dz) {
    if (n_ < 0) throw std::logic_error("LemkeSolver.backward() before setup() and solve()");
    const Vector g = to_vector(dl_dz, "dl_dz", n_, "rows of M");
    Busy busy(mutex_, "LemkeSolver");
    LcpGradient grad;
    {
      py::gil_scoped_release nogil;
      grad = solver_.backward(g);
    }
    return {to_scipy(grad.dM), to_numpy(grad.dq)};
  }

  py::dict settings() const { return settings_dict(settings_, lemke_fields()); }

 private:
  LemkeSettings settings_;
  LemkeSolver solver_;
  Index n_ = -1;
  std::mutex mutex_;
};

}  // namespace

void bind_lcp(py::module_& m) {
  py::class_<PyLcpResult>(m, "LcpResult", "Result of LemkeSolver.solve() (copies; see lcp/lcp_types.hpp)")
      .def_readonly("status", &PyLcpResult::status, "'solved', 'ray_termination', 'pivot_limit', ...")
      .def_readonly("message", &PyLcpResult::message)
      .def_readonly("z", &PyLcpResult::z)
      .def_readonly("w", &PyLcpResult::w, "Mz + q")
      .def_readonly("z_basic", &PyLcpResult::z_basic, "final basis (True: z_i basic), usable as a warm start")
      .def_readonly("pivots", &PyLcpResult::pivots)
      .def_readonly("complementarity", &PyLcpResult::complementarity, "max_i |min(z_i, w_i)|")
      .def_readonly("seconds", &PyLcpResult::seconds)
      .def_readonly("method", &PyLcpResult::method, "'dense' or 'sparse': the basis factorization used")
      .def_readonly("has_solution", &PyLcpResult::has_solution)
      .def_readonly("warm_started", &PyLcpResult::warm_started,
                    "the warm-start basis was complementary and feasible (0 pivots)")
      .def_readonly("crash_started", &PyLcpResult::crash_started,
                    "Lemke ran from the (infeasible) warm-start basis: a crash path")
      .def_readonly("crash_pivots", &PyLcpResult::crash_pivots, "pivots of that crash path (included in pivots)")
      .def_readonly("tie_breaks", &PyLcpResult::tie_breaks,
                    "pivots whose ratio test compared rows of B⁻¹ (lexicographic ties)")
      .def_readonly("refactorizations", &PyLcpResult::refactorizations, "basis factorizations from scratch")
      .def_readonly("ray_rechecks", &PyLcpResult::ray_rechecks,
                    "rays found with an updated factorization, rechecked after a fresh one")
      .def_readonly("repair_rounds", &PyLcpResult::repair_rounds,
                    "rounds of repair of a singular crash basis")
      .def_readonly("regularization", &PyLcpResult::regularization,
                    "ε of an accepted retry on M + εI (then the answer solves that LCP), 0 if none")
      .def_readonly("purification_steps", &PyLcpResult::purification_steps,
                    "steps of the purification of a warm_start_point (not counted in pivots)")
      .def("__repr__", [](const PyLcpResult& r) {
        return "LcpResult(status='" + r.status + "', pivots=" + std::to_string(r.pivots) +
               ", complementarity=" + std::string(py::repr(py::float_(r.complementarity))) + ")";
      });

  py::class_<PyLcpGradient>(m, "LcpGradient", "Gradients of LemkeSolver.backward()")
      .def_readonly("dM", &PyLcpGradient::dM, "scipy CSC on M's pattern")
      .def_readonly("dq", &PyLcpGradient::dq);

  py::class_<PyLemkeSolver>(m, "LemkeSolver", "Lexicographic Lemke LCP solver (lcp/lemke.hpp, docs/python.md)")
      .def(py::init([](const py::kwargs& kw) {
             LemkeSettings s;
             apply_settings(s, lemke_fields(), kw, "LemkeSolver()");
             return std::make_unique<PyLemkeSolver>(s);
           }),
           "LemkeSolver(**settings): keyword arguments named as the LemkeSettings fields")
      .def("setup", &PyLemkeSolver::setup, py::arg("M"), py::arg("q"), py::arg("lifted") = py::none(),
           "Validates the LCP w = Mz + q, 0 <= z _|_ w >= 0 (M: n x n scipy.sparse; q: 1-D float array); "
           "lifted: None or (J, d, H) with M = J diag(d) J^T + H (J: n x m scipy.sparse, d: m positive "
           "floats, H: n x n scipy.sparse), which the sparse basis factorizes instead of M's columns")
      .def("update_q", &PyLemkeSolver::update_q, py::arg("q"), "new q of the same size, M kept")
      .def("warm_start", &PyLemkeSolver::warm_start, py::arg("z_basic"), "basis to try first (bool array, n)")
      .def("warm_start_point", &PyLemkeSolver::warm_start_point, py::arg("z"), py::arg("fallback") = py::none(),
           "approximate solution (float array, n) to purify into a vertex basis and start from; fallback: "
           "the basis (bool array, n) used where purification does not end complementary")
      .def("solve", &PyLemkeSolver::solve, "Runs Lemke's method; returns an LcpResult (copies)")
      .def("backward", &PyLemkeSolver::backward, py::arg("dl_dz"),
           "Given dl/dz returns an LcpGradient (dl/dM, dl/dq); needs status solved (else UsageError)")
      .def_property_readonly("settings", &PyLemkeSolver::settings, "the settings as a dict");
}

}  // namespace lcprelax::python
