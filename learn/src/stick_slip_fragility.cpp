// Stick/slip fragility: derived and measured thresholds (stick_slip_fragility.hpp;
// derivation in docs/structure.md).
#include <lcprelax/learn/stick_slip_fragility.hpp>
#include <lcprelax/core/math_constants.hpp>

#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/learn/polygon_lcp.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::learn {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool has_normal(const StickCase& c) { return c.row_n >= 0; }

// The stick system K u = −b of the case: u = (λn, λt) with a normal row, else (λt).
struct StickSystem {
  DenseMatrix K;
  Vector b;
  Index t = 0;  // index of λt in u
};

StickSystem stick_system(const StickCase& c) {
  StickSystem s;
  if (has_normal(c)) {
    s.K.resize(2, 2);
    s.K << c.M(c.row_n, c.row_n), c.M(c.row_n, c.row_tp), c.M(c.row_tp, c.row_n), c.M(c.row_tp, c.row_tp);
    s.b.resize(2);
    s.b << c.q(c.row_n), c.q(c.row_tp);
    s.t = 1;
  } else {
    s.K = DenseMatrix::Constant(1, 1, c.M(c.row_tp, c.row_tp));
    s.b = Vector::Constant(1, c.q(c.row_tp));
  }
  return s;
}

// Friction capacity μλn + q_γ (polygon: q_γ = 0) or q_γ (block) for a given u.
double capacity(const StickCase& c, const Vector& u) {
  return c.q(c.row_gamma) + (has_normal(c) ? c.M(c.row_gamma, c.row_n) * u(0) : 0.0);
}

Index active_row(const StickCase& c, double lambda_t) { return lambda_t > 0 ? c.row_tp : c.row_tm; }
Index inactive_row(const StickCase& c, double lambda_t) { return lambda_t > 0 ? c.row_tm : c.row_tp; }

// First roots on each side of slack(ε) = cap⁰ + ε·dcap − |λt⁰ + ε·dλt| along a linear
// stick path. With `one_branch`, only roots where λt keeps its sign (a perturbation of one
// friction row: once λt changes sign, its other row, unperturbed, holds v_t and the
// contact coasts without friction instead of sliding).
FragilityThreshold linear_path_roots(double cap0, double dcap, double lt0, double dlt, bool one_branch) {
  FragilityThreshold out{-kInf, kInf, kNaN};
  for (double s : {1.0, -1.0}) {
    if (one_branch && s * lt0 <= 0) continue;
    const double den = dcap - s * dlt;
    if (den == 0.0) continue;
    const double eps = (s * lt0 - cap0) / den;
    if (s * (lt0 + eps * dlt) < 0) continue;  // the root lies on the other branch
    if (eps > 0) out.positive = std::min(out.positive, eps);
    if (eps < 0) out.negative = std::max(out.negative, eps);
  }
  return out;
}

double matrix_scale(const StickCase& c) { return std::max(1e-300, c.M.cwiseAbs().maxCoeff()); }

bool is_matrix_perturbation(FragilityPerturbation p) {
  return p == FragilityPerturbation::M_pair_inactive || p == FragilityPerturbation::M_cone_active ||
         p == FragilityPerturbation::M_gamma_active;
}

}  // namespace

const char* to_string(FragilityPerturbation p) {
  switch (p) {
    case FragilityPerturbation::q_pair: return "q_pair";
    case FragilityPerturbation::q_active: return "q_active";
    case FragilityPerturbation::q_inactive: return "q_inactive";
    case FragilityPerturbation::q_cone: return "q_cone";
    case FragilityPerturbation::q_normal: return "q_normal";
    case FragilityPerturbation::M_pair_inactive: return "M_pair_inactive";
    case FragilityPerturbation::M_cone_active: return "M_cone_active";
    case FragilityPerturbation::M_gamma_active: return "M_gamma_active";
  }
  return "unknown";
}

std::vector<FragilityPerturbation> fragility_perturbations(const StickCase& c) {
  using P = FragilityPerturbation;
  std::vector<P> out{P::q_pair, P::q_active, P::q_inactive, P::q_cone};
  if (has_normal(c)) out.push_back(P::q_normal);
  out.insert(out.end(), {P::M_pair_inactive, P::M_cone_active, P::M_gamma_active});
  return out;
}

void StickCase::validate() const {
  const Index n = static_cast<Index>(q.size());
  if (M.rows() != n || M.cols() != n) throw InputError("StickCase: M must be n×n with n = q.size()");
  for (Index r : {row_tp, row_tm, row_gamma})
    if (r < 0 || r >= n) throw InputError("StickCase: row index out of range");
  if (row_n >= n) throw InputError("StickCase: row_n out of range");
  const StickSolution s = stick_solution(*this);
  if (!(s.slack > 0) || s.lambda_t == 0.0 || (row_n >= 0 && !(s.lambda_n > 0)))
    throw InputError("StickCase " + name + ": the stick solution does not stick strictly (slack " +
                     std::to_string(s.slack) + ")");
}

