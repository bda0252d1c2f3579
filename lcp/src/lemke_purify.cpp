// Purification of an approximate LCP solution into a vertex basis (the purified start of
// lemke.hpp, LemkeSolver::warm_start_point).
//
// Tableau w − Mz = q (lemke_basis.hpp): basic columns e_i for w_i, −M_:j for z_j. Given
// z̃ ≥ 0, the crossover starts from the all-w basis with every z̃_j > 0 superbasic (held
// at its value outside the basis), so the basic values are x_B = w̃ = q + Mz̃ and the
// equations hold exactly. The superbasic z_s are then taken one at a time, largest first,
// and driven towards zero: lowering z_s by t moves x_B by t·a with a = B⁻¹(−M_:s). The
// first basic variable that reaches zero leaves and z_s enters the basis with what is left
// of its value; where nothing blocks, z_s ends at zero outside the basis (Megiddo, "On
// finding primal- and dual-optimal bases", ORSA J. Comput. 3, 1991; Bixby & Saltzman,
// "Recovering an optimal LP basis from an interior point solution", Oper. Res. Lett. 15,
// 1994: the crossover of interior-point LP codes). For a point near a solution w̃_s ≈ 0,
// so w_s blocks at once and z_s takes its place (a complementary exchange); when z_s's
// column depends on the z columns already basic (a jammed pile: more loaded contacts
// than degrees of freedom) its own w_s has no pivot left, and lowering z_s shifts its
// load to them until one of them or z_s reaches zero: the dependent columns drop out with
// the point kept, which a repair of the suggested basis (lemke_crash.cpp) cannot do.
// The ratio test is Harris' two-pass test (Harris, "Pivot selection methods of the Devex
// LP code", Math. Prog. 5, 1973) with the complement w_s preferred among the ties; pivots
// below 1e-9·‖a‖∞ are refused, so the basis stays as well conditioned as the point allows.
// Where z_s displaces a member of another pair j (which then has no basic member while
// pair s has both), w_j or z_j is pivoted into w_s's row when its pivot allows and the
// move stays below kDegenerateMove (degenerate for a consistent point: w_s ≈ 0); else
// complementary pivots as in Lemke's method, with z_s in the role of the artificial
// variable, run until a member of pair s leaves (purify_path). Pairs still left with both
// members basic are finally matched with pairs with neither (purify_match_pairs). The basis
// handed to the warm start is {z_j basic} when every pair has one basic member, else the
// fallback; negative basic values that remain (where z̃ was inconsistent) are left to the
// crash path.
// Units: normalized (q/‖q‖∞, lemke_impl.hpp); pivot tolerance `tol`, feasibility
// tolerance kFeasibility (values are O(1) in these units).
#include "lemke_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax {

namespace {
constexpr double kFeasibility = 1e-9;
constexpr double kRelativePivot = 1e-9;
constexpr double kPreferComplement = 1e-2;  // |a| of w_s against the largest tied pivot
// A pair swap or match moves the basic values by |x_p/a_p|·‖a‖∞ (degenerate only where the
// point is consistent); it is refused beyond this, the scale of q in normalized units: a
// larger move comes from a tiny pivot and leaves garbage (measured on a polygon pile's
// fc2d problem from a 50-sweep PGS point: basic values of −4.6e4 without the bound).
constexpr double kDegenerateMove = 1.0;
// Most complementary pivots of one path (purify_path) before it is given up, and of all
// paths of one purification per unknown (bounds its cost at a few solves per unknown on
// problems where the paths keep failing).
constexpr int kPathPivots = 50;
constexpr double kPathPivotsPerUnknown = 1.0;
}  // namespace

