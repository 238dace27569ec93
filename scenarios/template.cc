#include "scenarios/template.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"

namespace moorsim::scenarios {

const std::vector<TemplateKind> kTemplateKinds = {
    {"spread", "fairleads fixed to the hull on a 22 m circle (half the beam), no turret", 22.0,
     false, 0.5},
    {"turret", "fairleads on a 20 m turret at the reference point, free on its bearing", 20.0, true,
     0.0},
};

namespace {

constexpr double kMaxDepth = 12000.0;   // the loader's range: the deepest ocean is 11 km
constexpr double kMaxLength = 20000.0;  // the loader's range for a line's length

/// The seed chain of the library scenarios (Ren & Skjetne 2016; the seabed friction typical
/// chain-on-clay values in the style of DNV-RP-E301).
mooring_fem::LineType SeedChain() {
  mooring_fem::LineType chain;
  chain.name = "chain_seed";
  chain.diameter = 0.08;
  chain.mass_per_length = 275.0;
  chain.axial_stiffness = 2.28785e8;
  chain.axial_damping_ratio = 0.5;
  chain.drag_normal = 0.3;
  chain.drag_tangential = 1.0;
  chain.added_mass_normal = 1.5;
  chain.friction_axial = 0.5;
  chain.friction_lateral = 1.0;
  return chain;
}

/// The seed chain as the catenary and the FEM see it (submerged weight from the water).
mooring_fem::SectionProperties SeedLine(double depth, double length) {
  mooring_fem::MooringParameters spec;
  spec.water.depth = depth;  // sea water and gravity: the Water defaults
  spec.line_types = {SeedChain()};
  const auto line = mooring_fem::LineParameters::Uniform(1, spec.line_types.front().name, length, 1,
                                                         Vec3::Zero(), Vec3::Zero());
  return mooring_fem::MakeLineProperties(spec, line).sections.front();
}

/// Shortest text that reads back as the same double ("2250", "14.142135623730951"), large
/// numbers in scientific notation ("2.28785e+08").
std::string Number(double value) {
  char buffer[64];
  const auto result = std::abs(value) >= 1e6 ? std::to_chars(buffer, buffer + sizeof buffer, value,
                                                             std::chars_format::scientific)
                                             : std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string Kilonewtons(double newtons) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.1f kN", newtons / 1e3);
  return buffer;
}

std::string Metres(double metres) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.1f m", metres);
  return buffer;
}

/// Rounded toward zero to the micrometre: a fairlead never leaves its circle.
double TruncateToMicrometre(double metres) { return std::trunc(metres * 1e6) / 1e6; }

}  // namespace

const TemplateKind& FindTemplateKind(const std::string& name) {
  for (const TemplateKind& kind : kTemplateKinds) {
    if (kind.name == name) return kind;
  }
  std::string known;
  for (const TemplateKind& kind : kTemplateKinds) {
    known += (known.empty() ? "" : ", ") + std::string(kind.name);
  }
  throw InputError("kind: unknown mooring kind '" + name + "' (known: " + known + ")");
}