StickCase block_stick_case(const Block1d& block, double v_star) {
  const Block1dLcp lcp = block1d_lcp(block, v_star, 0.0);
  StickCase c;
  c.name = "block m=" + std::to_string(block.mass) + " mu=" + std::to_string(block.mu) + " v*=" + std::to_string(v_star);
  c.M = DenseMatrix(lcp.M);
  c.q = lcp.q;
  c.row_n = -1;
  c.row_tp = 0, c.row_tm = 1, c.row_gamma = 2;
  c.scale = std::max(1e-300, c.q.cwiseAbs().maxCoeff());
  return c;
}

StickCase polygon_stick_case(const PolygonContactData& d, double dt, const std::string& name) {
  if (d.num_contacts() != 1) throw InputError("polygon_stick_case: exactly one contact expected");
  PolygonLcp lcp;
  polygon_lcp(d, dt, lcp);
  StickCase c;
  c.name = name;
  c.M = lcp.M;
  c.q = lcp.q;
  c.row_n = 0, c.row_tp = 1, c.row_tm = 2, c.row_gamma = 3;
  c.scale = std::max(1e-300, c.q.cwiseAbs().maxCoeff());
  return c;
}

PolygonContactData square_on_corner(double tilt, const Vector& v, double mu, double dt) {
  if (!(tilt > 0 && tilt < 1.5707963267948966)) throw InputError("square_on_corner: tilt must be in (0, π/2)");
  if (v.size() != 3) throw InputError("square_on_corner: v must have 3 entries");
  PolygonContactData d;
  d.set_zero(1);
  const double c = std::cos(tilt), s = std::sin(tilt);
  const double rx = -0.5 * c + 0.5 * s, ry = -0.5 * s - 0.5 * c;  // R·(−½, −½), φ = 0
  const double nx = 0.0, ny = 1.0, tx = -ny, ty = nx;              // t = (−n_y, n_x)
  d.Jn.row(0) << nx, ny, rx * ny - ry * nx;
  d.Jt.row(0) << tx, ty, rx * ty - ry * tx;
  d.phi(0) = 0.0;
  d.mu(0) = mu;
  d.minv << 1.0, 1.0, 6.0;  // m = 1 kg, I = m(1² + 1²)/12 = 1/6 kg·m²
  d.v_star = v + dt * Vector((Vector(3) << 0.0, -9.81, 0.0).finished());
  return d;
}

PolygonContactData square_flat(const Vector& v, double mu, double dt) {
  if (v.size() != 3) throw InputError("square_flat: v must have 3 entries");
  PolygonContactData d;
  d.set_zero(2);
  for (Index i = 0; i < 2; ++i) {
    const double rx = i == 0 ? -0.5 : 0.5, ry = -0.5;  // n = (0, 1), t = (−1, 0)
    d.Jn.row(i) << 0.0, 1.0, rx;
    d.Jt.row(i) << -1.0, 0.0, ry;
    d.mu(i) = mu;
  }
  d.minv << 1.0, 1.0, 6.0;
  d.v_star = v + dt * Vector((Vector(3) << 0.0, -9.81, 0.0).finished());
  return d;
}

Vector polygon_sliding_speeds(const PolygonContactData& d, double dt, Index row, double eps,
                              const LemkeSettings& settings) {
  PolygonLcp lcp;
  polygon_lcp(d, dt, lcp);
  const Index nc = d.num_contacts();
  if (row < 0 || row >= 4 * nc) throw InputError("polygon_sliding_speeds: row out of range");
  lcp.q(row) += eps;
  LemkeSolver solver(settings);
  solver.setup(full_pattern(lcp.M), lcp.q);
  const LcpResult& r = solver.solve();
  if (!has_solution(r.info.status)) return Vector::Constant(nc, kNaN);
  return r.z.tail(nc);
}

StickSolution stick_solution(const StickCase& c) {
  const StickSystem s = stick_system(c);
  const Vector u = -s.K.fullPivLu().solve(s.b);
  StickSolution out;
  out.lambda_n = has_normal(c) ? u(0) : kNaN;
  out.lambda_t = u(s.t);
  out.slack = capacity(c, u) - std::abs(out.lambda_t);
  return out;
}

void perturb(const StickCase& c, FragilityPerturbation p, double eps, DenseMatrix& M, Vector& q) {
  M = c.M;
  q = c.q;
  const double lt = stick_solution(c).lambda_t;
  const Index act = active_row(c, lt), inact = inactive_row(c, lt);
  using P = FragilityPerturbation;
  switch (p) {
    case P::q_pair: q(c.row_tp) += eps, q(c.row_tm) -= eps; break;
    case P::q_active: q(act) += eps; break;
    case P::q_inactive: q(inact) += eps; break;
    case P::q_cone: q(c.row_gamma) += eps; break;
    case P::q_normal:
      if (!has_normal(c)) throw InputError("perturb: q_normal needs a normal row");
      q(c.row_n) += eps;
      break;
    case P::M_pair_inactive: M(inact, has_normal(c) ? c.row_n : act) += eps; break;
    case P::M_cone_active: M(c.row_gamma, act) += eps; break;
    case P::M_gamma_active: M(act, c.row_gamma) += eps; break;
  }
}

