// The 1-D frictional block: LCP and convex model of one step (models/block1d.hpp).
#include <lcprelax/models/block1d.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace lcprelax {

void Block1d::validate() const {
  if (!std::isfinite(mass) || !(mass > 0.0)) throw InputError("block: mass must be positive and finite");
  if (!std::isfinite(mg) || !(mg > 0.0)) throw InputError("block: mg (weight impulse) must be positive and finite");
  if (!std::isfinite(mu) || !(mu >= 0.0)) throw InputError("block: mu must be finite and ≥ 0");
}

namespace {

void check_state(double v, double u) {
  if (!std::isfinite(v)) throw InputError("block: velocity v is not finite");
  if (!std::isfinite(u)) throw InputError("block: push u is not finite");
}

}  // namespace

Block1dLcp block1d_lcp(const Block1d& b, double v, double u) {
  b.validate();
  check_state(v, u);
  const double w = 1.0 / b.mass, vs = v + u * w;
  Block1dLcp lcp;
  const Triplet t[] = {{0, 0, w}, {0, 1, -w}, {0, 2, 1.0}, {1, 0, -w}, {1, 1, w}, {1, 2, 1.0}, {2, 0, -1.0}, {2, 1, -1.0}};
  lcp.M.resize(3, 3);
  lcp.M.setFromTriplets(std::begin(t), std::end(t));
  lcp.M.makeCompressed();
  lcp.q = Vector(3);
  lcp.q << vs, -vs, b.mu * b.mg;
  return lcp;
}

QpProblem block1d_convex_qp(const Block1d& b, double v, double u, double rho) {
  b.validate();
  check_state(v, u);
  if (!std::isfinite(rho) || rho < 0.0) throw InputError("block: the convex model's rho must be finite and ≥ 0");
  QpProblem p(1);
  p.P.resize(1, 1);
  p.P.insert(0, 0) = (1.0 + rho) / b.mass;
  p.P.makeCompressed();
  p.q(0) = v + u / b.mass;
  p.xl = Vector::Constant(1, -b.mu * b.mg);
  p.xu = Vector::Constant(1, b.mu * b.mg);
  return p;
}

double block1d_exact_impulse(const Block1d& b, double v, double u) {
  b.validate();
  check_state(v, u);
  const double bound = b.mu * b.mg;
  return std::clamp(-b.mass * (v + u / b.mass), -bound, bound);
}

double block1d_next_velocity(const Block1d& b, double v, double u, double lambda) { return v + (u + lambda) / b.mass; }

Block1dStep block1d_step_lcp(const Block1d& b, double v, double u, const LemkeSettings& settings) {
  const Block1dLcp lcp = block1d_lcp(b, v, u);
  LemkeSolver solver(settings);
  solver.setup(lcp.M, lcp.q);
  const LcpResult& r = solver.solve();
  Block1dStep s;
  s.work = r.info.pivots;
  if (!has_solution(r.info.status)) {
    s.status = ContactStatus::failed;
    s.message = std::string("Lemke: ") + to_string(r.info.status) + " (" + r.info.message + ")";
    return s;
  }
  s.status = ContactStatus::solved;
  s.z = r.z;
  s.z_basic = r.z_basic;
  s.lambda = r.z(0) - r.z(1);
  s.v_next = block1d_next_velocity(b, v, u, s.lambda);
  return s;
}

Block1dStep block1d_step_convex(const Block1d& b, double v, double u, double rho, const QpSettings& settings) {
  const QpProblem p = block1d_convex_qp(b, v, u, rho);
  QpSolver solver(settings);
  solver.setup(p);
  const QpResult& r = solver.solve();
  Block1dStep s;
  s.work = r.info.iterations;
  if (!has_solution(r.info.status)) {
    s.status = ContactStatus::failed;
    s.message = std::string("QP: ") + to_string(r.info.status) + " (" + r.info.message + ")";
    return s;
  }
  s.status = r.info.status == QpStatus::solved ? ContactStatus::solved : ContactStatus::solved_inaccurate;
  s.z = r.x;
  s.lambda = r.x(0);
  s.v_next = block1d_next_velocity(b, v, u, s.lambda);
  return s;
}

}  // namespace lcprelax
