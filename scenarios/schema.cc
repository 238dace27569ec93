#include "scenarios/schema.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/format.h"
#include "scenarios/campaign.h"
#include "scenarios/scenario.h"
#include "scenarios/strict_yaml.h"

// The tables name only the members a key sets (designated initializers); the rest keep
// Key's defaults on purpose. GCC 12 warns for every member left out.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace moorsim::scenarios::schema {
namespace {

// ---------------------------------------------------------------------------------------
// Defaults: JSON text of a spec struct's member, so the schema shows what the loader uses.

std::string Json(double value) { return FormatNumber(value); }
std::string Json(int value) { return std::to_string(value); }
std::string Json(std::uint64_t value) { return std::to_string(value); }
std::string Json(bool value) { return value ? "true" : "false"; }
std::string Json(const std::string& value) { return nlohmann::json(value).dump(); }
template <Choice E>
std::string Json(E value) {
  return Json(std::string(ChoiceName(value)));
}
std::string Json(const Vec3& v) {
  return "[" + Json(v.x()) + ", " + Json(v.y()) + ", " + Json(v.z()) + "]";
}

// A default read from a spec struct's member: `+[] { return Json(<expression>); }`.
#define MOORSIM_DEFAULT(expression) (+[]() -> std::string { return Json(expression); })

// ---------------------------------------------------------------------------------------
// Physical bounds. Beyond them a value is a typo or a unit mistake (a mass in tonnes, a
// period in minutes, 1e308) that would otherwise overflow or stall the solvers deep in a
// run.

constexpr double kMaxDepth = 12000.0;       // [m]
constexpr double kMaxLineLength = 20000.0;  // [m]
constexpr double kMaxCoefficient = 10.0;    // drag, added-mass, friction: of order 1
constexpr double kMaxTime = 1e7;            // [s], 116 days: run lengths, time constants
constexpr double kMaxRate = 1000.0;         // [Hz]: sample and output rates
constexpr double kMaxOffset = 1e5;          // [m]: vessel positions in the field

constexpr std::string_view kDepthWhy = "the deepest ocean is 11 km";
constexpr std::string_view kCoefficientWhy = "a dimensionless coefficient, of order 1";
constexpr std::string_view kVesselPointWhy = "a point on the vessel";
constexpr std::string_view kThrustWhy = "the largest thrusters give about 2e6 N";

constexpr Bound Above(double v) { return {v, true, {}}; }
constexpr Bound AtLeast(double v, std::string_view why = {}) { return {v, false, why}; }
constexpr Bound Below(double v, std::string_view why = {}) { return {v, true, why}; }
constexpr Bound AtMost(double v, std::string_view why = {}) { return {v, false, why}; }

// Keys of one common shape.
constexpr Key Positive(std::string_view name, std::string_view unit, double high,
                       std::string_view description, std::string_view why = {}) {
  return {.name = name,
          .unit = unit,
          .description = description,
          .minimum = Above(0.0),
          .maximum = AtMost(high, why)};
}
constexpr Key NonNegative(std::string_view name, std::string_view unit, double high,
                          std::string_view description, std::string_view why = {}) {
  return {.name = name,
          .unit = unit,
          .description = description,
          .minimum = AtLeast(0.0),
          .maximum = AtMost(high, why)};
}
constexpr Key Probability(std::string_view name, std::string_view description) {
  return {.name = name,
          .description = description,
          .minimum = AtLeast(0.0),
          .maximum = Below(1.0),
          .interval = true};
}
constexpr Key Angle(std::string_view name, std::string_view description, bool required) {
  return {.name = name,
          .unit = "deg",
          .description = description,
          .required = required,
          .minimum = AtLeast(-360.0),
          .maximum = AtMost(360.0),
          .interval = true};
}
constexpr Key Rate(std::string_view name, std::string_view description) {
  return Positive(name, "Hz", kMaxRate, description);
}
constexpr Key Map(std::string_view name, const Block& block, std::string_view description,
                  bool required = false) {
  return {.name = name,
          .kind = Kind::kMap,
          .description = description,
          .required = required,
          .block = &block};
}
constexpr Key List(std::string_view name, const Block& block, std::string_view description,
                   bool required = false, int min_items = 0) {
  return {.name = name,
          .kind = Kind::kList,
          .description = description,
          .required = required,
          .block = &block,
          .min_items = min_items};
}

// Chained settings.
constexpr Key Required(Key key) {
  key.required = true;
  return key;
}
constexpr Key WithDefault(Key key, std::string (*json)()) {
  key.default_json = json;
  return key;
}

// ---------------------------------------------------------------------------------------
// mooring

constexpr Key kWaterKeys[] = {
    WithDefault({.name = "density",
                 .unit = "kg/m^3",
                 .description = "Sea water density.",
                 .minimum = AtLeast(900.0),
                 .maximum = AtMost(1100.0, "water: fresh 1000, sea about 1025"),
                 .interval = true},
                MOORSIM_DEFAULT(Water{}.density)),
    Required(Positive("depth", "m", kMaxDepth,
                      "Water depth: the waves' and a flat seabed's z (NED, down); a sloping "
                      "seabed's below the origin.",
                      kDepthWhy)),
    WithDefault({.name = "gravity",
                 .unit = "m/s^2",
                 .description = "Acceleration of gravity.",
                 .minimum = AtLeast(9.7),
                 .maximum = AtMost(9.9, "Earth's gravity"),
                 .interval = true},
                MOORSIM_DEFAULT(Water{}.gravity)),
};
constexpr Block kWater{"The water and its depth.", kWaterKeys};

constexpr Key kSeabedKeys[] = {
    WithDefault(Positive("contact_smoothing", "m", 10.0,
                         "Penetration over which the contact stiffness ramps up (smooth contact)."),
                MOORSIM_DEFAULT(Seabed{}.contact_smoothing)),
    WithDefault(
        NonNegative("damping", "N s/m^3", 1e10, "Contact damping per unit of contact area."),
        MOORSIM_DEFAULT(Seabed{}.damping)),
    WithDefault(Positive("friction_velocity", "m/s", 10.0,
                         "Sliding speed below which Coulomb friction is regularised."),
                MOORSIM_DEFAULT(Seabed{}.friction_velocity)),
    {.name = "grid",
     .kind = Kind::kString,
     .description = "A depth grid file, relative to this file's folder: a label and the east "
                    "coordinates y, then rows of a north coordinate x and the depths at each y "
                    "[m]; bilinear, held at the edges beyond. Not with slope_deg."},
    WithDefault({.name = "slope_deg",
                 .unit = "deg",
                 .description = "A plane seabed's angle to the horizontal; it passes through "
                                "water.depth below the origin.",
                 .minimum = AtLeast(0.0),
                 .maximum = AtMost(45.0, "steeper than the steepest continental slopes"),
                 .interval = true},
                MOORSIM_DEFAULT(0.0)),
    WithDefault(Angle("slope_direction_deg",
                      "Direction in which the sloping seabed gets deeper, from north, clockwise "
                      "(east = 90).",
                      false),
                MOORSIM_DEFAULT(0.0)),
    WithDefault(
        Positive("stiffness", "N/m^3", 1e10, "Penalty contact stiffness per unit of contact area.",
                 "stiffer than rock"),
        MOORSIM_DEFAULT(Seabed{}.stiffness)),
};
constexpr Block kSeabed{
    "The seabed's shape (flat, a plane or a depth grid) and penalty contact with it (smooth, "
    "regularised friction).",
    kSeabedKeys};

constexpr Key kCurrentPointKeys[] = {
    Required(NonNegative("depth", "m", kMaxDepth, "Depth of the point; strictly increasing.",
                         kDepthWhy)),
    Required(NonNegative("speed", "m/s", 5.0, "Current speed at that depth.",
                         "the strongest ocean currents run at about 2.5 m/s")),
};
constexpr Block kCurrentPoint{"One point of the current profile.", kCurrentPointKeys};

constexpr Key kCurrentKeys[] = {
    Angle("direction_deg",
          "Direction the water flows TOWARD, from north, clockwise (east = 90). Required with "
          "profile.",
          false),
    {.name = "file",
     .kind = Kind::kString,
     .description = "A current table file, relative to this file's folder, in place of "
                    "direction_deg and profile: the water's velocity (north, east, down) over "
                    "north, east, depth and time; quadrilinear, held at the ends beyond."},
    Positive("period", "s", 1e6,
             "With file: the table repeats in time with this period (longer than its times "
             "span); omitted = held at its first and last times.",
             "eleven days"),
    List("profile", kCurrentPoint,
         "Speed against depth, piecewise linear, held constant beyond the end points. Required "
         "without file.",
         false, 1),
};
constexpr Block kCurrent{"A current (a depth profile or a table); omitted = no current.",
                         kCurrentKeys};

constexpr Key kStrainTensionKeys[] = {
    Required(Positive("strain", "", 1.0, "Strain (stretched length / unstretched - 1).")),
    Required(Positive("tension", "N", 1e9, "Tension at that strain.", "above any rope's")),
};
constexpr Block kStrainTension{"One point of a tension-strain curve.", kStrainTensionKeys};

constexpr Key kFatigueKeys[] = {
    Positive("a", "", 1e30,
             "The curve's constant: a_D of N = a_D S^-m (S in MPa) for a stress curve, K of "
             "N R^M = K for a normalised one; omitted = the named curve's."),
    {.name = "curve",
     .kind = Kind::kString,
     .description = "A standard's curve: studless_chain, studlink_chain, six_strand_rope, "
                    "spiral_rope (DNV-OS-E301, on the nominal stress range) or polyester "
                    "(API RP 2SM, on the range over the breaking load). Omitted: give a and m.",
     .choices = ChoiceNames<analysis::TnPreset>(),
     .choice_noun = ChoiceNoun<analysis::TnPreset>()},
    Positive("m", "", 20.0, "The curve's exponent; omitted = the named curve's."),
    NonNegative("mean_load_slope", "", 100.0,
                "c of log10 a = log10 a0 - c L_m, L_m the cycle's mean tension over the "
                "minimum breaking load (API RP 2SK's mean-load term); omitted = the named "
                "curve's (0 for all of them)."),
    Positive("nominal_area", "m^2", 1.0,
             "The area a stress curve divides the tension range by; omitted = two bars of the "
             "type's diameter for a chain curve, one section (pi d^2 / 4) otherwise."),
    {.name = "range",
     .kind = Kind::kString,
     .description = "stress (the tension range over nominal_area, in MPa) or normalised (over "
                    "minimum_breaking_load); omitted = the named curve's, else stress.",
     .choices = ChoiceNames<analysis::TnRange>(),
     .choice_noun = ChoiceNoun<analysis::TnRange>()},
};
constexpr Block kFatigue{
    "The line type's T-N curve for the fatigue checks: a standard's curve, or a and m.",
    kFatigueKeys};

constexpr Key kLineTypeKeys[] = {
    {.name = "added_mass_normal",
     .description = "Added-mass coefficient C_MN.",
     .required = true,
     .minimum = AtLeast(0.0),
     .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
    WithDefault({.name = "added_mass_tangential",
                 .description = "Added-mass coefficient along the line C_MT (on the displaced "
                                "volume, as C_MN).",
                 .minimum = AtLeast(0.0),
                 .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
                MOORSIM_DEFAULT(mooring_fem::LineType{}.added_mass_tangential)),
    NonNegative("axial_damping", "N s", 1e10,
                "Axial damping c (force = c x strain rate); not with axial_damping_ratio."),
    {.name = "axial_damping_ratio",
     .description = "Fraction of one segment's critical axial damping; not with axial_damping. "
                    "Neither given = 0.5.",
     .minimum = AtLeast(0.0),
     .maximum = AtMost(10.0),
     .interval = true},
    Positive("axial_stiffness", "N", 1e11,
             "Axial stiffness EA (or give tension_strain instead); a visco-elastic rope's "
             "quasi-static stiffness.",
             "a solid steel bar 0.8 m thick"),
    Positive("creep_time", "s", 1e6,
             "A visco-elastic rope's creep time: under a constant tension its creep strain "
             "settles with this time constant. With dynamic_axial_stiffness.",
             "eleven days"),
    Required(Positive("diameter", "m", 1.0, "Hydrodynamic and displacement diameter.",
                      "the thickest mooring lines are about 0.3 m")),
    {.name = "drag_normal",
     .description = "Normal drag coefficient C_DN.",
     .required = true,
     .minimum = AtLeast(0.0),
     .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
    {.name = "drag_tangential",
     .description = "Tangential drag coefficient C_DT.",
     .required = true,
     .minimum = AtLeast(0.0),
     .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
    Positive("dynamic_axial_stiffness", "N", 1e11,
             "A visco-elastic rope's dynamic stiffness, above axial_stiffness: what it shows to "
             "loads faster than the creep time (the waves' cycles). With creep_time.",
             "a solid steel bar 0.8 m thick"),
    NonNegative("dynamic_axial_stiffness_slope", "", 1000.0,
                "A visco-elastic rope's rise of dynamic stiffness with its mean load: "
                "EA_d = dynamic_axial_stiffness + slope x mean tension (newtons per newton; "
                "Del Vecchio's beta per % of the breaking load, times 100). With "
                "dynamic_axial_stiffness; none = a constant dynamic stiffness.",
                "polyester's is about 30"),
    Map("fatigue", kFatigue,
        "The T-N curve for the fatigue checks; omitted = none (the checks then name the type)."),
    WithDefault({.name = "friction_axial",
                 .description = "Seabed Coulomb friction coefficient along the line.",
                 .minimum = AtLeast(0.0),
                 .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
                MOORSIM_DEFAULT(mooring_fem::LineType{}.friction_axial)),
    WithDefault({.name = "friction_lateral",
                 .description = "Seabed Coulomb friction coefficient across the line.",
                 .minimum = AtLeast(0.0),
                 .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)},
                MOORSIM_DEFAULT(mooring_fem::LineType{}.friction_lateral)),
    {.name = "mass_per_length",
     .unit = "kg/m",
     .description = "Dry mass per unit length; more than the water it displaces, but in a "
                    "section of a line that weighs more than its water as a whole.",
     .required = true,
     .maximum = AtMost(10000.0, "the heaviest chains weigh about 1000 kg/m")},
    Positive("minimum_breaking_load", "N", 1e9,
             "Minimum breaking load (MBL), which the design checks' safety factors and "
             "utilisations are taken against; omitted = none (the checks then name the type).",
             "the strongest chains break at about 3e7 N"),
    {.name = "name",
     .kind = Kind::kString,
     .description = "Unique name that lines refer to in their `type`.",
     .required = true},
    List("tension_strain", kStrainTension,
         "A measured tension-strain curve in place of axial_stiffness: points with strain and "
         "tension both increasing, joined by a monotone cubic through (0, 0); beyond the last "
         "the last slope goes on."),
};
constexpr Block kLineType{"A line type: the cable's properties.", kLineTypeKeys};

constexpr Key kDefaultsKeys[] = {
    WithDefault({.name = "segments",
                 .kind = Kind::kInteger,
                 .description = "Segments per line unless the line says otherwise.",
                 .minimum = AtLeast(2.0),
                 .maximum = AtMost(10000.0)},
                MOORSIM_DEFAULT(LineDefaults{}.segments)),
};
constexpr Block kDefaults{"Values that apply to every line unless it says otherwise.",
                          kDefaultsKeys};

constexpr Key kSectionKeys[] = {
    Required(Positive("length", "m", kMaxLineLength, "Unstretched length of the section.")),
    {.name = "segments",
     .kind = Kind::kInteger,
     .description = "Number of equal segments of the section.",
     .required = true,
     .minimum = AtLeast(1.0),
     .maximum = AtMost(10000.0)},
    {.name = "type", .kind = Kind::kString, .description = "A line_types name.", .required = true},
};
constexpr Block kSection{"A section of a line: one line type over a length.", kSectionKeys};

// What a body at a joint and a free point have alike.
constexpr Key kBodyAddedMass{
    .name = "added_mass",
    .description = "Added-mass coefficient C_A on the displaced volume (isotropic).",
    .minimum = AtLeast(0.0),
    .maximum = AtMost(kMaxCoefficient, kCoefficientWhy)};
constexpr Key kBodyDragArea =
    NonNegative("drag_area", "m^2", 1000.0,
                "C_D A: drag 0.5 rho C_D A |u| u on the water's velocity relative to the body.",
                "a buoy 35 m across");
constexpr Key kBodyMass =
    NonNegative("mass", "kg", 1e7, "Dry mass (a clump weight: heavier than its displaced water).",
                "ten thousand tonnes");
constexpr Key kBodyVolume =
    NonNegative("volume", "m^3", 1e4, "Displaced volume (a buoy: more than mass / water density).",
                "a buoy 27 m across");

constexpr Key kBodyKeys[] = {
    kBodyAddedMass,
    kBodyDragArea,
    {.name = "joint",
     .kind = Kind::kInteger,
     .description = "The joint it sits on: 1 between sections 1 and 2 (from the anchor), ...",
     .required = true,
     .minimum = AtLeast(1.0),
     .maximum = AtMost(1000.0)},
    kBodyMass,
    kBodyVolume,
};
constexpr Block kBody{"A clump weight or buoy on a joint between two sections of a line.",
                      kBodyKeys};

constexpr Key kPointKeys[] = {
    kBodyAddedMass,
    kBodyDragArea,
    kBodyMass,
    {.name = "name",
     .kind = Kind::kString,
     .description = "What lines call it in their from and to.",
     .required = true},
    {.name = "position",
     .kind = Kind::kVector,
     .unit = "m",
     .description = "Where it starts, Earth frame NED; the static solution moves it to rest.",
     .required = true},
    kBodyVolume,
};
constexpr Block kPoint{
    "A free point: where lines meet (a bridle's apex, a shared buoy or clump weight) or a line "
    "ends in the water, with the body there.",
    kPointKeys};

constexpr Key kLineKeys[] = {
    {.name = "anchor",
     .kind = Kind::kVector,
     .unit = "m",
     .description = "Anchor, Earth frame NED (z down: on a 1000 m seabed z = +1000); or from.",
     .required = false},
    WithDefault({.name = "anchor_in_water",
                 .kind = Kind::kBoolean,
                 .description = "The anchor is a fixed point held in the water (a jumper's or "
                                "riser's base): anywhere under water, the line may hang below "
                                "it; false: it lies on the seabed. Not with detectors."},
                MOORSIM_DEFAULT(LineSpec{}.anchor_in_water)),
    List("bodies", kBody, "Clump weights and buoys on the joints between sections."),
    {.name = "fairlead",
     .kind = Kind::kVector,
     .unit = "m",
     .description = "Fairlead, body frame (x forward, y starboard, z down); or to.",
     .required = false,
     .minimum = AtLeast(-kMaxBodyCoordinate),
     .maximum = AtMost(kMaxBodyCoordinate, kVesselPointWhy),
     .interval = true},
    {.name = "from",
     .kind = Kind::kString,
     .description = "A mooring.points name: the line's lower end hangs from that free point (in "
                    "place of anchor)."},
    {.name = "id",
     .kind = Kind::kInteger,
     .description = "Line number, 1..N in any order; default: the position in the list."},
    Positive("length", "m", kMaxLineLength,
             "Unstretched length of a line of one type; the line must reach its fairlead "
             "without lying slack. Not with sections."),
    List("sections", kSection,
         "A line of several types: its sections from the anchor up (not with type, length "
         "and segments).",
         false, 1),
    {.name = "segments",
     .kind = Kind::kInteger,
     .description = "Number of segments of a line of one type; default "
                    "mooring.defaults.segments.",
     .minimum = AtLeast(2.0),
     .maximum = AtMost(10000.0)},
    {.name = "to",
     .kind = Kind::kString,
     .description = "A mooring.points name: the line's upper end is held by that free point (in "
                    "place of fairlead)."},
    {.name = "type",
     .kind = Kind::kString,
     .description = "A line_types name, for a line of one type (not with sections)."},
};
constexpr Block kLine{
    "One mooring line, from its lower end (an anchor or a free point) to its "
    "upper end (a fairlead or a free point).",
    kLineKeys};

constexpr Key kMooringKeys[] = {
    Map("current", kCurrent, "A current (or give it under environment.current)."),
    Map("defaults", kDefaults, "Values that apply to every line unless it says otherwise."),
    List("line_types", kLineType, "The cable types the lines use.", true),
    List("lines", kLine, "The mooring lines, numbered 1..N.", true),
    List("points", kPoint, "Free points where lines meet or end."),
    Map("seabed", kSeabed, "The seabed's shape, contact and friction."),
    Map("water", kWater, "Water density, gravity and depth.", true),
};
constexpr Block kMooring{"The mooring: water, seabed, line types and lines.", kMooringKeys};

// ---------------------------------------------------------------------------------------
// solver

constexpr Key kSolverKeys[] = {
    WithDefault(Positive("atol_position", "m", 1.0, "Absolute tolerance of positions."),
                MOORSIM_DEFAULT(SolverSpec{}.atol_position)),
    WithDefault(Positive("atol_velocity", "m/s", 1.0, "Absolute tolerance of velocities."),
                MOORSIM_DEFAULT(SolverSpec{}.atol_velocity)),
    WithDefault({.name = "linear_solver",
                 .kind = Kind::kString,
                 .description = "Newton solver: block (the mooring's block structure) or klu "
                                "(general sparse LU).",
                 .choices = ChoiceNames<IntegratorOptions::LinearSolver>(),
                 .choice_noun = ChoiceNoun<IntegratorOptions::LinearSolver>()},
                MOORSIM_DEFAULT(SolverSpec{}.linear_solver)),
    WithDefault({.name = "max_order",
                 .kind = Kind::kInteger,
                 .description = "Highest BDF order (orders above 2 are not A-stable).",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(5.0)},
                MOORSIM_DEFAULT(SolverSpec{}.max_order)),
    WithDefault({.name = "max_step",
                 .unit = "s",
                 .description = "Longest step; 0 = no limit.",
                 .minimum = AtLeast(0.0, "0 = no limit"),
                 .maximum = AtMost(kMaxTime)},
                MOORSIM_DEFAULT(SolverSpec{}.max_step)),
    WithDefault({.name = "max_steps",
                 .kind = Kind::kInteger,
                 .description = "Steps allowed between two stops before the solver gives up.",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(1e8)},
                MOORSIM_DEFAULT(SolverSpec{}.max_steps)),
    WithDefault({.name = "rtol",
                 .description = "Relative tolerance.",
                 .minimum = Above(0.0),
                 .maximum = Below(1.0),
                 .interval = true},
                MOORSIM_DEFAULT(SolverSpec{}.rtol)),
    WithDefault({.name = "stability_limit_detection",
                 .kind = Kind::kBoolean,
                 .description = "CVODE's BDF stability-limit detection."},
                MOORSIM_DEFAULT(SolverSpec{}.stability_limit_detection)),
};
constexpr Block kSolver{"Integrator settings (CVODE BDF).", kSolverKeys};

// ---------------------------------------------------------------------------------------
// vessel

constexpr Key kDampingKeys[] = {
    WithDefault(Probability("heave_ratio", "Heave damping, fraction of critical."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.heave_ratio)),
    WithDefault(Probability("pitch_ratio", "Pitch damping, fraction of critical."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.pitch_ratio)),
    WithDefault(Probability("roll_ratio", "Roll damping, fraction of critical."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.roll_ratio)),
    WithDefault(Positive("surge_time", "s", kMaxTime, "Surge damping time: B_11 = (M + A)_11 / T."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.surge_time)),
    WithDefault(Positive("sway_time", "s", kMaxTime, "Sway damping time: B_22 = (M + A)_22 / T."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.sway_time)),
    WithDefault(Positive("yaw_time", "s", kMaxTime, "Yaw damping time: B_66 = (M + A)_66 / T."),
                MOORSIM_DEFAULT(LowFrequencyDampingSpec{}.yaw_time)),
};
constexpr Block kDamping{"Low-frequency hull damping.", kDampingKeys};

constexpr Key Offset(std::string_view name, std::string_view description) {
  return {.name = name,
          .unit = "m",
          .description = description,
          .minimum = AtLeast(-kMaxOffset),
          .maximum = AtMost(kMaxOffset),
          .interval = true};
}

constexpr Key kPoseKeys[] = {
    Angle("heading_deg", "Heading, from north, clockwise.", false),
    Offset("x", "North position."),
    Offset("y", "East position."),
};
constexpr Block kPose{"Low-frequency start; heave, roll and pitch start at the moored equilibrium.",
                      kPoseKeys};

constexpr Key BodyCoordinate(std::string_view name, std::string_view description) {
  return {.name = name,
          .unit = "m",
          .description = description,
          .required = true,
          .minimum = AtLeast(-kMaxBodyCoordinate),
          .maximum = AtMost(kMaxBodyCoordinate, kVesselPointWhy),
          .interval = true};
}

constexpr Key kThrusterKeys[] = {
    Angle("angle_deg", "Thrust direction from the bow toward starboard.", false),
    WithDefault({.name = "azimuth",
                 .kind = Kind::kBoolean,
                 .description = "true: the allocation chooses the direction."},
                MOORSIM_DEFAULT(ThrusterEntry{}.azimuth)),
    Required(Positive("max_thrust", "N", 1e8, "Largest thrust ahead.", kThrustWhy)),
    WithDefault({.name = "min_thrust",
                 .unit = "N",
                 .description = "Largest thrust astern, as a negative number (or 0).",
                 .minimum = AtLeast(-1e8, kThrustWhy),
                 .maximum = AtMost(0.0)},
                MOORSIM_DEFAULT(ThrusterEntry{}.min_thrust)),
    {.name = "name", .kind = Kind::kString, .description = "Unique name.", .required = true},
    WithDefault(NonNegative("rate_limit", "N/s", 1e9, "Rate limit of the command; 0 = none."),
                MOORSIM_DEFAULT(ThrusterEntry{}.rate_limit)),
    WithDefault(Positive("time_constant", "s", 1000.0, "First-order thrust response."),
                MOORSIM_DEFAULT(ThrusterEntry{}.time_constant)),
    WithDefault(Positive("weight", "", 1e6, "Allocation weight."),
                MOORSIM_DEFAULT(ThrusterEntry{}.weight)),
    BodyCoordinate("x", "Position, body frame (forward)."),
    BodyCoordinate("y", "Position, body frame (starboard)."),
};
constexpr Block kThruster{"One thruster.", kThrusterKeys};

constexpr Key kHullKeys[] = {
    WithDefault(Positive("beam", "m", kMaxBodyCoordinate, "Beam B."),
                MOORSIM_DEFAULT(HullSpec{}.beam)),
    WithDefault(NonNegative("cross_flow_drag_coefficient", "", kMaxCoefficient,
                            "Cross-flow drag C_d2D; 0 = Hoerner's curve at beam / (2 draught).",
                            kCoefficientWhy),
                MOORSIM_DEFAULT(HullSpec{}.cross_flow_drag_coefficient)),
    WithDefault({.name = "displaced_volume",
                 .unit = "m^3",
                 .description = "Displaced volume, at most length x beam x draught.",
                 .minimum = Above(0.0)},
                MOORSIM_DEFAULT(HullSpec{}.displaced_volume)),
    WithDefault(Positive("draught", "m", kMaxBodyCoordinate, "Draught T."),
                MOORSIM_DEFAULT(HullSpec{}.draught)),
    {.name = "form_factor",
     .description = "k of (1 + k) C_F; omitted = Watanabe's regression from the hull's "
                    "dimensions.",
     .minimum = Above(-1.0),
     .maximum = AtMost(kMaxCoefficient, "k of (1 + k) C_F; ships 0.1 to 0.5"),
     .interval = true},
    WithDefault({.name = "kinematic_viscosity",
                 .unit = "m^2/s",
                 .description = "Kinematic viscosity of the water.",
                 .minimum = AtLeast(1e-7),
                 .maximum = AtMost(1e-5, "water: 1.8e-6 at 0 deg C, 0.7e-6 at 40 deg C"),
                 .interval = true},
                MOORSIM_DEFAULT(HullSpec{}.kinematic_viscosity)),
    WithDefault(Positive("length", "m", kMaxBodyCoordinate, "Length between perpendiculars L."),
                MOORSIM_DEFAULT(HullSpec{}.length)),
    WithDefault(NonNegative("wetted_surface", "m^2", 1e6,
                            "Wetted surface; 0 = the Denny-Mumford estimate."),
                MOORSIM_DEFAULT(HullSpec{}.wetted_surface)),
};
constexpr Block kHull{"The hull for the current load; omitted = the seed FPSO's.", kHullKeys};

constexpr Key kWindageKeys[] = {
    WithDefault({.name = "air_density",
                 .unit = "kg/m^3",
                 .description = "Air density.",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(1.5, "air: 1.226 at sea level and 15 deg C"),
                 .interval = true},
                MOORSIM_DEFAULT(WindageSpec{}.air_density)),
    WithDefault(Positive("frontal_area", "m^2", 1e6, "Projected area seen from ahead."),
                MOORSIM_DEFAULT(WindageSpec{}.frontal_area)),
    WithDefault(Positive("lateral_area", "m^2", 1e6, "Projected area seen from the side."),
                MOORSIM_DEFAULT(WindageSpec{}.lateral_area)),
    WithDefault({.name = "lateral_centroid",
                 .unit = "m",
                 .description = "The lateral area's centroid forward of midship, within half "
                                "the windage length."},
                MOORSIM_DEFAULT(WindageSpec{}.lateral_centroid)),
    Positive("length", "m", kMaxBodyCoordinate, "Length of the yaw moment; omitted = hull.length."),
};
constexpr Block kWindage{"Areas above water for the wind load; omitted = the seed FPSO's.",
                         kWindageKeys};

constexpr Key kTurretKeys[] = {
    WithDefault({.name = "bearing",
                 .kind = Kind::kString,
                 .description = "locked (fixed to the hull), free, or friction.",
                 .choices = ChoiceNames<vessel::TurretBearing>(),
                 .choice_noun = ChoiceNoun<vessel::TurretBearing>()},
                MOORSIM_DEFAULT(TurretSpec{}.bearing)),
    Positive("bearing_radius", "m", kMaxBodyCoordinate,
             "friction: lever arm of the friction force; omitted = radius."),
    WithDefault(NonNegative("damping", "N m s/rad", 1e13, "Viscous bearing moment."),
                MOORSIM_DEFAULT(TurretSpec{}.damping)),
    WithDefault(NonNegative("friction_coefficient", "", 1.0,
                            "friction: Coulomb coefficient of the bearing.",
                            "a bearing's friction coefficient is about 0.001-0.1"),
                MOORSIM_DEFAULT(TurretSpec{}.friction_coefficient)),
    WithDefault(Positive("inertia", "kg m^2", 1e12, "Inertia about its axis."),
                MOORSIM_DEFAULT(TurretSpec{}.inertia)),
    Angle("initial_heading_deg",
          "free / friction: the turret's heading at the start; omitted = the hull's.", false),
    {.name = "radius",
     .unit = "m",
     .description = "Turret radius; omitted = the fairleads' largest distance from the centre.",
     .minimum = Above(0.0)},
    WithDefault(
        Positive("slip_rate", "rad/s", 0.1, "friction: regularisation rate of the Coulomb moment.",
                 "the regularisation must be far below the rates a turret turns at"),
        MOORSIM_DEFAULT(TurretSpec{}.slip_rate)),
    WithDefault({.name = "x", .unit = "m", .description = "Turret centre, body frame."},
                MOORSIM_DEFAULT(TurretSpec{}.x)),
    WithDefault({.name = "y", .unit = "m", .description = "Turret centre, body frame."},
                MOORSIM_DEFAULT(TurretSpec{}.y)),
};
constexpr Block kTurret{"The turret that carries the fairleads; omitted = locked at the origin.",
                        kTurretKeys};

constexpr Key kVesselKeys[] = {
    WithDefault({.name = "centre_of_gravity",
                 .kind = Kind::kVector,
                 .unit = "m",
                 .description = "Centre of gravity, body frame.",
                 .minimum = AtLeast(-kMaxBodyCoordinate),
                 .maximum = AtMost(kMaxBodyCoordinate, kVesselPointWhy),
                 .interval = true},
                MOORSIM_DEFAULT(VesselSpec{}.centre_of_gravity)),
    Map("damping", kDamping, "Low-frequency damping."),
    Map("hull", kHull, "Hull particulars for the current load."),
    {.name = "hydrodynamics",
     .kind = Kind::kString,
     .description = "WAMIT output stem (.1 and .hst required; .3 .4 .9 optional), relative to "
                    "this file's folder.",
     .required = true},
    Map("initial_pose", kPose, "Low-frequency start."),
    WithDefault(Positive("length_scale", "m", kMaxBodyCoordinate, "WAMIT ULEN."),
                MOORSIM_DEFAULT(VesselSpec{}.length_scale)),
    WithDefault(Positive("mass", "kg", 1e9, "Mass.",
                         "the largest floating structures displace about 6e8 kg"),
                MOORSIM_DEFAULT(VesselSpec{}.mass)),
    WithDefault({.name = "radii_of_gyration",
                 .kind = Kind::kVector,
                 .unit = "m",
                 .description = "Roll, pitch and yaw radii of gyration about the CG.",
                 .minimum = Above(0.0),
                 .maximum = AtMost(kMaxBodyCoordinate)},
                MOORSIM_DEFAULT(VesselSpec{}.radii_of_gyration)),
    List("thrusters", kThruster, "Thrusters; omitted = the seed layout.", false, 1),
    Map("turret", kTurret, "The turret."),
    Map("windage", kWindage, "Areas for the wind load."),
};
constexpr Block kVessel{"The 6-DOF vessel.", kVesselKeys};

// ---------------------------------------------------------------------------------------
// environment

constexpr Key kWaveTrainKeys[] = {
    Required(NonNegative("amplitude", "m", 30.0, "Elevation amplitude.",
                         "the highest sea states measured")),
    Angle("direction_toward_deg", "Direction it travels TOWARD, from north, clockwise.", true),
    Required(Positive("period", "s", 1e4, "Period 2 pi / omega.", "tides are slower")),
    Angle("phase_deg",
          "Phase phi: the elevation is amplitude cos(omega t - k (x cos(theta) + y sin(theta)) + "
          "phi).",
          true),
};
constexpr Block kWaveTrain{"One regular wave of a given sea.", kWaveTrainKeys};

constexpr Key kWavesKeys[] = {
    WithDefault({.name = "components",
                 .kind = Kind::kInteger,
                 .description = "Frequency components (>= 200 keeps Hs within 2 %).",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(100000.0)},
                MOORSIM_DEFAULT(WavesSpec{}.components)),
    Angle("direction_toward_deg",
          "Mean direction the waves travel TOWARD. Required without trains.", false),
    WithDefault({.name = "gamma",
                 .description = "JONSWAP peak enhancement.",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(10.0),
                 .interval = true},
                MOORSIM_DEFAULT(WavesSpec{}.gamma)),
    Positive("hs", "m", 30.0, "Significant wave height. Required without trains.",
             "the highest sea states measured"),
    WithDefault({.name = "on_lines",
                 .kind = Kind::kBoolean,
                 .description = "The lines see the waves' water velocity and acceleration in "
                                "their drag and inertia (finite-depth Airy); false: only the "
                                "hull feels the waves."},
                MOORSIM_DEFAULT(WavesSpec{}.on_lines)),
    NonNegative("spreading", "", 100.0, "cos-2s spreading exponent s; omitted = long-crested.",
                "s = 75 is narrow swell; omit it for long-crested waves"),
    WithDefault({.name = "stretching",
                 .kind = Kind::kString,
                 .description = "The lines' wave kinematics under a crest: wheeler (stretched "
                                "between the seabed and the instantaneous surface) or none "
                                "(linear theory held constant above the mean surface).",
                 .choices = ChoiceNames<mooring_fem::WaveStretching>(),
                 .choice_noun = ChoiceNoun<mooring_fem::WaveStretching>()},
                MOORSIM_DEFAULT(WavesSpec{}.stretching)),
    {.name = "tp",
     .unit = "s",
     .description = "Peak period. Required without trains.",
     .minimum = AtLeast(1.0),
     .maximum = AtMost(40.0, "wind sea and swell"),
     .interval = true},
    List("trains", kWaveTrain,
         "A given sea, in place of the JONSWAP one (hs, tp, gamma, spreading, components): "
         "regular waves summed as they are, no random draw.",
         false, 1),
};
constexpr Block kWaves{"An irregular JONSWAP sea, or a given one; omitted = calm water.",
                       kWavesKeys};

constexpr Key kWindKeys[] = {
    WithDefault({.name = "components",
                 .kind = Kind::kInteger,
                 .description = "Frequency components of the gust.",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(100000.0)},
                MOORSIM_DEFAULT(WindSpec{}.components)),
    Angle("direction_from_deg", "Where the wind comes FROM (meteorological).", true),
    WithDefault({.name = "gust",
                 .kind = Kind::kBoolean,
                 .description = "NPD (ISO 19901-1) gust spectrum on top of the mean."},
                MOORSIM_DEFAULT(WindSpec{}.gust)),
    Required(NonNegative("speed", "m/s", 80.0, "1-hour mean speed at 10 m.",
                         "above any hurricane's 1-hour mean")),
};
constexpr Block kWind{"Wind; omitted = no wind.", kWindKeys};

constexpr Key kEnvironmentKeys[] = {
    Map("current", kCurrent, "A current (or give it under mooring.current)."),
    WithDefault({.name = "hull_viscous_drag",
                 .kind = Kind::kBoolean,
                 .description = "Quadratic hull drag on the velocity relative to the water."},
                MOORSIM_DEFAULT(EnvironmentSpec{}.hull_viscous_drag)),
    Map("waves", kWaves, "Irregular waves."),
    Map("wind", kWind, "Wind."),
};
constexpr Block kEnvironment{"Waves, wind and current.", kEnvironmentKeys};

// ---------------------------------------------------------------------------------------
// controller

constexpr Key kHeadingLoopKeys[] = {
    Required(Positive("damping_ratio", "", 10.0, "Damping ratio of the heading loop.")),
    Required(Positive("natural_period", "s", 10000.0, "Natural period of the heading loop.")),
};
constexpr Block kHeadingLoop{
    "pi: yaw gains by pole placement on the yaw inertia and damping (replace kp/ki/kd[3]).",
    kHeadingLoopKeys};

constexpr Key kSetpointKeys[] = {
    Angle("heading_deg", "Heading to hold.", true),
    Required(Offset("x", "North position to hold.")),
    Required(Offset("y", "East position to hold.")),
};
constexpr Block kSetpoint{"Position and heading to hold; omitted = the initial pose.",
                          kSetpointKeys};

constexpr Key Gains(std::string_view name, std::string_view description, std::string (*json)()) {
  return {.name = name,
          .kind = Kind::kVector,
          .description = description,
          .minimum = AtLeast(0.0),
          .maximum = AtMost(1e12),
          .default_json = json};
}

constexpr Key kControllerKeys[] = {
    WithDefault(NonNegative("damping_ratio", "", 10.0, "observer_pid: zeta; 0 = its default."),
                MOORSIM_DEFAULT(ControllerSpec{}.damping_ratio)),
    Map("heading", kHeadingLoop, "pi: the heading loop by pole placement."),
    Gains("kd", "pi: derivative gains [N s/m, N s/m, N m s/rad].",
          MOORSIM_DEFAULT(ControllerSpec{}.kd)),
    Gains("ki", "pi: integral gains [N/(m s), N/(m s), N m/(rad s)].",
          MOORSIM_DEFAULT(ControllerSpec{}.ki)),
    Gains("kp", "pi: proportional gains [N/m, N/m, N m/rad].",
          MOORSIM_DEFAULT(ControllerSpec{}.kp)),
    WithDefault(NonNegative("natural_period", "s", 10000.0,
                            "observer_pid: 2 pi / omega_n; 0 = its default."),
                MOORSIM_DEFAULT(ControllerSpec{}.natural_period)),
    WithDefault(Rate("rate_hz", "Sample rate."), MOORSIM_DEFAULT(ControllerSpec{}.rate)),
    Map("setpoint", kSetpoint, "Position and heading to hold."),
    {.name = "type",
     .kind = Kind::kString,
     .description = "none, pi or observer_pid.",
     .required = true,
     .choices = ChoiceNames<vessel::ControllerType>(),
     .choice_noun = ChoiceNoun<vessel::ControllerType>()},
};
constexpr Block kController{"The position-mooring controller.", kControllerKeys};

// ---------------------------------------------------------------------------------------
// sensors

// One noise channel: its unit and the largest sensible size of its values.
constexpr std::array<Key, 6> NoiseKeys(std::string_view unit, std::string_view walk_unit,
                                       double scale, std::string (*std_dev_default)()) {
  return {{
      WithDefault(NonNegative("bias_time_constant", "s", kMaxTime,
                              "Bias time constant; 0 = a random walk."),
                  MOORSIM_DEFAULT(ChannelNoiseSpec{}.bias_time_constant)),
      WithDefault(NonNegative("bias_walk", walk_unit, scale, "Bias random-walk intensity."),
                  MOORSIM_DEFAULT(ChannelNoiseSpec{}.bias_walk)),
      WithDefault({.name = "initial_bias",
                   .unit = unit,
                   .description = "Bias at the start.",
                   .minimum = AtLeast(-scale),
                   .maximum = AtMost(scale),
                   .interval = true},
                  MOORSIM_DEFAULT(ChannelNoiseSpec{}.initial_bias)),
      WithDefault(Probability("outlier_probability", "Chance that a sample is an outlier."),
                  MOORSIM_DEFAULT(ChannelNoiseSpec{}.outlier_probability)),
      WithDefault(NonNegative("outlier_std_dev", unit, scale, "Standard deviation of outliers."),
                  MOORSIM_DEFAULT(ChannelNoiseSpec{}.outlier_std_dev)),
      WithDefault(NonNegative("std_dev", unit, scale, "White-noise standard deviation."),
                  std_dev_default),
  }};
}

constexpr auto kPositionNoiseKeys =
    NoiseKeys("m", "m/sqrt(s)", 1000.0, MOORSIM_DEFAULT(SensorsSpec{}.north.std_dev));
constexpr auto kHeadingNoiseKeys = NoiseKeys("rad", "rad/sqrt(s)", std::numbers::pi,
                                             MOORSIM_DEFAULT(SensorsSpec{}.heading.std_dev));
constexpr auto kTensionNoiseKeys =
    NoiseKeys("N", "N/sqrt(s)", 1e8, MOORSIM_DEFAULT(SensorsSpec{}.tension_noise.std_dev));
constexpr Block kPositionNoise{"Errors of one position channel.", kPositionNoiseKeys};
constexpr Block kHeadingNoise{"Errors of the heading channel.", kHeadingNoiseKeys};
constexpr Block kTensionNoise{"Errors of every load cell.", kTensionNoiseKeys};

// A sensor's faults (`faults:` of gnss, gyro and tension_cells), in the sensor's unit.
struct FaultUnits {
  std::string_view unit;       // m, rad, N
  std::string_view rate_unit;  // m/s, rad/s, N/s
  double largest_offset;
  double largest_rate;
};

constexpr Key FaultEnd() {
  return NonNegative("end", "s", kMaxTime, "When the fault clears; omitted = never.");
}
constexpr Key FaultFactor() {
  return {.name = "factor",
          .description = "degraded: how many times larger the white noise is.",
          .minimum = Above(1.0),
          .maximum = AtMost(1000.0)};
}
constexpr Key FaultGain() {
  return {.name = "gain",
          .description = "gain: the reading is gain x the true value (plus the errors).",
          .minimum = Above(0.0),
          .maximum = AtMost(10.0)};
}
constexpr Key FaultMode() {
  return {.name = "mode",
          .kind = Kind::kString,
          .description =
              "step (reads offset off), stuck (repeats its last reading), degraded "
              "(noise x factor), drift (adds rate x time), dead (no reading; a load "
              "cell reads its noise about zero), gain (reads gain x the truth).",
          .required = true,
          .choices = ChoiceNames<vessel::SensorFault::Mode>(),
          .choice_noun = ChoiceNoun<vessel::SensorFault::Mode>()};
}
constexpr Key FaultOffset(const FaultUnits& u) {
  return {.name = "offset",
          .unit = u.unit,
          .description = "step: how far off the reading jumps; nonzero.",
          .minimum = AtLeast(-u.largest_offset),
          .maximum = AtMost(u.largest_offset),
          .interval = true};
}
constexpr Key FaultRate(const FaultUnits& u) {
  return {.name = "rate",
          .unit = u.rate_unit,
          .description = "drift: the rate; nonzero.",
          .minimum = AtLeast(-u.largest_rate),
          .maximum = AtMost(u.largest_rate),
          .interval = true};
}
constexpr Key FaultTime() {
  return Required(NonNegative("time", "s", kMaxTime, "When the fault starts."));
}

constexpr FaultUnits kPositionFault{"m", "m/s", 1e4, 10.0};
constexpr FaultUnits kHeadingFault{"rad", "rad/s", 2.0 * std::numbers::pi, 1.0};
constexpr FaultUnits kCellFault{"N", "N/s", 1e8, 1e6};

constexpr Key kGnssFaultKeys[] = {
    WithDefault({.name = "channel",
                 .kind = Kind::kString,
                 .description = "The channel that goes wrong: both (the receiver), north or east.",
                 .choices = ChoiceNames<GnssFaultChannel>(),
                 .choice_noun = ChoiceNoun<GnssFaultChannel>()},
                MOORSIM_DEFAULT(SensorsSpec::Fault{}.channel)),
    FaultEnd(),
    FaultFactor(),
    FaultGain(),
    FaultMode(),
    FaultOffset(kPositionFault),
    FaultRate(kPositionFault),
    FaultTime(),
};
constexpr Key kGyroFaultKeys[] = {
    FaultEnd(),
    FaultFactor(),
    FaultGain(),
    FaultMode(),
    FaultOffset(kHeadingFault),
    FaultRate(kHeadingFault),
    FaultTime(),
};
constexpr Key kCellFaultKeys[] = {
    FaultEnd(),
    FaultFactor(),
    FaultGain(),
    {.name = "line",
     .kind = Kind::kInteger,
     .description = "The line whose cell goes wrong.",
     .required = true},
    FaultMode(),
    FaultOffset(kCellFault),
    FaultRate(kCellFault),
    FaultTime(),
};
constexpr Block kGnssFault{"A fault of the position sensor during the run.", kGnssFaultKeys};
constexpr Block kGyroFault{"A fault of the heading sensor during the run.", kGyroFaultKeys};
constexpr Block kCellFaultBlock{"A load cell that goes wrong during the run.", kCellFaultKeys};

constexpr Key kGnssKeys[] = {
    WithDefault(NonNegative("dropout_mean_duration", "s", kMaxTime,
                            "Mean length of a dropout; 0 = one sample."),
                MOORSIM_DEFAULT(SensorsSpec{}.gnss_dropout_mean_duration)),
    WithDefault(
        Probability("dropout_probability", "Chance per sample of a dropout (x and y together)."),
        MOORSIM_DEFAULT(SensorsSpec{}.gnss_dropout_probability)),
    Map("east", kPositionNoise, "East channel."),
    List("faults", kGnssFault, "Faults of the receiver during the run."),
    Map("north", kPositionNoise, "North channel."),
    WithDefault(Rate("rate_hz", "Sample rate."), MOORSIM_DEFAULT(SensorsSpec{}.gnss_rate)),
};
constexpr Block kGnss{"The position sensor.", kGnssKeys};

constexpr Key kGyroKeys[] = {
    WithDefault(Probability("dropout_probability", "Chance per sample of a dropout."),
                MOORSIM_DEFAULT(SensorsSpec{}.gyro_dropout_probability)),
    List("faults", kGyroFault, "Faults of the gyro during the run."),
    Map("heading", kHeadingNoise, "Heading channel."),
    WithDefault(Rate("rate_hz", "Sample rate."), MOORSIM_DEFAULT(SensorsSpec{}.gyro_rate)),
};
constexpr Block kGyro{"The heading sensor.", kGyroKeys};

constexpr Key kTensionCellsKeys[] = {
    List("faults", kCellFaultBlock, "Cells that go wrong during the run."),
    Map("noise", kTensionNoise, "The cells' errors."),
    WithDefault(Rate("rate_hz", "Sample rate."), MOORSIM_DEFAULT(SensorsSpec{}.tension_rate)),
};
constexpr Block kTensionCells{"Fairlead load cells; omitted = none.", kTensionCellsKeys};

constexpr Key kSensorsKeys[] = {
    Map("gnss", kGnss, "Position sensor."),
    Map("gyro", kGyro, "Heading sensor."),
    Map("tension_cells", kTensionCells, "Fairlead load cells."),
};
constexpr Block kSensors{"The sensors the detectors read.", kSensorsKeys};

// ---------------------------------------------------------------------------------------
// failure, detection, detectors, simulation

constexpr Key kFailureKeys[] = {
    {.name = "arc_length",
     .unit = "m",
     .description = "mode node: unstretched length from the anchor (or give node)."},
    {.name = "line",
     .kind = Kind::kInteger,
     .description = "The line that parts (1..N).",
     .required = true},
    WithDefault({.name = "mode",
                 .kind = Kind::kString,
                 .description = "Where the line parts: fairlead, node or anchor.",
                 .choices = ChoiceNames<mooring_fem::FailureMode>(),
                 .choice_noun = ChoiceNoun<mooring_fem::FailureMode>()},
                MOORSIM_DEFAULT(FailureSpec{}.mode)),
    {.name = "node",
     .kind = Kind::kInteger,
     .description = "mode node: node index from the anchor, 1..segments - 1 (or give "
                    "arc_length)."},
    Required(NonNegative("time", "s", kMaxTime, "When it parts; before the end of the run.")),
};
constexpr Block kFailure{"A line that parts; omitted = no failure.", kFailureKeys};

constexpr Key ModelVector(std::string_view name, std::string_view unit,
                          std::string_view description, Bound minimum, double maximum) {
  return {.name = name,
          .kind = Kind::kVector,
          .unit = unit,
          .description = description,
          .minimum = minimum,
          .maximum = AtMost(maximum)};
}

constexpr Key kModelKeys[] = {
    ModelVector("bias_std", "", "Bias force standard deviation per DOF [N, N, N m].", AtLeast(0.0),
                1e12),
    ModelVector("bias_time_constant", "s", "Bias time constant per DOF.", Above(0.0), kMaxTime),
    ModelVector("force_noise", "", "Force noise per DOF [N sqrt(s), N sqrt(s), N m sqrt(s)].",
                AtLeast(0.0), 1e12),
    ModelVector("mooring_damping_ratio", "", "Mooring damping per DOF, fraction of critical.",
                AtLeast(0.0), 10.0),
    ModelVector("wave_motion_std", "", "Wave-frequency motion per DOF [m, m, rad].", AtLeast(0.0),
                1000.0),
};
constexpr Block kModel{"The observers' disturbance model per DOF; omitted = the defaults.",
                       kModelKeys};

constexpr Key kDetectionKeys[] = {
    WithDefault(
        Positive("measurement_variance", "", 1e4, "The observers' R per DOF [m^2, m^2, rad^2]."),
        MOORSIM_DEFAULT(DetectionSpec{}.measurement_variance)),
    Map("model", kModel, "The observers' disturbance model."),
    WithDefault({.name = "observer",
                 .kind = Kind::kString,
                 .description = "ekf (one EKF per hypothesis) or passive (trained).",
                 .choices = ChoiceNames<simulation::ObserverType>(),
                 .choice_noun = ChoiceNoun<simulation::ObserverType>()},
                MOORSIM_DEFAULT(DetectionSpec{}.observer)),
    WithDefault({.name = "pairs",
                 .kind = Kind::kBoolean,
                 .description = "Also every pair of failed lines."},
                MOORSIM_DEFAULT(DetectionSpec{}.pairs)),
    {.name = "sensor_checks",
     .kind = Kind::kBoolean,
     .description = "ekf: withhold frozen and jumping sensor readings, weight noisy ones "
                    "less, and name the sensor; default: on with a fused detector."},
    NonNegative("switch_rate", "1/s", kMaxRate, "ekf: IMM mixing rate; 0 = independent filters."),
    WithDefault({.name = "training_seed",
                 .kind = Kind::kCount,
                 .description = "passive: seed of the training runs."},
                MOORSIM_DEFAULT(DetectionSpec{}.training_seed)),
};
constexpr Block kDetection{"How the hypothesis bank and its observers are built.", kDetectionKeys};

constexpr Key kDetectorKeys[] = {
    {.name = "label",
     .kind = Kind::kString,
     .description = "Unique name in the outputs; default: the type."},
    {.name = "plugin",
     .kind = Kind::kString,
     .description = "Shared library that provides the type, relative to this file's folder."},
    {.name = "type",
     .kind = Kind::kString,
     .description = "Detector type (dht, mle, glr, deficit, or a plugin's).",
     .required = true},
};
constexpr Block kDetector{
    "One detector: its type and its parameters (numbers; `moorsim run --help` lists them).",
    kDetectorKeys, true};

constexpr Key kSimulationKeys[] = {
    WithDefault(Positive("duration", "s", kMaxTime, "Simulated time.", "116 days"),
                MOORSIM_DEFAULT(SimulationSpec{}.duration)),
    WithDefault(Rate("output_rate_hz", "run.h5 rows per second."),
                MOORSIM_DEFAULT(SimulationSpec{}.output_rate)),
    WithDefault({.name = "seed",
                 .kind = Kind::kCount,
                 .description = "Run seed: every random stream derives from it."},
                MOORSIM_DEFAULT(SimulationSpec{}.seed)),
    WithDefault(NonNegative("statistics_from", "s", kMaxTime,
                            "Where the design record's statistics (the lines' extremes and "
                            "fatigue damage, the vessel's largest offset) start: what comes "
                            "before (a line removed at 0 s, the vessel settling) is left out. "
                            "Before the end of the run.",
                            "116 days"),
                MOORSIM_DEFAULT(SimulationSpec{}.statistics_from)),
};
constexpr Block kSimulation{"Run length, output rate and seed.", kSimulationKeys};

constexpr Key kScenarioKeys[] = {
    {.name = "base",
     .kind = Kind::kString,
     .description = "A scenario this one starts from (relative to this file's folder); the "
                    "keys here override its keys: maps merged key by key, lists and values "
                    "replaced whole, a key set to null (~) removed. Its name is not taken."},
    Map("controller", kController, "The position-mooring controller."),
    Map("detection", kDetection, "The hypothesis bank."),
    {.name = "detectors",
     .kind = Kind::kList,
     .description = "Detectors run side by side; default: [fused] with tension cells, else none.",
     .block = &kDetector},
    Map("environment", kEnvironment, "Waves, wind and current."),
    Map("failure", kFailure, "A line that parts."),
    Map("mooring", kMooring, "The mooring.", true),
    {.name = "name",
     .kind = Kind::kString,
     .description = "Scenario name; default: the file name without extension."},
    Map("sensors", kSensors, "The sensors."),
    Map("simulation", kSimulation, "Run length, output rate and seed."),
    Map("solver", kSolver, "Integrator settings."),
    Map("vessel", kVessel, "The vessel (needed by run, controller, sensors, failure)."),
};
constexpr Block kScenario{"A moorsim scenario.", kScenarioKeys};

// ---------------------------------------------------------------------------------------
// campaign

constexpr Key kRangeKeys[] = {
    {.name = "from", .description = "First value.", .required = true},
    {.name = "step", .description = "Step.", .required = true, .minimum = Above(0.0)},
    {.name = "to", .description = "Last value (inclusive, within rounding).", .required = true},
};
constexpr Block kRange{"Evenly spaced values from `from` to `to`.", kRangeKeys};

constexpr Key kNormalKeys[] = {
    {.name = "max", .description = "Upper end of the window (draws beyond are repeated)."},
    {.name = "mean", .description = "Mean.", .required = true},
    {.name = "min", .description = "Lower end of the window."},
    {.name = "std_dev",
     .description = "Standard deviation.",
     .required = true,
     .minimum = Above(0.0)},
};
constexpr Block kNormal{"A normal draw per run, optionally within [min, max].", kNormalKeys};

constexpr Key kFactorKeys[] = {
    {.name = "add",
     .kind = Kind::kValue,
     .description = "follows: a number, or [low, high] for a uniform draw, added."},
    {.name = "choice",
     .kind = Kind::kList,
     .description = "A value drawn per run from these.",
     .item = Kind::kValue,
     .min_items = 1},
    {.name = "follows",
     .kind = Kind::kString,
     .description = "The key of a factor listed above it whose value this one takes."},
    {.name = "function",
     .kind = Kind::kString,
     .description = "follows: cos or sin of the followed value in degrees, before adding.",
     .choices = ChoiceNames<CampaignFactor::Function>(),
     .choice_noun = ChoiceNoun<CampaignFactor::Function>()},
    {.name = "key",
     .kind = Kind::kString,
     .description = "The scenario key path to vary.",
     .required = true},
    {.name = "modulo",
     .description = "follows: reduce the result to [-modulo/2, modulo/2).",
     .minimum = Above(0.0)},
    {.name = "normal",
     .kind = Kind::kMap,
     .description = "A normal draw per run.",
     .block = &kNormal},
    {.name = "range", .kind = Kind::kMap, .description = "Evenly spaced values.", .block = &kRange},
    {.name = "scale", .description = "follows with function: the factor s of s cos(v)."},
    {.name = "uniform",
     .kind = Kind::kList,
     .description = "[low, high]: a uniform draw per run.",
     .item = Kind::kNumber,
     .min_items = 2,
     .max_items = 2},
    {.name = "values",
     .kind = Kind::kList,
     .description = "The values, in order.",
     .item = Kind::kValue,
     .min_items = 1},
};
constexpr Block kFactor{"One varied key and how its values come.", kFactorKeys};

constexpr Key kSeedRangeKeys[] = {
    {.name = "from", .kind = Kind::kCount, .description = "First seed.", .required = true},
    {.name = "to", .kind = Kind::kCount, .description = "Last seed (inclusive).", .required = true},
};
constexpr Block kSeedRange{"These seeds, from `from` to `to`.", kSeedRangeKeys};

constexpr Key kBlockDesignKeys[] = {
    WithDefault({.name = "condition",
                 .kind = Kind::kString,
                 .description = "The condition the block's storms test: intact, damaged (a "
                                "line removed before the storm: its failure at 0 s and "
                                "simulation.statistics_from after the vessel settles) or "
                                "transient (a line parting during the storm).",
                 .choices = ChoiceNames<analysis::DesignCondition>(),
                 .choice_noun = ChoiceNoun<analysis::DesignCondition>()},
                MOORSIM_DEFAULT(CampaignBlock::Design{}.condition)),
    {.name = "intact",
     .kind = Kind::kString,
     .description = "transient: the intact block whose runs give the instants: each run "
                    "parts its failure.line at the time of that line's largest top tension in "
                    "the intact block's run of the same seed and factor values (explicit "
                    "seeds in both blocks). Omitted: the failure.time the runs are given."},
    WithDefault({.name = "method",
                 .kind = Kind::kString,
                 .description = "How the extremes are estimated: gumbel (the maxima of the "
                                "point's seeds, one storm each) or weibull (the peaks of one "
                                "long run per point, scaled to the campaign's storm_duration).",
                 .choices = ChoiceNames<analysis::ExtremesMethod>(),
                 .choice_noun = ChoiceNoun<analysis::ExtremesMethod>()},
                MOORSIM_DEFAULT(CampaignBlock::Design{}.method)),
    {.name = "probability",
     .description = "A fatigue sea state: the share of the time it holds (the scatter "
                    "diagram's), in (0, 1]. The blocks with one give the fatigue life.",
     .minimum = Above(0.0),
     .maximum = AtMost(1.0),
     .interval = true},
};
constexpr Block kBlockDesign{"The block's part in the design checks.", kBlockDesignKeys};

constexpr Key kCampaignBlockKeys[] = {
    {.name = "combine",
     .kind = Kind::kString,
     .description = "grid (every combination, the first factor slowest) or zip (the i-th "
                    "value of each).",
     .choices = ChoiceNames<CampaignBlock::Combine>(),
     .choice_noun = ChoiceNoun<CampaignBlock::Combine>()},
    Map("design", kBlockDesign,
        "The block's part in the design checks (with the campaign's `design`); omitted: none."),
    {.name = "factors",
     .kind = Kind::kList,
     .description = "The keys varied in this block.",
     .block = &kFactor},
    {.name = "name",
     .kind = Kind::kString,
     .description = "Unique block name: letters, digits, _ and -.",
     .required = true},
    {.name = "seeds",
     .kind = Kind::kValue,
     .description = "Per point: a count, or {from: A, to: B} for these seeds.",
     .required = true,
     .block = &kSeedRange},
    {.name = "set", .kind = Kind::kValueMap, .description = "Overrides for this block."},
};
constexpr Block kCampaignBlock{"A block of runs.", kCampaignBlockKeys};

constexpr Key kCampaignDesignKeys[] = {
    WithDefault({.name = "confidence",
                 .description = "Of the statistics' intervals.",
                 .minimum = Above(0.5),
                 .maximum = Below(1.0),
                 .interval = true},
                MOORSIM_DEFAULT(CampaignDesign{}.confidence)),
    WithDefault({.name = "consequence_class",
                 .kind = Kind::kInteger,
                 .description = "dnv_os_e301's consequence class, 1 or 2.",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(2.0),
                 .interval = true},
                MOORSIM_DEFAULT(CampaignDesign{}.consequence_class)),
    WithDefault({.name = "fatigue_factor",
                 .description = "The fatigue life must be at least service_life times this "
                                "(DNV-OS-E301's design fatigue factor, API RP 2SK's factor of "
                                "safety on the life).",
                 .minimum = AtLeast(1.0),
                 .maximum = AtMost(100.0)},
                MOORSIM_DEFAULT(CampaignDesign{}.fatigue_factor)),
    Positive("offset_limit", "m", kMaxDepth,
             "The vessel's largest allowed offset from its initial pose (the risers' "
             "limit); omitted: the offsets are reported, not checked.",
             "the deepest ocean is 11 km"),
    WithDefault({.name = "quantile",
                 .description = "A storm maximum's quantile reported beside the MPM.",
                 .minimum = Above(0.0),
                 .maximum = Below(1.0),
                 .interval = true},
                MOORSIM_DEFAULT(CampaignDesign{}.quantile)),
    WithDefault(Positive("service_life", "years", 200.0, "The mooring's service life."),
                MOORSIM_DEFAULT(CampaignDesign{}.service_life)),
    WithDefault({.name = "standard",
                 .kind = Kind::kString,
                 .description = "api_rp_2sk (the MPM against the breaking load over 1.67 "
                                "intact, 1.25 damaged, 1.05 transient) or dnv_os_e301 "
                                "(partial factors on the mean and dynamic tension against "
                                "0.95 of the breaking load; ULS intact, ALS damaged and "
                                "transient).",
                 .choices = ChoiceNames<analysis::DesignStandard>(),
                 .choice_noun = ChoiceNoun<analysis::DesignStandard>()},
                MOORSIM_DEFAULT(CampaignDesign{}.standard)),
    WithDefault(Positive("storm_duration", "s", 1.0e6,
                         "The storm a weibull block's maxima are of (its runs may be longer)."),
                MOORSIM_DEFAULT(CampaignDesign{}.storm_duration)),
};
constexpr Block kCampaignDesign{
    "The design checks from the blocks' runs: the standard and its settings.", kCampaignDesignKeys};

constexpr Key kCampaignKeys[] = {
    {.name = "blocks",
     .kind = Kind::kList,
     .description = "The blocks of runs.",
     .required = true,
     .block = &kCampaignBlock,
     .min_items = 1},
    Map("design", kCampaignDesign,
        "The design checks (extreme tensions, safety factors, offsets, fatigue) from the "
        "blocks with a `design`; omitted: none."),
    {.name = "name",
     .kind = Kind::kString,
     .description = "Campaign name; default: the file name without extension."},
    {.name = "scenario",
     .kind = Kind::kString,
     .description = "The base scenario, relative to this file's folder.",
     .required = true},
    {.name = "seed", .kind = Kind::kCount, .description = "The campaign seed.", .required = true},
    {.name = "set",
     .kind = Kind::kValueMap,
     .description = "Overrides for every run: scenario key paths and values."},
};
constexpr Block kCampaign{"A moorsim campaign.", kCampaignKeys};

#undef MOORSIM_DEFAULT

// ---------------------------------------------------------------------------------------
// JSON Schema.

using nlohmann::ordered_json;

std::string Described(const Key& key) {
  std::string text(key.description);
  if (!key.unit.empty()) text += " [" + std::string(key.unit) + "]";
  return text;
}

void AddBounds(const Key& key, ordered_json& out) {
  if (key.minimum)
    out[key.minimum->exclusive ? "exclusiveMinimum" : "minimum"] = key.minimum->value;
  if (key.maximum)
    out[key.maximum->exclusive ? "exclusiveMaximum" : "maximum"] = key.maximum->value;
}

ordered_json BlockSchema(const Block& block, bool required);

ordered_json ScalarSchema(Kind kind) {
  switch (kind) {
    case Kind::kNumber:
      return {{"type", "number"}};
    case Kind::kInteger:
      return {{"type", "integer"}};
    case Kind::kCount:
      return {{"type", "integer"}, {"minimum", 0}};
    case Kind::kBoolean:
      return {{"type", "boolean"}};
    case Kind::kString:
      return {{"type", "string"}};
    default:
      return ordered_json::object();
  }
}

ordered_json KeySchema(const Key& key, bool required) {
  ordered_json out;
  out["description"] = Described(key);
  switch (key.kind) {
    case Kind::kMap:
      out.update(BlockSchema(*key.block, required));
      out["description"] = Described(key);
      break;
    case Kind::kList: {
      out["type"] = "array";
      out["items"] = key.block ? BlockSchema(*key.block, required) : ScalarSchema(key.item);
      if (key.min_items > 0) out["minItems"] = key.min_items;
      if (key.max_items > 0) out["maxItems"] = key.max_items;
      break;
    }
    case Kind::kVector: {
      out["type"] = "array";
      ordered_json item = {{"type", "number"}};
      AddBounds(key, item);
      out["items"] = item;
      out["minItems"] = 3;
      out["maxItems"] = 3;
      break;
    }
    case Kind::kValueMap:
      out["type"] = "object";
      break;
    case Kind::kValue:
      // Any value; one with a block is a count or that map (a campaign block's seeds).
      if (key.block) {
        out["anyOf"] = {{{"type", "integer"}, {"minimum", 1}}, BlockSchema(*key.block, required)};
      }
      break;
    default:
      out.update(ScalarSchema(key.kind));
      AddBounds(key, out);
      break;
  }
  if (!key.choices.empty())
    out["enum"] = std::vector<std::string>(key.choices.begin(), key.choices.end());
  if (key.default_json) out["default"] = ordered_json::parse(key.default_json());
  return out;
}

// `required`: list each block's required keys (a whole file); not in a file that starts
// from a base, where any key may come from the base.
ordered_json BlockSchema(const Block& block, bool required) {
  ordered_json out;
  out["type"] = "object";
  out["description"] = block.description;
  ordered_json properties = ordered_json::object();
  std::vector<std::string> names;
  for (const Key& key : block.keys) {
    properties[std::string(key.name)] = KeySchema(key, required);
    if (key.required) names.emplace_back(key.name);
  }
  out["properties"] = properties;
  if (required && !names.empty()) out["required"] = names;
  out["additionalProperties"] =
      block.open_numbers ? ordered_json({{"type", "number"}}) : ordered_json(false);
  return out;
}

std::string KindName(const Key& key) {
  switch (key.kind) {
    case Kind::kNumber:
      return "number";
    case Kind::kInteger:
      return "integer";
    case Kind::kCount:
      return "integer >= 0";
    case Kind::kBoolean:
      return "true/false";
    case Kind::kString:
      return key.choices.empty() ? "text" : "choice";
    case Kind::kVector:
      return "[x, y, z]";
    case Kind::kMap:
      return "map";
    case Kind::kList:
      return key.block ? "list of maps" : "list";
    case Kind::kValue:
      return "value";
    case Kind::kValueMap:
      return "map of values";
  }
  return "";
}

std::string RangeText(const Key& key) {
  if (!key.choices.empty()) {
    std::string text;
    for (std::string_view choice : key.choices)
      text += (text.empty() ? "" : ", ") + std::string(choice);
    return text;
  }
  if (!key.minimum && !key.maximum) return "";
  const auto number = [&](double v) {
    return key.kind == Kind::kInteger ? std::to_string(static_cast<long long>(v)) : FormatNumber(v);
  };
  std::string text = key.minimum ? (key.minimum->exclusive ? "(" : "[") + number(key.minimum->value)
                                 : std::string("(-inf");
  text += ", ";
  text += key.maximum ? number(key.maximum->value) + (key.maximum->exclusive ? ")" : "]")
                      : std::string("inf)");
  for (const std::optional<Bound>& bound : {key.minimum, key.maximum}) {
    if (bound && !bound->why.empty()) text += " (" + std::string(bound->why) + ")";
  }
  return text;
}

void MarkdownRows(const Block& block, const std::string& path, std::string& out) {
  for (const Key& key : block.keys) {
    const std::string here = (path.empty() ? "" : path + ".") + std::string(key.name);
    std::string description(key.description);
    for (char& c : description) {
      if (c == '|') c = '/';
    }
    out += "| `" + here + "`" + (key.required ? " (required)" : "") + " | " + KindName(key) +
           " | " + std::string(key.unit) + " | " + RangeText(key) + " | " +
           (key.default_json ? "`" + key.default_json() + "`" : "") + " | " + description + " |\n";
    if (key.block != nullptr) {
      MarkdownRows(*key.block, here + (key.kind == Kind::kList ? "[]" : ""), out);
    }
  }
}

}  // namespace

std::string MarkdownTable(const Block& root) {
  std::string out =
      "| key | kind | unit | range | default | what it is |\n|---|---|---|---|---|---|\n";
  MarkdownRows(root, "", out);
  return out;
}

const Key* Block::Find(std::string_view name) const {
  for (const Key& key : keys) {
    if (key.name == name) return &key;
  }
  return nullptr;
}

const Block& Scenario() { return kScenario; }
const Block& Campaign() { return kCampaign; }

std::string JsonSchema(const Block& root, std::string_view title) {
  ordered_json out;
  out["$schema"] = "http://json-schema.org/draft-07/schema#";
  out["title"] = title;
  if (root.Find("base") == nullptr) {
    out.update(BlockSchema(root, true));
  } else {
    // A file with a base may leave out any key (the base gives it): required keys only
    // without one.
    out["description"] = root.description;
    out["if"] = {{"required", {"base"}}};
    out["then"] = {{"$ref", "#/definitions/override"}};
    out["else"] = {{"$ref", "#/definitions/whole"}};
    out["definitions"] = {{"whole", BlockSchema(root, true)},
                          {"override", BlockSchema(root, false)}};
  }
  return out.dump(2) + "\n";
}

int EditDistance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

std::string NearestKey(const Block& block, std::string_view name) {
  // A unit suffix left out: "direction" for "direction_deg", "rate" for "rate_hz".
  std::string extended;
  int extensions = 0;
  for (const Key& key : block.keys) {
    if (key.name.size() > name.size() + 1 && key.name.substr(0, name.size()) == name &&
        key.name[name.size()] == '_') {
      extended = key.name;
      ++extensions;
    }
  }
  if (extensions == 1) return extended;
  // A misspelling: at most a third of the word changed (one edit for short words, two from
  // six letters), and one candidate closer than the rest.
  const int allowed = std::max(1, static_cast<int>(name.size()) / 3);
  std::string best;
  int best_distance = allowed + 1;
  bool tie = false;
  for (const Key& key : block.keys) {
    const int distance = EditDistance(name, key.name);
    if (distance < best_distance) {
      best = key.name;
      best_distance = distance;
      tie = false;
    } else if (distance == best_distance) {
      tie = true;
    }
  }
  return best_distance <= allowed && !tie ? best : "";
}

}  // namespace moorsim::scenarios::schema