FragilityThreshold derived_threshold(const StickCase& c, FragilityPerturbation p) {
  const StickSystem sys = stick_system(c);
  const StickSolution st = stick_solution(c);
  const Vector u0 = -sys.K.fullPivLu().solve(sys.b);
  const double cap0 = capacity(c, u0), lt0 = st.lambda_t, sigma = lt0 > 0 ? 1.0 : -1.0;
  const double mu = has_normal(c) ? c.M(c.row_gamma, c.row_n) : 0.0;
  // Stick path u(ε) = u⁰ + ε·du when the right-hand side moves by ε·e (K u = −b − ε e).
  auto path = [&](Index k, double sign, bool one_branch) {
    const Vector du = -sign * sys.K.fullPivLu().solve(Vector::Unit(sys.K.rows(), k));
    const double dcap = has_normal(c) ? mu * du(0) : 0.0;
    return linear_path_roots(cap0, dcap, lt0, du(sys.t), one_branch);
  };
  using P = FragilityPerturbation;
  FragilityThreshold zero_side{-0.0, kInf, -0.5};  // slides for every ε < 0 (σ = ε < 0)
  switch (p) {
    case P::q_pair: return path(sys.t, 1.0, false);
    case P::q_active: {
      // The active row's equation is σ·(K_t u + q_t) + ε = 0, i.e. b_t moves by σ·ε.
      FragilityThreshold t = path(sys.t, sigma, true);
      t.negative = -0.0, t.slope = -0.5;
      return t;
    }
    case P::q_inactive: return zero_side;
    case P::q_cone: return {-st.slack, kInf, kNaN};
    case P::q_normal: {
      // A root where λn(ε) reaches 0 too is a lift-off (λ → 0 together, e.g. q_t = 0): the
      // contact separates with v_t⁺ = q_t = 0 and never slides.
      FragilityThreshold t = path(0, 1.0, false);
      const double dln = -sys.K.fullPivLu().solve(Vector::Unit(sys.K.rows(), 0))(0);
      for (double* e : {&t.negative, &t.positive})
        if (std::isfinite(*e) && u0(0) + *e * dln <= 1e-9 * u0(0)) *e = *e > 0 ? kInf : -kInf;
      return t;
    }
    case P::M_pair_inactive:
      // σ = ε·z_c with z_c just past 0: λn (continuous) with a normal row; for the block the
      // active β of the sliding split β± = (cap ± |λt|)/2 (the stick split is not unique).
      zero_side.slope = -0.5 * (has_normal(c) ? st.lambda_n : 0.5 * (cap0 + std::abs(lt0)));
      return zero_side;
    case P::M_cone_active: return {-st.slack / std::abs(lt0), kInf, kNaN};
    case P::M_gamma_active: return {-kInf, kInf, kNaN};
  }
  return {kNaN, kNaN, kNaN};
}

double measured_sliding_speed(const StickCase& c, FragilityPerturbation p, double eps, const LemkeSettings& settings) {
  DenseMatrix M;
  Vector q;
  perturb(c, p, eps, M, q);
  LemkeSolver solver(settings);
  solver.setup(full_pattern(M), q);
  const LcpResult& r = solver.solve();
  if (!has_solution(r.info.status)) return kNaN;
  return r.z(c.row_gamma);
}

FragilityMeasurement measured_threshold(const StickCase& c, FragilityPerturbation p, const LemkeSettings& settings) {
  FragilityMeasurement out;
  const double scale = is_matrix_perturbation(p) ? matrix_scale(c) : c.scale;
  const double tol = 1e-9 * std::max(1.0, c.q.cwiseAbs().maxCoeff());
  auto slides = [&](double eps) {
    const double g = measured_sliding_speed(c, p, eps, settings);
    ++out.solves;
    if (std::isnan(g)) {  // no solution found: the sticking solution is gone too
      ++out.lemke_failures;
      return true;
    }
    return g > tol;
  };
  auto side = [&](double sign) {
    double last_stick = 0.0;
    for (int k = -48; k <= 4; ++k) {
      const double eps = sign * scale * std::pow(10.0, k / 4.0);
      if (!slides(eps)) {
        last_stick = eps;
        continue;
      }
      double a = last_stick, b = eps;  // a sticks, b slides
      for (int it = 0; it < 200 && std::abs(b - a) > 1e-10 * std::abs(b); ++it) {
        const double mid = 0.5 * (a + b);
        (slides(mid) ? b : a) = mid;
      }
      return b;
    }
    return sign * kInf;
  };
  out.threshold.negative = side(-1.0);
  out.threshold.positive = side(1.0);
  out.threshold.slope = kNaN;
  const FragilityThreshold d = derived_threshold(c, p);
  if (d.negative == 0.0) {  // a zero side: γ/ε just past 0
    const double eps = -1e-6 * scale;
    out.threshold.slope = measured_sliding_speed(c, p, eps, settings) / eps;
  }
  return out;
}

}  // namespace lcprelax::learn
