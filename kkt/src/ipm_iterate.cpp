// Interior-point iterate bookkeeping (see ipm_iterate.hpp for the equations).
#include "ipm_iterate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::detail {
namespace {

void make_side(Side& side, const Vector& bounds, bool upper) {
  side.idx.clear();
  side.upper = upper;
  for (Index i = 0; i < bounds.size(); ++i)
    if (std::isfinite(bounds(i))) side.idx.push_back(i);
  const Index m = side.size();
  side.bound.resize(m);
  for (Index k = 0; k < m; ++k) side.bound(k) = bounds(side.idx[k]);
  side.s = Vector::Ones(m);
  side.z = Vector::Ones(m);
  side.r = Vector::Zero(m);
  side.rc = Vector::Zero(m);
  side.ds = Vector::Zero(m);
  side.dz = Vector::Zero(m);
  side.ds_saved = Vector::Zero(m);
  side.dz_saved = Vector::Zero(m);
  side.rc_saved = Vector::Zero(m);
}

void side_residual(Side& side, const Vector& v) {
  for (Index k = 0; k < side.size(); ++k) {
    const double vk = v(side.idx[k]);
    side.r(k) = side.upper ? vk + side.s(k) - side.bound(k) : vk - side.s(k) - side.bound(k);
  }
}

void add_barrier(const Side& side, Vector& D) {
  for (Index k = 0; k < side.size(); ++k) D(side.idx[k]) += side.z(k) / side.s(k);
}

void add_xi(const Side& side, Vector& xi) {
  for (Index k = 0; k < side.size(); ++k) {
    const double c = side.upper ? -side.rc(k) : side.rc(k);
    xi(side.idx[k]) += (c + side.z(k) * side.r(k)) / side.s(k);
  }
}

void side_step(Side& side, const Vector& dv) {
  for (Index k = 0; k < side.size(); ++k) {
    const double d = dv(side.idx[k]);
    side.ds(k) = side.upper ? -d - side.r(k) : d + side.r(k);
    side.dz(k) = (-side.rc(k) - side.z(k) * side.ds(k)) / side.s(k);
  }
}

double side_max_step(const Side& side) {
  double a = 1.0;
  for (Index k = 0; k < side.size(); ++k) {
    if (side.ds(k) < 0) a = std::min(a, -side.s(k) / side.ds(k));
    if (side.dz(k) < 0) a = std::min(a, -side.z(k) / side.dz(k));
  }
  return a;
}

// Bounds whose larger z/s is below this (scaled problem, unit-order diagonal after Ruiz
// equilibration) keep their rebuilt step: there z/s·dx + ξ is accurate, and moving the
// solve's error into a small z/s side's slack step breaks its primal consistency
// (QRECIPE, QSC205, QSHARE1B, ... stalled when every bound was corrected).
constexpr double kActiveBoundWeight = 1.0;

// Corrects the pair (lower kl, upper ku; −1 where absent) of one quantity so that
// dz_u − dz_l = target: the side with the larger z/s is assigned target minus the other
// side's step (assigned, not corrected by a difference: its rebuilt dz = (−r_c − z·ds)/s
// may be ~1e20 at s ~ 1e-18, and adding a difference of that size loses every digit) and
// its ds follows from its complementarity equation s·dz + z·ds = −r_c.
void match_signed_step(Side& lower, Side& upper, Index kl, Index ku, double target, double min_weight) {
  const double wl = kl >= 0 ? lower.z(kl) / lower.s(kl) : -1.0;
  const double wu = ku >= 0 ? upper.z(ku) / upper.s(ku) : -1.0;
  if (std::max(wl, wu) < min_weight) return;
  if (wu >= wl) {
    upper.dz(ku) = target + (kl >= 0 ? lower.dz(kl) : 0.0);
    upper.ds(ku) = (-upper.rc(ku) - upper.s(ku) * upper.dz(ku)) / upper.z(ku);
  } else {
    lower.dz(kl) = (ku >= 0 ? upper.dz(ku) : 0.0) - target;
    lower.ds(kl) = (-lower.rc(kl) - lower.s(kl) * lower.dz(kl)) / lower.z(kl);
  }
}

}  // namespace

