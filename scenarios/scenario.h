// The scenario model: plain structs filled from YAML by LoadScenario(). All values are SI
// and Earth-frame NED unless a name says otherwise; angles are radians here (the YAML
// gives them in degrees under keys ending in `_deg`). Line numbers are 1-based.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"

namespace moorsim::scenarios {

/// Where a value came from in the YAML text (1-based line and column), for messages.
struct SourceMark {
  int line = 0;
  int column = 0;
};

/// Material and hydrodynamic properties of one line type (seed 002 Table 2 style).
struct LineType {
  std::string name;
  double diameter = 0.0;         ///< nominal (hydrodynamic and displacement) diameter [m]
  double mass_per_length = 0.0;  ///< dry mass per unstretched length [kg/m]
  double axial_stiffness = 0.0;  ///< EA [N]
  /// Axial structural damping: internal force = c * strain rate, c in [N s]. If
  /// axial_damping_ratio is set instead, c is chosen per line so that a single segment's
  /// axial mode has that fraction of critical damping (a numerical damping that vanishes
  /// as segments shrink).
  std::optional<double> axial_damping;
  std::optional<double> axial_damping_ratio;
  double drag_normal = 0.0;        ///< C_DN [-]
  double drag_tangential = 0.0;    ///< C_DT [-]
  double added_mass_normal = 0.0;  ///< C_MN [-]
  double friction_axial = 0.0;     ///< seabed Coulomb coefficient along the line [-]
  double friction_lateral = 0.0;   ///< seabed Coulomb coefficient across the line [-]
  SourceMark mark;
};

struct LineSpec {
  int id = 0;              ///< 1-based line number
  std::string type;        ///< name of a LineType
  Vec3 anchor;             ///< anchor position, Earth frame [m] (z = +depth for the seabed)
  Vec3 fairlead_body;      ///< fairlead position in the body frame of the vessel [m]
  double length = 0.0;     ///< unstretched length [m]
  int segments = 50;       ///< number of equal segments
  SourceMark mark;         ///< the list entry
  SourceMark length_mark;  ///< the `length` key's value (for the distance check)
  /// 1-based position of the entry in the YAML list (0 = not from YAML). Lines are sorted
  /// by id after loading, so messages use this to name the entry the user wrote.
  int entry = 0;
};

struct Water {
  double density = 1025.0;  ///< [kg/m^3]
  double gravity = 9.81;    ///< [m/s^2]
  double depth = 0.0;       ///< seabed depth below the mean free surface [m], > 0
};

/// Penalty contact with a flat seabed at z = water.depth, per unit of contact area
/// (diameter x length), and regularised Coulomb friction (coefficients per line type).
struct Seabed {
  double stiffness = 3.0e6;  ///< [N/m^3] (pressure per metre of penetration)
  double damping = 3.0e5;    ///< [N s/m^3]
  /// Penetration [m] over which the contact stiffness ramps from zero to `stiffness`. A
  /// gradual ramp keeps touchdown smooth for the implicit integrator (benchmarks/README.md:
  /// with 2 mm, landing nodes caused most Newton failures and halved the step size).
  double contact_smoothing = 0.5;
  /// Speed [m/s] below which Coulomb friction is regularised (force ~ speed). Smaller is
  /// closer to true stick-slip and costs steps (0.05 m/s ran 20 % slower than 0.1).
  double friction_velocity = 0.1;
};

/// Current: a horizontal velocity whose speed varies piecewise linearly with depth and is
/// held constant beyond the first and last points. `direction` is the direction the water
/// flows TO, measured from north toward east [rad].
struct CurrentProfile {
  double direction = 0.0;
  std::vector<double> depth;  ///< strictly increasing depths [m], >= 0
  std::vector<double> speed;  ///< speeds at those depths [m/s], >= 0
};

/// Values that apply to every line unless the line says otherwise.
struct LineDefaults {
  int segments = 50;
};

struct MooringSpec {
  Water water;
  Seabed seabed;
  CurrentProfile current;  ///< empty profile = no current
  std::vector<LineType> line_types;
  LineDefaults defaults;
  std::vector<LineSpec> lines;  ///< ordered by id after loading: lines[k - 1] is line k
};

/// Integrator settings (CVODE BDF).
struct SolverSpec {
  double rtol = 1e-4;
  double atol_position = 1e-3;  ///< [m]
  double atol_velocity = 1e-3;  ///< [m/s]
  /// BDF order cap. 2 (A-stable) by default: orders 3-5 are not A-stable and the lines'
  /// lightly damped modes kept them at small steps (benchmarks/README.md).
  int max_order = 2;
  bool stability_limit_detection = false;
  double max_step = 0.0;  ///< [s]; 0 = no limit
};

struct Scenario {
  std::string name;
  std::string source_path;  ///< file it was read from
  std::string text;         ///< the full YAML text, recorded in outputs
  MooringSpec mooring;
  SolverSpec solver;
  /// Where each value was written, by key path ("mooring.lines[3].length", list indices
  /// 1-based), so checks after parsing can point at the offending text.
  std::map<std::string, SourceMark> marks;
};

}  // namespace moorsim::scenarios