// Harris' ratio test for lowering a superbasic variable by at most `limit`: the row that
// blocks first (-1: none before `limit`), the complement position `prefer` chosen among
// the tied rows when its pivot is within kPreferComplement of the largest.
Index LemkeSolver::Impl::purify_ratio_row(double limit, Index prefer) const {
  const double amax = a.lpNorm<Eigen::Infinity>();
  const double ptol = std::max(tol, kRelativePivot * amax);
  double relaxed = limit;
  for (Index k = 0; k < n; ++k)
    if (a(k) < -ptol) relaxed = std::min(relaxed, (std::max(xB(k), 0.0) + kFeasibility) / -a(k));
  Index r = -1;
  for (Index k = 0; k < n; ++k)
    if (a(k) < -ptol && std::max(xB(k), 0.0) / -a(k) <= relaxed && (r < 0 || a(k) < a(r))) r = k;
  if (r >= 0 && prefer >= 0 && prefer != r && a(prefer) < -ptol && a(prefer) <= kPreferComplement * a(r) &&
      std::max(xB(prefer), 0.0) / -a(prefer) <= relaxed)
    r = prefer;
  if (r >= 0 && std::max(xB(r), 0.0) / -a(r) >= limit) r = -1;
  return r;
}

// Pivot of the solved column `a` (variable `entering`) into row r; x_B(r) = value, the
// other basic values unchanged. Refactorizes when the update asks for it; false if the
// basis became singular.
bool LemkeSolver::Impl::purify_exchange(Index r, Index entering, double value) {
  const bool updated = basis->replace(r, a);
  factor_current = false;
  basic[r] = entering;
  xB(r) = value;
  return updated || factorize_basic();
}

// Variable `var` into row p by a degenerate exchange: its pivot there must be above the
// relative tolerance and the move of the basic values, |x_p/a_p|·‖a‖∞, at most
// kDegenerateMove. 1: done; 0: refused (nothing changed); −1: the basis became singular.
int LemkeSolver::Impl::purify_degenerate_exchange(Index p, Index var) {
  basis->solve_column(var, a);
  const double amax = a.lpNorm<Eigen::Infinity>();
  if (!a.allFinite() || !(std::abs(a(p)) > std::max(tol, kRelativePivot * amax))) return 0;
  const double value = xB(p) / a(p);
  if (std::abs(value) * amax > kDegenerateMove) return 0;
  for (Index k = 0; k < n; ++k)
    if (k != p) xB(k) -= a(k) * value;
  ++result.info.purification_steps;
  return purify_exchange(p, var, value) ? 1 : -1;
}

// Complementary pivots after z_s displaced another pair's member v (z_s and w_s both
// basic, v and its complement both nonbasic): as in Lemke's method, with z_s in the role of
// the artificial z₀, the complement of the variable that left enters and the ratio test
// picks the next to leave, until a member of pair s leaves (then every pair has exactly one
// basic member again), or kPathPivots pivots, the purification's `budget` (counted down
// here) or a ray end the path with pair s left as it is. An entering z_k that is still
// superbasic enters at its value plus the step. Ties are broken towards pair s (as
// Lemke's towards z₀), then towards the largest pivot (Harris). False if the basis became
// singular.
bool LemkeSolver::Impl::purify_path(Index s, Index leaving, Vector& z_super, std::vector<Index>& position,
                                    long& budget) {
  Index entering = complement(leaving, n);
  for (int step = 0; step < kPathPivots && budget > 0; ++step, --budget) {
    basis->solve_column(entering, a);  // x_B(θ) = x_B − θ·a as the entering variable rises by θ
    if (!a.allFinite()) return false;
    const double ptol = std::max(tol, kRelativePivot * a.lpNorm<Eigen::Infinity>());
    double relaxed = std::numeric_limits<double>::infinity();
    for (Index k = 0; k < n; ++k)
      if (a(k) > ptol) relaxed = std::min(relaxed, (std::max(xB(k), 0.0) + kFeasibility) / a(k));
    Index r = -1;
    bool r_in_pair = false;
    for (Index k = 0; k < n; ++k) {
      if (!(a(k) > ptol) || std::max(xB(k), 0.0) / a(k) > relaxed) continue;
      const bool in_pair = basic[k] == s || basic[k] == n + s;
      if (r < 0 || (in_pair && !r_in_pair) || (in_pair == r_in_pair && a(k) > a(r))) {
        r = k;
        r_in_pair = in_pair;
      }
    }
    if (r < 0) return true;  // a ray: pair s stays with both members
    const double theta = std::max(xB(r), 0.0) / a(r);
    xB.noalias() -= theta * a;
    double value = theta;
    if (entering >= n && z_super(entering - n) > 0.0) {
      value += z_super(entering - n);
      z_super(entering - n) = 0.0;
    }
    const Index left = basic[r];
    position[static_cast<std::size_t>(left)] = -1;
    position[static_cast<std::size_t>(entering)] = r;
    ++result.info.purification_steps;
    if (!purify_exchange(r, entering, value)) return false;
    if (left == s || left == n + s) return true;
    entering = complement(left, n);
  }
  return true;
}

