// Binds the 1-D frictional block's learning losses (learn/block_losses.hpp) as
// lcprelax.BlockObjective, and its data generator (learn/block_dataset.hpp) as
// lcprelax.generate_block_data.
//
// The block (models/block1d.hpp; Parmar, Halm & Posa, IROS 2021), one transition per sample:
//   v       velocity before the step (m/s), u push impulse during the step (N·s),
//   v_next  observed velocity after it (m/s); mass m (kg) and mg = m·g·Δt (N·s) are the
//   dataset's. Prediction v⁺ = v + (u + λ)/m with the friction impulse |λ| ≤ μ·mg.
// Methods: 'hard' ℓ = (v⁺ − v̄)² with λ from Lemke (gradient exactly 0 in μ where the
// prediction sticks); 'relaxed' the relaxed-LCP cost (learn/relaxed_lcp.hpp; its weights
// through relaxed=dict(a1=..)); 'convex' ℓ = (v⁺ − v̄)² with λ from the convex model
// (penalty convex_rho). θ = (mu) [+ mass (kg)] [+ mg (N·s)] with learn_mass / learn_mg;
// otherwise the dataset's mass and mg are used. Conventions of evaluate(): objective.hpp.
#include "objective.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/learn/block_losses.hpp>

#include <cmath>
#include <cstdint>

