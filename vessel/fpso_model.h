// The low-frequency vessel model built from hydrodynamic data: M_RB from the mass
// properties, A(0) and hydrostatic restoring from the BEM files, and low-frequency damping
// by the MSS rule (docs/design.md section 9).
#pragma once

#include "vessel/hydro_data.h"
#include "vessel/rigid_body.h"
#include "vessel/vessel_model.h"

namespace moorsim::vessel {

/// Viscous low-frequency damping (MSS rule, docs/design.md section 9): surge, sway and yaw get
/// B_ii = (M_RB,ii + A_ii(0)) / T_i; heave, roll and pitch a fraction of their critical
/// damping 2 sqrt((M_ii + A_ii(0)) C_ii) (roll 5-10 % per the same table).
struct LowFrequencyDamping {
  double surge_time = 50.0;  ///< T_1 [s]
  double sway_time = 100.0;  ///< T_2 [s]
  double yaw_time = 20.0;    ///< T_6 [s]
  double heave_ratio = 0.1;  ///< fraction of critical
  double roll_ratio = 0.07;
  double pitch_ratio = 0.1;
};

/// The seed FPSO's mass properties (docs/design.md section 9: 1.0041e8 kg = rho x 97 961 m^3; CG on
/// the centreline 1 m below the waterline, z = +1 m in the body frame; radii of gyration
/// 16.3 / 54 / 54 m).
MassProperties SeedFpsoMass();

VesselParameters LowFrequencyVessel(const HydroData& hydro, const MassProperties& mass,
                                    const LowFrequencyDamping& damping = {});

}  // namespace moorsim::vessel