// w_j, else z_j, into row ws (held by w_s) when its pivot there is large enough; false if
// the basis became singular (true also when neither pivot qualifies: nothing changes).
bool LemkeSolver::Impl::purify_pair_swap(Index ws, Index j) {
  for (Index var : {j, n + j})
    if (const int done = purify_degenerate_exchange(ws, var); done != 0) return done > 0;
  return true;
}

// Pairs left with both members basic (the entering z_s kept its complement w_s where no
// pair swap qualified at the time) are matched with pairs left with neither: the member
// of a both-pair with the smaller value (near zero for a consistent point) leaves, and
// the member of a none-pair with the largest pivot in its row enters (pivots from the row
// of B⁻¹, e_pᵀB⁻¹·column; a degenerate exchange). Pairs that find no pivot above the
// relative tolerance stay as they are. False if the basis became singular.
bool LemkeSolver::Impl::purify_match_pairs(std::vector<Index>& position) {
  std::vector<Index> none;
  for (Index j = 0; j < n; ++j)
    if (position[static_cast<std::size_t>(j)] < 0 && position[static_cast<std::size_t>(n + j)] < 0) none.push_back(j);
  if (none.empty()) return true;
  std::vector<int> index;
  std::vector<double> value;
  Vector rho = Vector::Zero(n);
  for (Index s = 0; s < n && !none.empty(); ++s) {
    const Index pw = position[static_cast<std::size_t>(s)], pz = position[static_cast<std::size_t>(n + s)];
    if (pw < 0 || pz < 0) continue;
    const Index p = std::abs(xB(pz)) < std::abs(xB(pw)) ? pz : pw;
    basis->inverse_row_nonzeros(p, index, value);
    for (std::size_t k = 0; k < index.size(); ++k) rho(index[k]) = value[k];
    double best = 0.0;
    Index best_var = -1;
    std::size_t best_slot = 0;
    for (std::size_t k = 0; k < none.size(); ++k) {
      const Index j = none[k];
      double pz_j = 0.0;
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) pz_j -= rho(it.row()) * it.value();
      for (const auto& [var, piv] : {std::pair<Index, double>{j, rho(j)}, std::pair<Index, double>{n + j, pz_j}})
        if (std::abs(piv) > best) {
          best = std::abs(piv);
          best_var = var;
          best_slot = k;
        }
    }
    for (std::size_t k = 0; k < index.size(); ++k) rho(index[k]) = 0.0;
    if (best_var < 0) continue;
    const Index leaving = basic[p];
    const int done = purify_degenerate_exchange(p, best_var);
    if (done < 0) return false;
    if (done == 0) continue;
    position[static_cast<std::size_t>(leaving)] = -1;
    position[static_cast<std::size_t>(best_var)] = p;
    none.erase(none.begin() + static_cast<std::ptrdiff_t>(best_slot));
  }
  return true;
}