namespace lcprelax::python {
namespace {

class PyBlockObjective : public PyObjective {
 public:
  PyBlockObjective(const std::string& method, const py::object& v, const py::object& u, const py::object& v_next,
                   double mass, double mg, bool learn_mass, bool learn_mg, int threads,
                   const learn::BlockLossSettings& settings) {
    const Vector vv = to_vector(v, "v");
    const Index n = vv.size();
    const Vector uu = to_vector(u, "u", n, "length of v");
    const Vector vn = to_vector(v_next, "v_next", n, "length of v");
    if (n == 0) throw InputError("the block dataset is empty (v has length 0)");
    if (!(std::isfinite(mass) && mass > 0)) throw InputError("mass: must be finite and > 0");
    if (!(std::isfinite(mg) && mg > 0)) throw InputError("mg: must be finite and > 0");
    learn::BlockDataset data;
    data.mass = mass, data.mg = mg;
    for (Index i = 0; i < n; ++i) {
      if (!std::isfinite(vv(i)) || !std::isfinite(uu(i)) || !std::isfinite(vn(i)))
        throw InputError("sample " + std::to_string(i) + ": v, u and v_next must be finite");
      data.samples.push_back({vv(i), uu(i), vn(i)});
    }
    const learn::BlockMethod m = learn::parse_block_method(method);
    // θ: exactly the learned parameters (read_theta takes mass and mg from the data otherwise).
    learn::ParameterSet base;
    base.add(learn::Parameter{"mu", 1.0, learn::Transform::log, 1e-8, 1e8, true});
    if (learn_mass) base.add(learn::Parameter{"mass", mass, learn::Transform::log, 1e-8, 1e8, true});
    if (learn_mg) base.add(learn::Parameter{"mg", mg, learn::Transform::log, 1e-8, 1e8, true});
    std::vector<Index> learned;
    for (Index k = 0; k < base.size(); ++k) learned.push_back(k);
    init(method, base, learned, threads, nullptr, learn::make_block_objective(m, data, settings));
  }
};

py::dict block_data_dict(const learn::BlockDataset& d) {
  Vector v(d.size()), u(d.size()), vn(d.size());
  for (Index i = 0; i < d.size(); ++i) {
    const auto& s = d.samples[static_cast<std::size_t>(i)];
    v(i) = s.v, u(i) = s.u, vn(i) = s.v_next;
  }
  py::dict out;
  out["v"] = to_numpy(v), out["u"] = to_numpy(u), out["v_next"] = to_numpy(vn);
  out["mass"] = d.mass, out["mg"] = d.mg;
  return out;
}

}  // namespace

void bind_learning(py::module_& m) {
  bind_objective_base(m);
  py::class_<PyBlockObjective, PyObjective>(
      m, "BlockObjective",
      "Loss of the 1-D frictional block's transitions and its gradient in theta = (mu[, mass][, mg])\n"
      "(learn/block_losses.hpp; docs/python.md 'Learning').")
      .def(py::init([](const std::string& method, const py::object& v, const py::object& u, const py::object& v_next,
                       double mass, double mg, bool learn_mass, bool learn_mg, int threads, double convex_rho,
                       bool warm_start_lemke, bool warm_start_qp, const py::object& relaxed, const py::object& qp,
                       const py::object& lemke) {
             learn::BlockLossSettings s;
             s.convex_rho = convex_rho;
             s.warm_start_lemke = warm_start_lemke;
             s.warm_start_qp = warm_start_qp;
             apply_settings_dict(s.relaxed, relaxed_loss_fields(), relaxed, "relaxed");
             apply_settings_dict(s.qp, qp_fields(), qp, "qp");
             apply_settings_dict(s.lemke, lemke_fields(), lemke, "lemke");
             return std::make_unique<PyBlockObjective>(method, v, u, v_next, mass, mg, learn_mass, learn_mg, threads, s);
           }),
           py::arg("method"), py::arg("v"), py::arg("u"), py::arg("v_next"), py::kw_only(), py::arg("mass") = 1.0,
           py::arg("mg") = 1.0, py::arg("learn_mass") = false, py::arg("learn_mg") = false, py::arg("threads") = 0,
           py::arg("convex_rho") = 0.0, py::arg("warm_start_lemke") = true, py::arg("warm_start_qp") = false,
           py::arg("relaxed") = py::none(), py::arg("qp") = py::none(), py::arg("lemke") = py::none(),
           "BlockObjective(method, v, u, v_next, *, mass=1, mg=1, learn_mass=False, learn_mg=False,\n"
           "threads=0, convex_rho=0, relaxed=None, qp=None, lemke=None): method 'hard' | 'relaxed' |\n"
           "'convex'; v, v_next (m/s) and u (N*s) 1-D arrays of one length; mass (kg), mg (N*s).\n"
           "relaxed: dict of the relaxed loss's weights (a1..a5, soft_nonnegativity, soft_lambdas,\n"
           "l1_softness, regularization, max_dissipation); qp / lemke: solver settings dicts.");

  m.def(
      "generate_block_data",
      [](double true_mu, double mass, double mg, long long samples, long long seed, double noise,
         const std::string& noise_kind, double stick_max, double slip_min, double slip_max) {
        if (seed < 0) throw InputError("seed: must be >= 0");
        if (noise_kind != "relative" && noise_kind != "absolute")
          throw InputError("noise_kind = '" + noise_kind + "' is not one of: relative, absolute");
        learn::BlockDataSettings g;
        g.truth = Block1d{mass, mg, true_mu};
        g.samples = static_cast<Index>(samples);
        if (samples < 1 || samples > 10'000'000) throw InputError("samples: must be in [1, 10000000]");
        g.seed = static_cast<std::uint64_t>(seed);
        g.noise = noise;
        g.noise_kind = noise_kind == "absolute" ? learn::NoiseKind::absolute : learn::NoiseKind::relative;
        g.stick_max = stick_max, g.slip_min = slip_min, g.slip_max = slip_max;
        learn::BlockDataset d;
        {
          py::gil_scoped_release nogil;
          d = learn::generate_block_dataset(g);
        }
        return block_data_dict(d);
      },
      py::arg("true_mu") = 0.1, py::kw_only(), py::arg("mass") = 1.0, py::arg("mg") = 1.0, py::arg("samples") = 200,
      py::arg("seed") = 1, py::arg("noise") = 0.0, py::arg("noise_kind") = "relative", py::arg("stick_max") = 0.9,
      py::arg("slip_min") = 1.1, py::arg("slip_max") = 9.0,
      "Transitions of a true block (learn/block_dataset.hpp), as `lcprelax learn block` generates\n"
      "them: half stick, half slip. Returns {'v', 'u', 'v_next', 'mass', 'mg'}, so that\n"
      "BlockObjective(method, **data) builds the objective.");
}

}  // namespace lcprelax::python
