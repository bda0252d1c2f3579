// Binds lcprelax.RelaxedLcpBatch: the relaxed (soft-LCP) loss of Parmar, Halm & Posa (IROS
// 2021) for B samples with one sparsity pattern of M (n×n), P (k×n) and optionally E (r×n),
// evaluated in parallel with OpenMP, each with its gradient by the envelope theorem
// (learn/relaxed_lcp.hpp states the QP, its weights a1..a5 and the gradient formulas).
// The engine of lcprelax.torch.RelaxedLcpLoss.
//
// Per sample: c = min a1‖Pλ + p − x̄‖² + a2 λᵀ(Mλ + q) + slack terms [+ a5‖Eλ − e‖²] +
// (ε/2)‖x‖² over the relaxed constraints; the prediction x̂ = Pλ + p, the target x̄.
// Matrix VALUES are arrays over the stored entries in the canonical CSC order of
// `M_pattern`, `P_pattern`, `E_pattern` (None keeps the pattern's values); q and target are
// required, p and e default to 0. Batched arguments: batch.hpp. Each sample keeps its own
// RelaxedLcpSolver workspace (the analysis is reused across calls; results are equal bit
// for bit to a fresh workspace's, relaxed_lcp.hpp).
// Settings: keyword arguments named as RelaxedLcpSettings' fields (the table of
// objective.hpp: max_dissipation as 'none' | 'qp' | 'ext', nonconvex as 'report' | 'shift');
// QP settings as a dict `qp`.
#include "batch.hpp"
#include "objective.hpp"

#include <lcprelax/learn/relaxed_lcp.hpp>

#include <memory>
#include <mutex>

namespace lcprelax::python {
namespace {

using learn::RelaxedLcpData;
using learn::RelaxedLcpSettings;
using learn::RelaxedLcpSolver;

struct PyRelaxedBatchResult {
  py::array_t<double> cost, lambda;
  py::array_t<bool> solved;
  std::vector<std::string> status;
  py::dict gradient;  ///< dl/d(M, q, P, p, target, E, e) per sample, NaN rows where not solved
};

class PyRelaxedLcpBatch {
 public:
  PyRelaxedLcpBatch(const py::object& M, const py::object& P, const py::object& E, int threads,
                    const RelaxedLcpSettings& s, const QpSettings& qp)
      : settings_(s), qp_(qp), threads_(threads) {
    RelaxedLcpSolver check(settings_, qp_);  // throws InputError on invalid settings
    pattern_.M = to_sparse(M, "M");
    pattern_.P = to_sparse(P, "P");
    const Index n = static_cast<Index>(pattern_.M.cols());
    pattern_.E = E.is_none() ? SparseMatrix(0, n) : to_sparse(E, "E");
    pattern_.q = Vector::Zero(n);
    pattern_.p = Vector::Zero(pattern_.P.rows());
    pattern_.target = Vector::Zero(pattern_.P.rows());
    pattern_.e = Vector::Zero(pattern_.E.rows());
    pattern_.validate(settings_);
  }