// Sets `warm` to the purified basis. False (warm = warm_fallback if given, else {z_j : z̃_j >
// w̃_j}, the basis the point suggests) when the basis became singular, the values
// non-finite, or a pair is left with both members basic.
bool LemkeSolver::Impl::purify_warm_point() {
  const bool ok = purify_into_warm();
  // The warm start then runs on a fresh basis object, as it would on a fresh solver given
  // the purified basis: the pivots after a purification do not depend on its solves (the
  // sparse basis adapts its solves to the density of the columns it has seen; on a
  // 2,336-contact polygon pile the cold path after a failed purification took 658,883
  // pivots to its ray against 191,655 without this).
  new_basis();
  return ok;
}

bool LemkeSolver::Impl::purify_into_warm() {
  const Vector zt = (warm_point / q_norm).cwiseMax(0.0);
  Vector z_super = zt;
  xB = q;
  xB.noalias() += M * zt;  // w̃
  warm.assign(static_cast<std::size_t>(n), false);
  for (Index j = 0; j < n; ++j) warm[static_cast<std::size_t>(j)] = zt(j) > xB(j);
  if (!warm_fallback.empty()) warm = warm_fallback;
  std::vector<Index> order;
  for (Index j = 0; j < n; ++j)
    if (zt(j) > 0.0) order.push_back(j);
  std::sort(order.begin(), order.end(), [&](Index i, Index j) { return zt(i) > zt(j); });
  for (Index k = 0; k < n; ++k) basic[k] = k;
  if (!refactor(refine)) return false;  // the identity (refine: scratch)
  std::vector<Index> position(static_cast<std::size_t>(2 * n), -1);  // basis row of each variable
  for (Index k = 0; k < n; ++k) position[static_cast<std::size_t>(k)] = k;
  bool ok = true;
  long path_budget = static_cast<long>(kPathPivotsPerUnknown * static_cast<double>(n)) + kPathPivots;
  for (Index s : order) {
    basis->solve_column(n + s, a);
    if (!a.allFinite()) {
      ok = false;
      break;
    }
    ++result.info.purification_steps;
    const Index ws = position[static_cast<std::size_t>(s)];
    const Index r = purify_ratio_row(z_super(s), ws);
    const double t = r < 0 ? z_super(s) : std::max(xB(r), 0.0) / -a(r);
    xB.noalias() += t * a;
    const double rest = z_super(s) - t;
    z_super(s) = 0.0;
    if (r < 0) continue;  // z_s reached zero outside the basis
    const Index leaving = basic[r];
    position[static_cast<std::size_t>(leaving)] = -1;
    position[static_cast<std::size_t>(n + s)] = r;
    if (!purify_exchange(r, n + s, rest)) {
      ok = false;
      break;
    }
    // z_s displaced another pair's member (now zero), which leaves that pair without a
    // basic variable and pair s with both: complementary pivots restore one per pair.
    const Index j = leaving < n ? leaving : leaving - n;
    if (j != s && ws >= 0) {
      if (!purify_pair_swap(ws, j)) {
        ok = false;
        break;
      }
      if (basic[ws] != s) {
        position[static_cast<std::size_t>(s)] = -1;
        position[static_cast<std::size_t>(basic[ws])] = ws;
      } else if (!purify_path(s, leaving, z_super, position, path_budget)) {
        ok = false;
        break;
      }
    }
  }
  if (ok) ok = purify_match_pairs(position);
  // A basis that holds both members of some pair is not a complementary start: the
  // suggested basis (`warm` as set above) is used instead.
  for (Index j = 0; j < n && ok; ++j)
    ok = (position[static_cast<std::size_t>(j)] < 0) != (position[static_cast<std::size_t>(n + j)] < 0);
  if (!ok || !xB.allFinite()) return false;
  std::fill(warm.begin(), warm.end(), false);
  for (Index k = 0; k < n; ++k)
    if (basic[k] >= n && basic[k] < 2 * n) warm[static_cast<std::size_t>(basic[k] - n)] = true;
  return true;
}

}  // namespace lcprelax
