// Binds lcprelax::QpSolver (kkt/qp_solver.hpp) as lcprelax.QpSolver, with QpResult and
// QpGradient as read-only result objects holding copies (NumPy arrays, scipy CSC matrices).
//
// Conventions (kkt/qp_problem.hpp, docs/conventions.md, docs/python.md):
//   minimize ½xᵀPx + qᵀx + r  s.t.  Ax = b,  l ≤ Gx ≤ u,  xl ≤ x ≤ xu
// - P is given as its UPPER triangle (with the diagonal); an entry below the diagonal is an
//   InputError. A stored off-diagonal p at (i, j) means P(i, j) = P(j, i) = p.
// - Px + q + Aᵀy + Gᵀz + z_bounds = 0, z > 0 where an upper side is active, z < 0 where a
//   lower side is.
// - Omitted A/G mean no rows; omitted l, xl mean −∞, u, xu mean +∞.
// - Settings are keyword arguments named as the QpSettings fields (max_iter, eps_abs, ...);
//   enums (kkt_form, kkt_ordering, kkt_backend) as their to_string() names.
// setup(), update(), solve() and backward() release the GIL; one solver object must not be
// used from two threads at once (a second call while one runs raises UsageError).
#include "bindings.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace lcprelax::python {

const std::vector<SettingField<QpSettings>>& qp_fields() {
  using S = QpSettings;
  static const std::vector<SettingField<S>> fields = {
      double_field("eps_abs", &S::eps_abs), double_field("eps_rel", &S::eps_rel),
      double_field("eps_infeasible", &S::eps_infeasible), int_field("max_iter", &S::max_iter),
      double_field("time_limit", &S::time_limit), double_field("reg_primal", &S::reg_primal),
      double_field("reg_dual", &S::reg_dual), double_field("reg_max", &S::reg_max),
      int_field("max_refinement", &S::max_refinement),
      double_field("conservative_row_reg_drop", &S::conservative_row_reg_drop),
      double_field("primal_reg_drop", &S::primal_reg_drop), bool_field("exact_bound_steps", &S::exact_bound_steps),
      bool_field("clean_bound_multipliers", &S::clean_bound_multipliers), bool_field("polish", &S::polish),
      bool_field("polish_forcing_rows", &S::polish_forcing_rows),
      bool_field("polish_least_norm", &S::polish_least_norm),
      int_field("centrality_correctors", &S::centrality_correctors),
      double_field("multiplier_restart_growth", &S::multiplier_restart_growth),
      int_field("ruiz_iterations", &S::ruiz_iterations), double_field("step_fraction", &S::step_fraction),
      enum_field("kkt_form", &S::kkt_form, {KktForm::automatic, KktForm::full, KktForm::eliminated}),
      enum_field("kkt_ordering", &S::kkt_ordering, {KktOrdering::automatic, KktOrdering::amd}),
      enum_field("kkt_backend", &S::kkt_backend,
                 {KktBackend::automatic, KktBackend::cholmod, KktBackend::dense, KktBackend::mumps,
                  KktBackend::mumps_distributed}),
      int_field("dense_max_kkt", &S::dense_max_kkt), bool_field("verbose", &S::verbose),
      bool_field("infeasibility_lps", &S::infeasibility_lps), bool_field("check_convexity", &S::check_convexity)};
  return fields;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct PyQpResult {
  std::string status, message;
  py::array_t<double> x, y, z, z_bounds;
  double objective, primal_residual, dual_residual, duality_gap, setup_seconds, solve_seconds;
  int iterations;
  bool has_solution, polish_accepted;
};

struct PyQpGradient {
  py::object dP, dA, dG;
  py::array_t<double> dq, db, dl, du, dxl, dxu;
  double adjoint_residual;
};

class PyQpSolver {
 public:
  explicit PyQpSolver(const QpSettings& s) : solver_(s) {}

  void setup(const py::object& P, const py::object& q, const py::object& A, const py::object& b, const py::object& G,
             const py::object& l, const py::object& u, const py::object& xl, const py::object& xu, double r) {
    if (q.is_none()) throw py::type_error("setup(): q is required");
    QpProblem p;
    p.q = to_vector(q, "q");
    const Index n = static_cast<Index>(p.q.size());
    p.r = r;
    p.P = P.is_none() ? SparseMatrix(n, n) : to_sparse(P, "P");
    p.A = A.is_none() ? SparseMatrix(0, n) : to_sparse(A, "A");
    if (A.is_none() != b.is_none()) throw InputError("setup(): A and b must be given together");
    p.b = b.is_none() ? Vector(0) : to_vector(b, "b", static_cast<Index>(p.A.rows()), "rows of A");
    p.G = G.is_none() ? SparseMatrix(0, n) : to_sparse(G, "G");
    if (G.is_none() && !(l.is_none() && u.is_none())) throw InputError("setup(): l or u given without G");
    const Index mi = static_cast<Index>(p.G.rows());
    p.l = l.is_none() ? Vector::Constant(mi, -kInf) : to_vector(l, "l", mi, "rows of G");
    p.u = u.is_none() ? Vector::Constant(mi, kInf) : to_vector(u, "u", mi, "rows of G");
    p.xl = xl.is_none() ? Vector::Constant(n, -kInf) : to_vector(xl, "xl", n, "length of q");
    p.xu = xu.is_none() ? Vector::Constant(n, kInf) : to_vector(xu, "xu", n, "length of q");
    Busy busy(mutex_, "QpSolver");
    ready_ = false;
    {
      py::gil_scoped_release nogil;
      solver_.setup(p);
    }
    problem_ = std::move(p);
    ready_ = true;
  }

  void update(const py::object& P, const py::object& q, const py::object& A, const py::object& b,
              const py::object& G, const py::object& l, const py::object& u, const py::object& xl,
              const py::object& xu, const py::object& r) {
    if (!ready_) throw std::logic_error("QpSolver.update() before setup()");
    QpProblem p = problem_;
    const Index n = p.num_variables(), me = p.num_equalities(), mi = p.num_inequalities();
    if (!P.is_none()) p.P = to_sparse(P, "P");
    if (!q.is_none()) p.q = to_vector(q, "q", n, "number of variables");
    if (!A.is_none()) p.A = to_sparse(A, "A");
    if (!b.is_none()) p.b = to_vector(b, "b", me, "rows of A");
    if (!G.is_none()) p.G = to_sparse(G, "G");
    if (!l.is_none()) p.l = to_vector(l, "l", mi, "rows of G");
    if (!u.is_none()) p.u = to_vector(u, "u", mi, "rows of G");
    if (!xl.is_none()) p.xl = to_vector(xl, "xl", n, "number of variables");
    if (!xu.is_none()) p.xu = to_vector(xu, "xu", n, "number of variables");
    if (!r.is_none()) p.r = setting_double(r, "r");
    Busy busy(mutex_, "QpSolver");
    {
      py::gil_scoped_release nogil;
      solver_.update(p);
    }
    problem_ = std::move(p);
  }

  void warm_start(const py::object& x, const py::object& y, const py::object& z, const py::object& zb) {
    if (!ready_) throw std::logic_error("QpSolver.warm_start() before setup()");
    const Index n = problem_.num_variables();
    const Vector xv = to_vector(x, "x", n, "number of variables");
    const Vector yv = to_vector(y, "y", problem_.num_equalities(), "rows of A");
    const Vector zv = to_vector(z, "z", problem_.num_inequalities(), "rows of G");
    const Vector bv = to_vector(zb, "z_bounds", n, "number of variables");
    Busy busy(mutex_, "QpSolver");
    solver_.warm_start(xv, yv, zv, bv);
  }

  PyQpResult solve() {
    Busy busy(mutex_, "QpSolver");
    const QpResult* r = nullptr;
    {
      py::gil_scoped_release nogil;
      r = &solver_.solve();
    }
    const QpInfo& i = r->info;
    return {to_string(i.status), i.message, to_numpy(r->x), to_numpy(r->y), to_numpy(r->z), to_numpy(r->z_bounds),
            i.objective, i.primal_residual, i.dual_residual, i.duality_gap, i.setup_seconds, i.solve_seconds,
            i.iterations, has_solution(i.status), i.polish_accepted};
  }

  PyQpGradient backward(const py::object& dl_dx, const py::object& dl_dy, const py::object& dl_dz) {
    if (!ready_) throw std::logic_error("QpSolver.backward() before setup() and solve()");
    const Vector dx = to_vector(dl_dx, "dl_dx", problem_.num_variables(), "number of variables");
    const Vector dy = dl_dy.is_none() ? Vector() : to_vector(dl_dy, "dl_dy", problem_.num_equalities(), "rows of A");
    const Vector dz = dl_dz.is_none() ? Vector() : to_vector(dl_dz, "dl_dz", problem_.num_inequalities(), "rows of G");
    Busy busy(mutex_, "QpSolver");
    QpGradient g;
    {
      py::gil_scoped_release nogil;
      g = solver_.backward(dx, dy, dz);
    }
    return {to_scipy(g.dP), to_scipy(g.dA), to_scipy(g.dG), to_numpy(g.dq), to_numpy(g.db), to_numpy(g.dl),
            to_numpy(g.du), to_numpy(g.dxl), to_numpy(g.dxu), g.adjoint_residual};
  }

  py::dict settings() const { return settings_dict(solver_.settings(), qp_fields()); }
  void set_settings(const py::kwargs& kw) {
    QpSettings s = solver_.settings();
    apply_settings(s, qp_fields(), kw, "QpSolver.set_settings()");
    Busy busy(mutex_, "QpSolver");
    solver_.set_settings(s);
  }
  py::object problem() const { return ready_ ? py::object(problem_dict(problem_)) : py::object(py::none()); }

 private:
  QpSolver solver_;
  QpProblem problem_;
  bool ready_ = false;
  std::mutex mutex_;
};

}  // namespace

