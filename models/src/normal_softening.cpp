// Softening methods of the convex model's normal phase (normal_softening.hpp).
#include <lcprelax/models/normal_softening.hpp>

#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <string>

namespace lcprelax {

NormalSoftening parse_normal_softening(std::string_view text) {
  if (text == "exp_phi" || text == "exp") return NormalSoftening::exp_phi;
  if (text == "linear_penalty" || text == "penalty") return NormalSoftening::linear_penalty;
  if (text == "mujoco_impedance" || text == "impedance") return NormalSoftening::mujoco_impedance;
  throw InputError("unknown softening '" + std::string(text) +
                   "' (expected exp_phi, linear_penalty or mujoco_impedance)");
}

std::string NormalSofteningSettings::validation_error() const {
  auto open_unit = [](double x) { return std::isfinite(x) && x > 0.0 && x < 1.0; };
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!open_unit(d0)) return "d0: must be in (0, 1)";
  if (!open_unit(d_width)) return "d_width: must be in (0, 1)";
  if (!positive(width)) return "width: must be finite and > 0";
  if (!positive(time_constant)) return "time_constant: must be finite and > 0";
  if (!positive(damping_ratio)) return "damping_ratio: must be finite and > 0";
  return {};
}

NormalSofteningTerms normal_softening_terms(const NormalSofteningSettings& o, double rho, double dt,
                                            const Vector& phi, const Vector& vn) {
  const Index nc = static_cast<Index>(phi.size());
  NormalSofteningTerms t;
  t.g.resize(nc);
  t.dg_dphi.resize(nc);
  t.v_ref = Vector::Zero(nc);
  t.dvref_dphi = Vector::Zero(nc);
  t.dvref_dvn = Vector::Zero(nc);
  switch (o.method) {
    case NormalSoftening::exp_phi:
      for (Index i = 0; i < nc; ++i) {
        t.g(i) = 2.0 * rho * std::exp(phi(i));  // the order of the original term: bitwise the same r
        t.dg_dphi(i) = t.g(i);
      }
      break;
    case NormalSoftening::linear_penalty:
      t.g.setConstant(2.0 * rho);
      t.dg_dphi.setZero();
      for (Index i = 0; i < nc; ++i)
        if (phi(i) < 0.0) {
          t.v_ref(i) = -phi(i) / dt;
          t.dvref_dphi(i) = -1.0 / dt;
        }
      break;
    case NormalSoftening::mujoco_impedance: {
      const double tau = o.time_constant, zeta = o.damping_ratio, dmax = o.d_width;
      const double b = 2.0 / (dmax * tau);
      const double k_per_d = 1.0 / (dmax * dmax * tau * tau * zeta * zeta);
      const double dvn = 1.0 - dt * b;
      for (Index i = 0; i < nc; ++i) {
        const double x = std::abs(phi(i)) / o.width;
        const double d = x < 1.0 ? o.d0 + (o.d_width - o.d0) * x : o.d_width;
        // dd/dφ: slope inside the width, with the sign of φ (0 at φ = 0 and beyond width).
        const double dd = x < 1.0 && phi(i) != 0.0 ? (o.d_width - o.d0) / o.width * (phi(i) > 0 ? 1.0 : -1.0) : 0.0;
        t.g(i) = (1.0 - d) / d;
        t.dg_dphi(i) = -dd / (d * d);
        const double k = d * k_per_d;
        t.dvref_dvn(i) = dvn;
        t.v_ref(i) = dvn * vn(i) - dt * k * phi(i);
        t.dvref_dphi(i) = -dt * (dd * k_per_d * phi(i) + k);
      }
      break;
    }
  }
  return t;
}

void add_pair_softness(NormalSofteningTerms& t, const Vector& phi, const Vector& compliance, const Vector& erp,
                       double dt) {
  const Index nc = phi.size();
  t.compliance = compliance.size() == nc ? compliance : Vector::Zero(nc);
  t.dvref_derp = -phi.cwiseMin(0.0) / dt;
  if (erp.size() != nc) return;
  for (Index i = 0; i < nc; ++i) {
    t.v_ref(i) += erp(i) * t.dvref_derp(i);
    if (phi(i) < 0.0) t.dvref_dphi(i) -= erp(i) / dt;
  }
}

NormalSofteningTerms phase1_softening_terms(const NormalSofteningTerms& terms) {
  NormalSofteningTerms t = terms;
  for (Index i = 0; i < t.v_ref.size(); ++i)
    if (!(t.v_ref(i) > 0.0)) {
      // At v_ref = 0 the e-derivative stays: dvref_derp ≥ 0, so for e growing from its
      // bound 0 max(v_ref, 0) = v_ref (header).
      if (t.dvref_derp.size() > 0 && !(t.v_ref(i) == 0.0)) t.dvref_derp(i) = 0.0;
      t.v_ref(i) = 0.0, t.dvref_dphi(i) = 0.0, t.dvref_dvn(i) = 0.0;
    }
  return t;
}

}  // namespace lcprelax
