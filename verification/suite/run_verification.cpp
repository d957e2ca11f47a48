#include "run_verification.hpp"

#include "basis_checks.hpp"
#include "quadrature_checks.hpp"

namespace hofem::verification {

Report run_all_checks() {
  Report report;
  add_quadrature_checks(report);
  add_basis_checks(report);
  return report;
}

}  // namespace hofem::verification
