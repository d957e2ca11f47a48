#pragma once
#include "report.hpp"

namespace hofem::verification {

/// Runs every check of the suite (quadrature, bases) into one report.
Report run_all_checks();

}  // namespace hofem::verification