void Iterate::init_sides(const StandardForm& f) {
  make_side(g_lower, f.gl, false);
  make_side(g_upper, f.gu, true);
  make_side(b_lower, f.xl, false);
  make_side(b_upper, f.xu, true);
  g_lower_pos.assign(f.mg, -1);
  g_upper_pos.assign(f.mg, -1);
  for (Index k = 0; k < g_lower.size(); ++k) g_lower_pos[g_lower.idx[k]] = k;
  for (Index k = 0; k < g_upper.size(); ++k) g_upper_pos[g_upper.idx[k]] = k;
  b_lower_pos.assign(f.n, -1);
  b_upper_pos.assign(f.n, -1);
  for (Index k = 0; k < b_lower.size(); ++k) b_lower_pos[b_lower.idx[k]] = k;
  for (Index k = 0; k < b_upper.size(); ++k) b_upper_pos[b_upper.idx[k]] = k;
}

Index Iterate::num_constraints() const {
  return g_lower.size() + g_upper.size() + b_lower.size() + b_upper.size();
}

double Iterate::mu() const {
  const Index N = num_constraints();
  if (N == 0) return 0.0;
  double sum = 0.0;
  for (const Side* s : sides()) sum += s->s.dot(s->z);
  return sum / N;
}

void Iterate::compute_side_residuals(const StandardForm& f) {
  vg.resize(f.mg);
  vg.noalias() = f.G * x;
  side_residual(g_lower, vg);
  side_residual(g_upper, vg);
  side_residual(b_lower, x);
  side_residual(b_upper, x);
}

void Iterate::barrier_terms(Index mg, Index n, Vector& Dg, Vector& Db) const {
  Dg.setZero(mg);
  Db.setZero(n);
  add_barrier(g_lower, Dg);
  add_barrier(g_upper, Dg);
  add_barrier(b_lower, Db);
  add_barrier(b_upper, Db);
}

void Iterate::xi_terms(Index mg, Index n, Vector& xig, Vector& xib) const {
  xig.setZero(mg);
  xib.setZero(n);
  add_xi(g_lower, xig);
  add_xi(g_upper, xig);
  add_xi(b_lower, xib);
  add_xi(b_upper, xib);
}

void Iterate::recover_side_steps(const Vector& dx, const Vector& dvg, const Vector& dzeta, const Vector& dzeta_b) {
  side_step(g_lower, dvg);
  side_step(g_upper, dvg);
  side_step(b_lower, dx);
  side_step(b_upper, dx);
  for (Index i = 0; i < static_cast<Index>(g_lower_pos.size()); ++i)
    match_signed_step(g_lower, g_upper, g_lower_pos[i], g_upper_pos[i], dzeta(i), 0.0);
  if (dzeta_b.size() == 0) return;
  for (Index j = 0; j < static_cast<Index>(b_lower_pos.size()); ++j)
    if (b_lower_pos[j] >= 0 || b_upper_pos[j] >= 0)
      match_signed_step(b_lower, b_upper, b_lower_pos[j], b_upper_pos[j], dzeta_b(j), kActiveBoundWeight);
}

double Iterate::max_step() const {
  double a = 1.0;
  for (const Side* s : sides()) a = std::min(a, side_max_step(*s));
  return a;
}

void Iterate::signed_multipliers(Index mg, Index n, Vector& zg, Vector& zb) const {
  zg.setZero(mg);
  zb.setZero(n);
  for (Index k = 0; k < g_upper.size(); ++k) zg(g_upper.idx[k]) += g_upper.z(k);
  for (Index k = 0; k < g_lower.size(); ++k) zg(g_lower.idx[k]) -= g_lower.z(k);
  for (Index k = 0; k < b_upper.size(); ++k) zb(b_upper.idx[k]) += b_upper.z(k);
  for (Index k = 0; k < b_lower.size(); ++k) zb(b_lower.idx[k]) -= b_lower.z(k);
}

void Iterate::signed_positive_parts(Index mg, Index n, bool use_steps, Vector& zg, Vector& zb) const {
  const auto part = [use_steps](const Side& s, Index k) { return std::max(use_steps ? s.dz(k) : s.z(k), 0.0); };
  zg.setZero(mg);
  zb.setZero(n);
  for (Index k = 0; k < g_upper.size(); ++k) zg(g_upper.idx[k]) += part(g_upper, k);
  for (Index k = 0; k < g_lower.size(); ++k) zg(g_lower.idx[k]) -= part(g_lower, k);
  for (Index k = 0; k < b_upper.size(); ++k) zb(b_upper.idx[k]) += part(b_upper, k);
  for (Index k = 0; k < b_lower.size(); ++k) zb(b_lower.idx[k]) -= part(b_lower, k);
}

}  // namespace lcprelax::detail