  PyRelaxedBatchResult evaluate(const py::object& q, const py::object& target, const py::object& M,
                                const py::object& P, const py::object& p, const py::object& E, const py::object& e) {
    if (q.is_none() || target.is_none()) throw py::type_error("RelaxedLcpBatch.evaluate(): q and target are required");
    const Index n = pattern_.q.size(), k = pattern_.p.size(), r = pattern_.e.size();
    const Index nM = pattern_.M.nonZeros(), nP = pattern_.P.nonZeros(), nE = pattern_.E.nonZeros();
    BatchArgs args;
    const BatchRows rq = args.add(q, "q", n), rt = args.add(target, "target", k), rM = args.add(M, "M", nM);
    const BatchRows rP = args.add(P, "P", nP), rp = args.add(p, "p", k), rE = args.add(E, "E", nE), re = args.add(e, "e", r);
    const Index B = args.batch_size();
    PyRelaxedBatchResult out;
    out.cost = py::array_t<double>(B), out.lambda = batch_array(B, n), out.solved = py::array_t<bool>(B);
    py::array_t<double> dM = batch_array(B, nM), dq = batch_array(B, n), dP = batch_array(B, nP), dp = batch_array(B, k);
    py::array_t<double> dt = batch_array(B, k), dE = batch_array(B, nE), de = batch_array(B, r);
    double *pc = out.cost.mutable_data(), *pl = out.lambda.mutable_data();
    bool* ps = out.solved.mutable_data();
    double *pM = dM.mutable_data(), *pq = dq.mutable_data(), *pP = dP.mutable_data(), *pp = dp.mutable_data();
    double *pt = dt.mutable_data(), *pE = dE.mutable_data(), *pe = de.mutable_data();
    std::vector<learn::RelaxedLcpStatus> status(static_cast<std::size_t>(B));
    Busy busy(mutex_, "RelaxedLcpBatch");
    if (static_cast<Index>(workspaces_.size()) != B) {
      data_.assign(static_cast<std::size_t>(B), pattern_);
      workspaces_.clear();
      for (Index s = 0; s < B; ++s) workspaces_.push_back(std::make_unique<RelaxedLcpSolver>(settings_, qp_));
    }
    {
      py::gil_scoped_release nogil;
      for_each_sample(B, threads_, [&](Index s) {
        RelaxedLcpData& d = data_[static_cast<std::size_t>(s)];
        auto fill = [s](const BatchRows& rows, double* dst, Index len) {
          if (rows.given()) copy_row(rows.row(s), len, dst);
        };
        fill(rq, d.q.data(), n), fill(rt, d.target.data(), k), fill(rM, d.M.valuePtr(), nM);
        fill(rP, d.P.valuePtr(), nP), fill(rp, d.p.data(), k), fill(rE, d.E.valuePtr(), nE), fill(re, d.e.data(), r);
        const learn::RelaxedLcpResult& res = workspaces_[static_cast<std::size_t>(s)]->solve(d, true);
        status[static_cast<std::size_t>(s)] = res.status;
        const bool ok = res.status == learn::RelaxedLcpStatus::solved;
        ps[s] = ok;
        pc[s] = res.cost;
        copy_or_nan(res.lambda, n, pl + s * n);
        if (!ok) return;  // gradient rows stay NaN below
        const learn::RelaxedLcpGradient& g = res.gradient;
        if (g.dM.nonZeros() != nM || g.dP.nonZeros() != nP)
          throw std::runtime_error("RelaxedLcpBatch: a gradient left its matrix's sparsity pattern");
        copy_row(g.dM.valuePtr(), nM, pM + s * nM), copy_or_nan(g.dq, n, pq + s * n);
        copy_row(g.dP.valuePtr(), nP, pP + s * nP), copy_or_nan(g.dp, k, pp + s * k);
        copy_or_nan(g.dtarget, k, pt + s * k);
        if (g.dE.nonZeros() == nE) copy_row(g.dE.valuePtr(), nE, pE + s * nE);
        if (g.de.size() == r) copy_or_nan(g.de, r, pe + s * r);
      });
    }
    for (Index s = 0; s < B; ++s) {
      out.status.push_back(learn::to_string(status[static_cast<std::size_t>(s)]));
      if (ps[s]) continue;
      for (auto* a : {&dM, &dq, &dP, &dp, &dt, &dE, &de}) {
        const Index w = static_cast<Index>(a->shape(1));
        std::fill(a->mutable_data() + s * w, a->mutable_data() + (s + 1) * w, std::numeric_limits<double>::quiet_NaN());
      }
    }
    out.gradient["M"] = dM, out.gradient["q"] = dq, out.gradient["P"] = dP, out.gradient["p"] = dp;
    out.gradient["target"] = dt, out.gradient["E"] = dE, out.gradient["e"] = de;
    return out;
  }

