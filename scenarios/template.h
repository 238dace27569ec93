// Starting scenarios for `moorsim template`: the seed FPSO on N identical chain lines,
// evenly spread in bearing, every anchor placed from the elastic catenary
// (mooring_fem/catenary.h) so that all lines carry the same pretension, written as a
// commented scenario file that loads as it is.
//
// Two kinds (kTemplateKinds), both with radial lines (each line on the horizontal ray from
// the reference point through its fairlead), so that equal pretension on evenly spread
// bearings puts neither a net force nor a yaw moment on the vessel: the written pose is the
// moored equilibrium.
//  - turret: the fairleads on a 20 m turret circle 12 m deep at the reference point, line k
//    (from 1) toward bearing (k - 1) 360/N deg from north, the turret free on its bearing,
//    as in the library's thesis cases;
//  - spread: the fairleads fixed to the hull on a 22 m circle (half the beam) round the
//    reference point, 12 m deep, the bearings half a step off the bow so
//    that no line runs straight ahead; no turret (the mooring holds the heading). A spread
//    mooring usually groups its fairleads at the bow and the stern, but the loader takes
//    every fairlead to lie on a circle inside the hull's waterplane (the turret's, locked
//    when there is none), whose radius is at most half the beam.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"

namespace moorsim::scenarios {

/// A stretch of a template line, from the anchor up, of one of kTemplateLineTypes.
struct TemplateSection {
  std::string type;     ///< "chain" (the seed chain) or "polyester" (a 200 mm rope)
  double length = 0.0;  ///< unstretched [m]
  int segments = 0;     ///< 0: one per 40 m, at least 2
};

/// The line types a template line may be made of: name in --sections, name in the scenario.
struct TemplateLineType {
  std::string_view name;
  std::string_view scenario_name;
  std::string_view description;
};
extern const std::vector<TemplateLineType> kTemplateLineTypes;

/// Parses --sections: "TYPE:LENGTH[:SEGMENTS],..." from the anchor up, e.g.
/// "chain:400,polyester:1650:30,chain:150". Throws InputError "--sections: ...".
std::vector<TemplateSection> ParseTemplateSections(const std::string& text);

struct TemplateRequest {
  std::string kind;     ///< a kTemplateKinds name
  int lines = 0;        ///< number of lines N, 3..kMaxTemplateLines
  double depth = 0.0;   ///< water depth [m]
  double length = 0.0;  ///< unstretched length of every line [m] (no sections)
  /// Every line's sections from the anchor up; empty: one section of the seed chain,
  /// `length` long. (Give one of the two.)
  std::vector<TemplateSection> sections;
  /// 0: the bearings evenly spread; else the lines in this many groups (>= 3), the groups
  /// evenly spread and the lines of a group `group_spread_deg` apart.
  int groups = 0;
  double group_spread_deg = 5.0;
  std::optional<double> pretension;  ///< fairlead tension of every line [N], or
  std::optional<double> radius;      ///< anchors' horizontal distance from the reference point [m]
  std::string hydrodynamics;         ///< vessel.hydrodynamics as YAML text (quoted as needed)
};

struct TemplateKind {
  std::string_view name;
  std::string_view description;  ///< for --help
  double fairlead_radius;        ///< from the reference point [m]
  bool turret;                   ///< a free turret carries the fairleads (else the hull)
  double bearing_offset_steps;   ///< line 1's bearing from north, in steps of 360/N deg
};
/// Sorted by name.
extern const std::vector<TemplateKind> kTemplateKinds;
/// Throws moorsim::InputError "kind: unknown mooring kind 'x' (known: spread, turret)".
const TemplateKind& FindTemplateKind(const std::string& name);

constexpr int kMaxTemplateLines = 64;
/// The seed FPSO's fairleads: at its 12 m draught [m].
constexpr double kTemplateFairleadDepth = 12.0;

struct TemplateLine {
  double bearing_deg = 0.0;           ///< direction from fairlead to anchor, from north
  Vec3 fairlead_body = Vec3::Zero();  ///< body frame [m]
  Vec3 anchor = Vec3::Zero();         ///< Earth frame NED [m], vessel at the origin, heading 0
};

struct TemplateLayout {
  std::vector<TemplateLine> lines;
  double span = 0.0;            ///< horizontal fairlead-anchor distance of every line [m]
  double pretension = 0.0;      ///< catenary fairlead tension of every line [N]
  double anchor_radius = 0.0;   ///< from the reference point [m]
  double min_pretension = 0.0;  ///< the touchdown range of the line (mooring_fem) [N]
  double max_pretension = 0.0;
  /// What bounds it: "the whole line lifted off the seabed" or, for a short line in deep
  /// water, "the line pulled straight" (the loader takes no line shorter than its straight
  /// anchor-fairlead distance).
  std::string max_pretension_limit;
};

/// Checks the request and places the lines. Throws moorsim::InputError naming the
/// `moorsim template` flag, its value and the rule (e.g. "--pretension: 1e6 N is below ...").
TemplateLayout PlanTemplate(const TemplateRequest& request);

/// The commented scenario text; `command` (the command line that asked for it) goes into
/// its header. The text is not validated here (LoadScenario / ParseScenario do that).
std::string WriteTemplate(const TemplateRequest& request, const TemplateLayout& layout,
                          const std::string& command);

}  // namespace moorsim::scenarios
