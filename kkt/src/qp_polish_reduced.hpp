#pragma once
// The reduced KKT system of solution polishing (internal; method in qp_polish.hpp, step 2)
// and its refinement (step 2).
#include "standard_form.hpp"

#include <vector>

namespace lcprelax::detail {

/// Active side per kept row of G̃ (rows) and per variable (bounds): 0 inactive, −1 lower,
/// +1 upper. Fixed variables (Ẽ rows) have no side here.
struct ActiveSet {
  std::vector<signed char> rows, bounds;
  bool operator==(const ActiveSet& o) const { return rows == o.rows && bounds == o.bounds; }
};

/// Scaled polished point: x̃ (n), ỹ (me), ζ (mg; 0 at inactive rows).
struct ScaledPoint {
  Vector x, y, zg;
};

/// Index maps of a reduced system: free variables (col), active rows (pos), the values of
/// the variables fixed at a bound (xb; 0 at free ones) and the dimensions.
struct Reduced {
  std::vector<Index> col, pos;
  Vector xb;
  Index nF = 0, mA = 0, N = 0;
};

Reduced reduce(const StandardForm& f, const ActiveSet& a);

/// Step 2: refinement on K0 v = r from the scaled point `start`, keeping the iterate of
/// smallest ‖r − K0 v‖∞ (residual accumulated in long double). False when the
/// factorization fails.
bool solve_reduced(const StandardForm& f, const ScaledPoint& start, const ActiveSet& a, ScaledPoint& out);

}  // namespace lcprelax::detail