  py::dict settings() const { return settings_dict(settings_, relaxed_loss_fields()); }
  const RelaxedLcpData& pattern() const { return pattern_; }

 private:
  RelaxedLcpSettings settings_;
  QpSettings qp_;
  int threads_;
  RelaxedLcpData pattern_;
  std::vector<RelaxedLcpData> data_;
  std::vector<std::unique_ptr<RelaxedLcpSolver>> workspaces_;
  std::mutex mutex_;
};

}  // namespace

void bind_relaxed_lcp(py::module_& m) {
  py::class_<PyRelaxedBatchResult>(m, "RelaxedLcpBatchResult", "Result of RelaxedLcpBatch.evaluate()")
      .def_readonly("cost", &PyRelaxedBatchResult::cost, "the relaxed loss c per sample (NaN where not solved)")
      .def_readonly("lam", &PyRelaxedBatchResult::lambda, "the relaxed QP's lambda per sample (B, n)")
      .def_readonly("solved", &PyRelaxedBatchResult::solved)
      .def_readonly("status", &PyRelaxedBatchResult::status, "'solved', 'nonconvex' or 'qp_failed' per sample")
      .def_readonly("gradient", &PyRelaxedBatchResult::gradient,
                    "dict of dc/d(M, q, P, p, target, E, e), one row per sample (matrices on their\n"
                    "pattern's entries); NaN rows where the sample is not solved");

  py::class_<PyRelaxedLcpBatch>(m, "RelaxedLcpBatch",
                                "The relaxed LCP loss (Parmar, Halm & Posa 2021) of B samples with gradients,\n"
                                "in parallel (OpenMP). See learn/relaxed_lcp.hpp and docs/python.md.")
      .def(py::init([](const py::object& M, const py::object& P, const py::object& E, int threads,
                       const py::object& qp, const py::kwargs& kw) {
             RelaxedLcpSettings s;
             apply_settings(s, relaxed_loss_fields(), kw, "RelaxedLcpBatch()");
             QpSettings q;
             if (!qp.is_none()) apply_settings(q, qp_fields(), py::kwargs(py::dict(qp)), "RelaxedLcpBatch(qp=...)");
             return std::make_unique<PyRelaxedLcpBatch>(M, P, E, threads, s, q);
           }),
           py::arg("M"), py::arg("P"), py::arg("E") = py::none(), py::kw_only(), py::arg("threads") = 0,
           py::arg("qp") = py::none(),
           "RelaxedLcpBatch(M, P, E=None, *, threads=0, qp=None, **settings): patterns of M (n x n),\n"
           "P (k x n), E (r x n; with max_dissipation 'qp' or 'ext'); settings a1..a5,\n"
           "soft_nonnegativity, soft_lambdas, l1_softness, max_dissipation, regularization, nonconvex;\n"
           "qp: a dict of QpSettings keywords")
      .def("evaluate", &PyRelaxedLcpBatch::evaluate, py::arg("q"), py::arg("target"), py::kw_only(),
           py::arg("M") = py::none(), py::arg("P") = py::none(), py::arg("p") = py::none(), py::arg("E") = py::none(),
           py::arg("e") = py::none(),
           "Loss and gradient of every sample; each argument (k,) shared or (B, k) per sample")
      .def_property_readonly("settings", &PyRelaxedLcpBatch::settings)
      .def_property_readonly("M_pattern", [](const PyRelaxedLcpBatch& b) { return to_scipy(b.pattern().M); })
      .def_property_readonly("P_pattern", [](const PyRelaxedLcpBatch& b) { return to_scipy(b.pattern().P); })
      .def_property_readonly("E_pattern", [](const PyRelaxedLcpBatch& b) { return to_scipy(b.pattern().E); });
}

}  // namespace lcprelax::python
