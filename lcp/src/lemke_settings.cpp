// LemkeSettings validation (see lcp_types.hpp).
#include <lcprelax/lcp/lcp_types.hpp>

#include <cmath>
#include <sstream>

namespace lcprelax {

std::string LemkeSettings::validation_error() const {
  std::ostringstream os;
  if (max_pivots < 0) os << "max_pivots = " << max_pivots << " must be >= 0";
  else if (!(pivot_tolerance >= 0)) os << "pivot_tolerance = " << pivot_tolerance << " must be >= 0";
  else if (!(residual_tolerance >= 0)) os << "residual_tolerance = " << residual_tolerance << " must be >= 0";
  else if (covering_retries < 0) os << "covering_retries = " << covering_retries << " must be >= 0";
  else if (regularization_retries < 0) os << "regularization_retries = " << regularization_retries << " must be >= 0";
  else if (!(regularization > 0) || !std::isfinite(regularization)) os << "regularization = " << regularization << " must be finite and > 0";
  else if (dense_max_n < 0) os << "dense_max_n = " << dense_max_n << " must be >= 0";
  else if (crash_flip_rounds < 0) os << "crash_flip_rounds = " << crash_flip_rounds << " must be >= 0";
  else if (refactor_interval < 1) os << "refactor_interval = " << refactor_interval << " must be >= 1";
  else if (!(lu_pivot_tolerance > 0 && lu_pivot_tolerance <= 1))
    os << "lu_pivot_tolerance = " << lu_pivot_tolerance << " must be in (0, 1]";
  else
    for (Index i = 0; i < covering.size(); ++i)
      if (!(covering(i) > 0) || !std::isfinite(covering(i))) {
        os << "covering(" << i << ") = " << covering(i) << " must be finite and > 0";
        break;
      }
  return os.str();
}

}  // namespace lcprelax