py::dict problem_dict(const QpProblem& p) {
  py::dict d;
  d["P"] = to_scipy(p.P), d["q"] = to_numpy(p.q), d["A"] = to_scipy(p.A), d["b"] = to_numpy(p.b);
  d["G"] = to_scipy(p.G), d["l"] = to_numpy(p.l), d["u"] = to_numpy(p.u);
  d["xl"] = to_numpy(p.xl), d["xu"] = to_numpy(p.xu), d["r"] = p.r;
  return d;
}

void bind_qp(py::module_& m) {
  py::class_<PyQpResult>(m, "QpResult", "Result of QpSolver.solve() (copies; see kkt/qp_result.hpp)")
      .def_readonly("status", &PyQpResult::status, "'solved', 'solved_inaccurate', 'primal_infeasible', ...")
      .def_readonly("message", &PyQpResult::message)
      .def_readonly("x", &PyQpResult::x).def_readonly("y", &PyQpResult::y)
      .def_readonly("z", &PyQpResult::z).def_readonly("z_bounds", &PyQpResult::z_bounds)
      .def_readonly("objective", &PyQpResult::objective)
      .def_readonly("primal_residual", &PyQpResult::primal_residual)
      .def_readonly("dual_residual", &PyQpResult::dual_residual)
      .def_readonly("duality_gap", &PyQpResult::duality_gap)
      .def_readonly("iterations", &PyQpResult::iterations)
      .def_readonly("has_solution", &PyQpResult::has_solution, "status is solved or solved_inaccurate")
      .def_readonly("polish_accepted", &PyQpResult::polish_accepted)
      .def_readonly("setup_seconds", &PyQpResult::setup_seconds)
      .def_readonly("solve_seconds", &PyQpResult::solve_seconds)
      .def("__repr__", [](const PyQpResult& r) {
        return "QpResult(status='" + r.status + "', objective=" + std::string(py::repr(py::float_(r.objective))) +
               ", iterations=" + std::to_string(r.iterations) + ")";
      });

  py::class_<PyQpGradient>(m, "QpGradient", "Gradients of QpSolver.backward() (see kkt/qp_gradient.hpp)")
      .def_readonly("dP", &PyQpGradient::dP, "scipy CSC on P's upper-triangular pattern")
      .def_readonly("dq", &PyQpGradient::dq).def_readonly("dA", &PyQpGradient::dA)
      .def_readonly("db", &PyQpGradient::db).def_readonly("dG", &PyQpGradient::dG)
      .def_readonly("dl", &PyQpGradient::dl).def_readonly("du", &PyQpGradient::du)
      .def_readonly("dxl", &PyQpGradient::dxl).def_readonly("dxu", &PyQpGradient::dxu)
      .def_readonly("adjoint_residual", &PyQpGradient::adjoint_residual,
                    "relative residual of the adjoint solve; >> 1e-9 means the gradient does not exist");

  py::class_<PyQpSolver>(m, "QpSolver", "Sparse interior-point QP solver (kkt/qp_solver.hpp, docs/python.md)")
      .def(py::init([](const py::kwargs& kw) {
             QpSettings s;
             apply_settings(s, qp_fields(), kw, "QpSolver()");
             return std::make_unique<PyQpSolver>(s);
           }),
           "QpSolver(**settings): keyword arguments named as the QpSettings fields")
      .def("setup", &PyQpSolver::setup, py::arg("P"), py::arg("q"), py::arg("A") = py::none(),
           py::arg("b") = py::none(), py::arg("G") = py::none(), py::arg("l") = py::none(), py::arg("u") = py::none(),
           py::arg("xl") = py::none(), py::arg("xu") = py::none(), py::arg("r") = 0.0,
           "Validates and analyses min ½xᵀPx + qᵀx + r s.t. Ax = b, l ≤ Gx ≤ u, xl ≤ x ≤ xu.\n"
           "P: scipy.sparse, the UPPER triangle of the symmetric PSD Hessian (an entry below the\n"
           "diagonal is an InputError; None means P = 0). A, G: scipy.sparse (any format, CSC\n"
           "used). q, b, l, u, xl, xu: 1-D float arrays; omitted l, xl are -inf, u, xu +inf.")
      .def("update", &PyQpSolver::update, py::kw_only(), py::arg("P") = py::none(), py::arg("q") = py::none(),
           py::arg("A") = py::none(), py::arg("b") = py::none(), py::arg("G") = py::none(),
           py::arg("l") = py::none(), py::arg("u") = py::none(), py::arg("xl") = py::none(),
           py::arg("xu") = py::none(), py::arg("r") = py::none(),
           "New values with the same sparsity pattern; omitted arguments keep their values")
      .def("warm_start", &PyQpSolver::warm_start, py::arg("x"), py::arg("y"), py::arg("z"), py::arg("z_bounds"))
      .def("solve", &PyQpSolver::solve, "Runs the interior point; returns a QpResult (copies)")
      .def("backward", &PyQpSolver::backward, py::arg("dl_dx"), py::arg("dl_dy") = py::none(),
           py::arg("dl_dz") = py::none(),
           "Adjoint pass at the last solution: given dl/dx (and optionally dl/dy, dl/dz; None = 0)\n"
           "returns a QpGradient with dl/d(P, q, A, b, G, l, u, xl, xu). Needs status solved or\n"
           "solved_inaccurate (else UsageError). Check adjoint_residual before trusting it.")
      .def_property_readonly("settings", &PyQpSolver::settings, "the settings as a dict")
      .def("set_settings", &PyQpSolver::set_settings, "changes settings (keyword arguments) without a new setup")
      .def("problem", &PyQpSolver::problem, "the problem of the last setup()/update() as a dict (copies), or None");
}

}  // namespace lcprelax::python
