// QpSettings validation (see qp_settings.hpp).
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <cmath>
#include <sstream>

namespace lcprelax {

std::string QpSettings::validation_error() const {
  std::ostringstream os;
  auto positive = [&](const char* name, double v) {
    if (!(v > 0) || std::isnan(v)) {
      if (os.str().empty()) os << name << " = " << v << " must be > 0";
    }
  };
  if (!(eps_abs >= 0) || !(eps_rel >= 0) || (eps_abs == 0 && eps_rel == 0))
    os << "eps_abs = " << eps_abs << ", eps_rel = " << eps_rel << ": both must be >= 0 and one > 0";
  positive("eps_infeasible", eps_infeasible);
  positive("time_limit", time_limit);
  positive("reg_primal", reg_primal);
  positive("reg_dual", reg_dual);
  positive("reg_max", reg_max);
  positive("conservative_row_reg_drop", conservative_row_reg_drop);
  if (os.str().empty() && max_iter < 1) os << "max_iter = " << max_iter << " must be >= 1";
  if (os.str().empty() && max_refinement < 0) os << "max_refinement = " << max_refinement << " must be >= 0";
  if (os.str().empty() && centrality_correctors < 0)
    os << "centrality_correctors = " << centrality_correctors << " must be >= 0";
  if (os.str().empty() && !(multiplier_restart_growth >= 0))
    os << "multiplier_restart_growth = " << multiplier_restart_growth << " must be >= 0";
  if (os.str().empty() && ruiz_iterations < 0) os << "ruiz_iterations = " << ruiz_iterations << " must be >= 0";
  if (os.str().empty() && !(step_fraction > 0 && step_fraction < 1))
    os << "step_fraction = " << step_fraction << " must be in (0, 1)";
  if (os.str().empty() && dense_max_kkt < 0) os << "dense_max_kkt = " << dense_max_kkt << " must be >= 0";
  if (os.str().empty() && uses_petsc(kkt_backend) && !mpi::petsc_available())
    os << "kkt_backend = " << to_string(kkt_backend)
       << " needs PETSc, but lcprelax was built with LCPRELAX_WITH_PETSC=OFF (or without PETSc found)";
  return os.str();
}

}  // namespace lcprelax
