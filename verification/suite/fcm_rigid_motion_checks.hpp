#pragma once
#include "report.hpp"

namespace hofem::verification {

/// Longva et al. 2020 Fig. 6: a spinning body keeps its centre of mass when embedded in
/// one coarse cell (FCM), and not on a coarse conforming mesh. Group "embedded.fig6".
void add_fcm_rigid_motion_checks(Report& report);

}  // namespace hofem::verification