TemplateLayout PlanTemplate(const TemplateRequest& request) {
  const TemplateKind& kind = FindTemplateKind(request.kind);
  const int n = request.lines;
  if (n < 3) {
    throw InputError("--lines: " + std::to_string(n) +
                     " must be >= 3 (fewer lines cannot hold the vessel in every direction)");
  }
  if (n > kMaxTemplateLines) {
    throw InputError("--lines: " + std::to_string(n) +
                     " must be <= " + std::to_string(kMaxTemplateLines) +
                     " (moorings in service have at most a few dozen lines)");
  }
  const double depth = request.depth;
  if (!(depth > 0.0)) throw InputError("--depth: " + Number(depth) + " m must be > 0");
  if (!(depth > kTemplateFairleadDepth)) {
    throw InputError("--depth: " + Number(depth) + " m must be deeper than the fairleads, " +
                     Number(kTemplateFairleadDepth) + " m down at the FPSO's draught");
  }
  if (depth > kMaxDepth) {
    throw InputError("--depth: " + Number(depth) + " m must be <= " + Number(kMaxDepth) +
                     " (the deepest ocean is 11 km)");
  }
  const double length = request.length;
  if (!(length > 0.0) || length > kMaxLength) {
    throw InputError("--length: " + Number(length) + " m must be in (0, " + Number(kMaxLength) +
                     "] m");
  }
  if (request.pretension.has_value() == request.radius.has_value()) {
    throw InputError(std::string("--pretension, --radius: give exactly one of them (") +
                     (request.pretension ? "both" : "neither") + " given)");
  }

  const mooring_fem::SectionProperties seed = SeedLine(depth, length);
  const mooring_fem::CatenaryLineProperties line{seed.length, seed.weight_per_length,
                                                 seed.axial_stiffness};
  const double height = depth - kTemplateFairleadDepth;
  mooring_fem::TouchdownRange range;
  try {
    range = mooring_fem::SolveTouchdownRange(line, height);
  } catch (const Error& e) {
    throw InputError("--length: " + Number(length) + " m in " + Number(depth) +
                     " m of water: " + e.what());
  }
  const double radius_offset = kind.fairlead_radius;  // radial lines
  TemplateLayout layout;
  // The loader takes no line shorter than its straight anchor-fairlead distance, stretched
  // or not; a short line in deep water is pulled straight before it lifts off.
  std::string upper_limit =
      "the whole line is lifted off the seabed and pulls its anchor up (a drag anchor holds no "
      "uplift)";
  layout.max_pretension_limit = "the whole line lifted off the seabed";
  // (Less a micrometre per kilometre, which the loader's own arithmetic may need.)
  const double straight_span = std::sqrt(length * length - height * height) * (1.0 - 1e-9);
  if (straight_span < range.max_span) {
    range.max_span = straight_span;
    range.max_tension = mooring_fem::SolveCatenary(line, straight_span, height).fairlead_tension;
    upper_limit =
        "the line is pulled straight: its anchor as far from its fairlead as it is long "
        "(unstretched)";
    layout.max_pretension_limit = "the line pulled straight";
  }

  layout.min_pretension = range.min_tension;
  layout.max_pretension = range.max_tension;
  if (request.pretension) {
    const double t = *request.pretension;
    if (!(t > range.min_tension)) {
      throw InputError("--pretension: " + Number(t) + " N is not above " +
                       Kilonewtons(range.min_tension) +
                       ", the weight in water of the line hanging straight down from the "
                       "fairlead to the seabed (a line touching down pulls more)");
    }
    if (t > range.max_tension) {
      throw InputError("--pretension: " + Number(t) + " N is above " +
                       Kilonewtons(range.max_tension) + ", where " + upper_limit);
    }
    layout.span = t == range.max_tension ? range.max_span
                                         : mooring_fem::SpanForFairleadTension(line, height, t);
  } else {
    const double r = *request.radius;
    const double span = r - radius_offset;
    if (!(span > range.min_span)) {
      throw InputError("--radius: " + Number(r) +
                       " m is too small: the anchors must be more than " +
                       Metres(range.min_span + radius_offset) +
                       " from the reference point, or the line lies slack on the seabed (no "
                       "horizontal tension)");
    }
    if (span > range.max_span) {
      throw InputError("--radius: " + Number(r) + " m is too large: beyond " +
                       Metres(range.max_span + radius_offset) + " from the reference point " +
                       upper_limit);
    }
    layout.span = span;
  }
  layout.anchor_radius = layout.span + radius_offset;
  layout.pretension = mooring_fem::SolveCatenary(line, layout.span, height).fairlead_tension;

  for (int k = 0; k < n; ++k) {
    TemplateLine l;
    l.bearing_deg = (k + kind.bearing_offset_steps) * 360.0 / n;
    const double angle = l.bearing_deg * std::numbers::pi / 180.0;
    // cos(90 deg) = 6e-17 would be written as an anchor 1e-13 m off the axis.
    const auto exact = [](double v) { return std::abs(v) < 1e-15 ? 0.0 : v; };
    const Vec3 ray(exact(std::cos(angle)), exact(std::sin(angle)), 0.0);
    l.fairlead_body = {TruncateToMicrometre(kind.fairlead_radius * ray.x()),
                       TruncateToMicrometre(kind.fairlead_radius * ray.y()),
                       kTemplateFairleadDepth};
    l.anchor = {layout.anchor_radius * ray.x(), layout.anchor_radius * ray.y(), depth};
    layout.lines.push_back(l);
  }
  return layout;
}

std::string WriteTemplate(const TemplateRequest& request, const TemplateLayout& layout,
                          const std::string& command) {
  const TemplateKind& kind = FindTemplateKind(request.kind);
  const bool turret = kind.turret;
  const int n = static_cast<int>(layout.lines.size());
  std::ostringstream y;
  y << "# yaml-language-server: $schema=moorsim.schema.json\n"
       "# (`moorsim schema > moorsim.schema.json` writes that schema next to this file, for\n"
       "# editors that check and complete scenarios as they are typed.)\n"
       "#\n"
       "# A starting scenario to edit, written by\n"
       "#   "
    << command
    << "\n"
       "# The seed FPSO (docs/design.md section 9), "
    << (turret ? "turret-moored" : "spread-moored") << ", on " << n
    << " identical chain lines in\n# " << Number(request.depth)
    << " m of water, their bearings evenly spread, every anchor placed on the elastic\n"
       "# catenary (seabed contact, stretch, the chain's weight in water) so that every line\n"
       "# has the same pretension. SI units throughout; Earth frame NED (x north, y east,\n"
       "# z down), body frame x forward, y starboard, z down. Lines are numbered from 1.\n"
       "name: "
    << request.kind << "_" << n << "_lines\n\n";

  const mooring_fem::Water water;  // sea water
  const mooring_fem::LineType chain = SeedChain();
  const mooring_fem::SectionProperties seed = SeedLine(request.depth, request.length);
  // "      key: value" with its comment from column 37, as in the library files.
  const auto field = [&y](const std::string& key, const std::string& value,
                          const std::string& comment) {
    const std::string text = "      " + key + ": " + value;
    y << text;
    if (!comment.empty()) {
      y << std::string(std::max<std::size_t>(1, 36 - text.size()), ' ') << "# " << comment;
    }
    y << "\n";
  };
  y << "mooring:\n"
       "  # Sea water density [kg/m^3], gravity [m/s^2], flat seabed at depth [m].\n"
       "  water: {density: "
    << Number(water.density) << ", gravity: " << Number(water.gravity)
    << ", depth: " << Number(request.depth)
    << "}\n\n"
       "  # Penalty contact with the seabed: stiffness [N/m^3] and damping [N s/m^3] per unit of\n"
       "  # contact area, the penetration [m] over which the stiffness ramps up, and the speed\n"
       "  # [m/s] below which Coulomb friction is regularised (the loader's defaults).\n"
       "  seabed: {stiffness: 3.0e6, damping: 3.0e5, contact_smoothing: 0.5, friction_velocity: "
       "0.1}\n\n"
       "  # No current; add one as in scenarios/README.md (current: direction_deg, profile).\n\n"
       "  line_types:\n"
       "    - name: "
    << chain.name << "\n";
  field("diameter", Number(chain.diameter), "nominal diameter [m]");
  field("mass_per_length", Number(chain.mass_per_length),
        "dry mass [kg/m]; submerged weight " +
            Number(std::round(seed.weight_per_length * 10.0) / 10.0) + " N/m");
  field("axial_stiffness", Number(chain.axial_stiffness), "EA [N] (Ren & Skjetne 2016)");
  field("axial_damping_ratio", Number(chain.axial_damping_ratio.value()),
        "fraction of a segment's critical axial damping [-]");
  field("drag_normal", Number(chain.drag_normal), "C_DN [-] (Ren & Skjetne 2016)");
  field("drag_tangential", Number(chain.drag_tangential), "C_DT [-] (Ren & Skjetne 2016)");
  field("added_mass_normal", Number(chain.added_mass_normal), "C_MN [-]");
  y << "      # Seabed Coulomb friction [-]: typical chain-on-clay values in the style of\n"
       "      # DNV-RP-E301 (sliding along the chain easier than across it).\n";
  field("friction_axial", Number(chain.friction_axial), "");
  field("friction_lateral", Number(chain.friction_lateral), "");
  y << "\n  defaults: {segments: 50}          # equal segments per line (README.md: "
       "convergence)\n\n";

  const double height = request.depth - kTemplateFairleadDepth;
  y << "  # Every line: " << Number(request.length) << " m unstretched, its fairlead "
    << Number(height)
    << " m above the seabed,\n"
       "  # its anchor "
    << Metres(layout.span) << " from the fairlead horizontally, " << Metres(layout.anchor_radius)
    << " from the reference point.\n"
       "  # Pretension: "
    << Kilonewtons(layout.pretension)
    << " at the fairlead by the elastic catenary (Irvine 1981), within\n"
       "  # the touchdown range "
    << Kilonewtons(layout.min_pretension) << " (slack) to " << Kilonewtons(layout.max_pretension)
    << " (" << layout.max_pretension_limit
    << ");\n"
       "  # `moorsim static` gives the FEM's at rest.\n";
  if (turret) {
    y << "  # Fairleads: body frame [m] on a 20 m-radius turret at the reference point, 12 m\n"
         "  # deep (the draught), each on the ray toward its own anchor at heading 0;\n"
         "  # line k toward (k - 1) 360/"
      << n << " deg.\n";
  } else {
    y << "  # Fairleads: body frame [m] fixed to the hull on the 22 m circle (half the beam)\n"
         "  # round the reference point, 12 m deep (the draught);\n"
         "  # line k toward (k - 1/2) 360/"
      << n
      << " deg, so that no line runs straight ahead. Each line is\n"
         "  # radial: equal pretension then puts no yaw moment on the hull. (A spread mooring\n"
         "  # usually groups its fairleads at the bow and the stern: any point of the hull's\n"
         "  # waterplane, |x| <= 100 m, |y| <= 22 m, will do; one circle keeps one pretension\n"
         "  # for one anchor radius.)\n";
  }
  y << "  # Anchors: Earth frame [m] on the seabed (z = depth), with the vessel at the origin,\n"
       "  # heading 0 (north).\n"
       "  lines:\n";
  for (int k = 0; k < n; ++k) {
    const TemplateLine& l = layout.lines[k];
    const std::string id = "    - id: " + std::to_string(k + 1);
    y << id << std::string(std::max<std::size_t>(1, 36 - id.size()), ' ') << "# toward "
      << Number(std::round(l.bearing_deg * 1e3) / 1e3) << " deg\n"
      << "      type: chain_seed\n"
      << "      anchor: [" << Number(l.anchor.x()) << ", " << Number(l.anchor.y()) << ", "
      << Number(l.anchor.z()) << "]\n"
      << "      fairlead: [" << Number(l.fairlead_body.x()) << ", " << Number(l.fairlead_body.y())
      << ", " << Number(l.fairlead_body.z()) << "]\n"
      << "      length: " << Number(request.length) << "\n";
  }

  y << "\n"
       "# CVODE BDF settings (the SolverSpec defaults, written out).\n"
       "solver:\n"
       "  rtol: 1.0e-4\n"
       "  atol_position: 1.0e-3             # [m]\n"
       "  atol_velocity: 1.0e-3             # [m/s]\n"
       "  max_order: 2\n"
       "  stability_limit_detection: false\n"
       "  max_step: 0                       # [s], 0 = no limit\n\n"
       "# --- coupled simulation (moorsim run) ---\n\n"
       "# The seed FPSO (docs/design.md section 9): WAMIT data of the MSS FPSO (the absolute\n"
       "# path, so that this file loads wherever it is moved; a relative path is taken from\n"
       "# this file's folder), mass 1.0041e8 kg, CG 1 m below the waterline [m, body frame],\n"
       "# radii of gyration [m], the MSS low-frequency damping rule; the seed thruster layout.\n"
       "vessel:\n"
       "  hydrodynamics: "
    << request.hydrodynamics
    << "\n"
       "  mass: 1.0041e8\n"
       "  centre_of_gravity: [0, 0, 1]\n"
       "  radii_of_gyration: [16.3, 54, 54]\n"
       "  damping: {surge_time: 50, sway_time: 100, yaw_time: 20, heave_ratio: 0.1, "
       "roll_ratio: 0.07, pitch_ratio: 0.1}\n"
       "  # Start at the moored equilibrium: equal pretension on evenly spread lines puts no\n"
       "  # net load on the vessel here [m, m, deg].\n"
       "  initial_pose: {x: 0, y: 0, heading_deg: 0}\n"
       "  # The hull under water for the current load (Lpp, B, T [m], displaced volume [m^3];\n"
       "  # 0 = the Denny-Mumford wetted surface and Hoerner's cross-flow drag) and above it\n"
       "  # for the wind load (Blendermann 1994 areas [m^2], centroid forward of midship [m]).\n"
       "  hull: {length: 200, beam: 44, draught: 12, displaced_volume: 97961, wetted_surface: "
       "0, cross_flow_drag_coefficient: 0}\n"
       "  windage: {frontal_area: 1200, lateral_area: 4500, lateral_centroid: 0}\n";
  if (turret) {
    y << "  # The turret on its bearing, as on a real turret-moored FPSO (Ren & Skjetne 2016,\n"
         "  # section 3.4): the hull weathervanes about it and the thrusters hold the heading\n"
         "  # (controller.heading). Inertia and damping: the defaults.\n"
         "  turret: {bearing: free}\n";
  } else {
    y << "  # No turret: the fairleads are on the hull, so the mooring holds the heading too.\n";
  }

  y << "\n"
       "# JONSWAP Hs 2.5 m [m], peak period 7 s [s], gamma 3.3, long-crested, travelling toward\n"
       "# 315 deg (north-west), the library's thesis sea state.\n"
       "environment:\n"
       "  waves: {hs: 2.5, tp: 7, gamma: 3.3, direction_toward_deg: 315, components: 200}\n\n"
       "# The thesis PI at 1 Hz holding the initial pose: Kp [N/m, N/m, N m/rad], Ki [N/(m s),\n"
       "# N/(m s), N m/(rad s)], Kd; in yaw a loop sized for a 200 s period at 0.8 of critical\n"
       "# damping on the yaw inertia and damping (scenarios/README.md).\n"
       "controller:\n"
       "  type: pi\n"
       "  rate_hz: 1\n"
       "  setpoint: {x: 0, y: 0, heading_deg: 0}\n"
       "  kp: [1.0e5, 1.0e6, 1.0e3]\n"
       "  ki: [1.0e3, 1.0e3, 1.0e2]\n"
       "  kd: [0, 0, 0]\n"
       "  heading: {natural_period: 200, damping_ratio: 0.8}\n\n"
       "# GNSS and gyro at 1 Hz, white noise of variance 0.005 (m^2, rad^2) per channel.\n"
       "sensors:\n"
       "  gnss:\n"
       "    rate_hz: 1\n"
       "    north: {std_dev: 0.0707106781}\n"
       "    east: {std_dev: 0.0707106781}\n"
       "  gyro:\n"
       "    rate_hz: 1\n"
       "    heading: {std_dev: 0.0707106781}\n\n"
       "# No failure. To part line 1 at its fairlead 400 s into the run:\n"
       "# failure: {line: 1, time: 400, mode: fairlead}\n\n"
       "# Duration [s], output rows per second [Hz], and the run seed.\n"
       "simulation: {duration: 1000, output_rate_hz: 1, seed: 1}\n\n"
       "# No failure detectors; `moorsim run --help` lists them, e.g.\n"
       "# detectors:\n"
       "#   - {type: dht}\n"
       "#   - {type: glr}\n";
  return y.str();
}

}  // namespace moorsim::scenarios
