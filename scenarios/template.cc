#include "scenarios/template.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"
#include "scenarios/strict_yaml.h"

namespace moorsim::scenarios {

const std::vector<TemplateKind> kTemplateKinds = {
    {"spread", "fairleads fixed to the hull on a 22 m circle (half the beam), no turret", 22.0,
     false, 0.5},
    {"turret", "fairleads on a 20 m turret at the reference point, free on its bearing", 20.0, true,
     0.0},
};

const std::vector<TemplateLineType> kTemplateLineTypes = {
    {"chain", "chain_seed", "the seed chain: 80 mm, 275 kg/m, EA 2.28785e8 N"},
    {"polyester", "polyester", "a 200 mm polyester rope: 40 kg/m, EA 2e8 N (linear)"},
};

namespace {

constexpr double kMaxDepth = 12000.0;   // the loader's range: the deepest ocean is 11 km
constexpr double kMaxLength = 20000.0;  // the loader's range for a line's length

/// A template section's segments: as given, or one per 40 m (at least 2).
int SegmentsOf(const TemplateSection& section) {
  return section.segments > 0 ? section.segments
                              : std::max(2, static_cast<int>(std::lround(section.length / 40.0)));
}

/// The template line as the FEM sees it: its types, and one line of its sections.
mooring_fem::MooringParameters CompositeSpec(double depth,
                                             const std::vector<TemplateSection>& sections) {
  mooring_fem::MooringParameters spec;
  spec.water.depth = depth;  // sea water and gravity: the Water defaults
  spec.line_types = {mooring_fem::SeedChain(), mooring_fem::PolyesterRope()};
  mooring_fem::LineParameters line;
  line.id = 1;
  for (const TemplateSection& section : sections) {
    for (const TemplateLineType& type : kTemplateLineTypes) {
      if (type.name == section.type) {
        line.sections.push_back(
            {std::string(type.scenario_name), section.length, SegmentsOf(section)});
      }
    }
  }
  spec.lines.push_back(line);
  return spec;
}

/// The seed chain as the catenary and the FEM see it (submerged weight from the water).
mooring_fem::SectionProperties SeedLine(double depth, double length) {
  mooring_fem::MooringParameters spec;
  spec.water.depth = depth;  // sea water and gravity: the Water defaults
  spec.line_types = {mooring_fem::SeedChain()};
  const auto line = mooring_fem::LineParameters::Uniform(1, spec.line_types.front().name, length, 1,
                                                         Vec3::Zero(), Vec3::Zero());
  return mooring_fem::MakeLineProperties(spec, line).sections.front();
}

/// A value in the written file: FormatNumber's shortest text that reads back as the same
/// double ("2250", "14.142135623730951"), large numbers in scientific notation
/// ("2.28785e+08").
std::string Number(double value) {
  if (!(std::abs(value) >= 1e6)) return FormatNumber(value);
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
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

std::vector<TemplateSection> ParseTemplateSections(const std::string& text) {
  std::vector<TemplateSection> sections;
  std::string known;
  for (const TemplateLineType& type : kTemplateLineTypes) {
    known += (known.empty() ? "" : ", ") + std::string(type.name);
  }
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    const std::string where =
        ": '" + item + "' (section " + std::to_string(sections.size() + 1) + ")";
    std::vector<std::string> parts;
    std::stringstream fields(item);
    for (std::string part; std::getline(fields, part, ':');) parts.push_back(part);
    if (parts.size() < 2 || parts.size() > 3) {
      throw OptionError("sections", where + " must be TYPE:LENGTH or TYPE:LENGTH:SEGMENTS");
    }
    TemplateSection section;
    section.type = parts[0];
    if (std::none_of(kTemplateLineTypes.begin(), kTemplateLineTypes.end(),
                     [&](const TemplateLineType& t) { return t.name == section.type; })) {
      throw OptionError(
          "sections", where + ": unknown line type '" + section.type + "' (known: " + known + ")");
    }
    const auto number = [&](const std::string& field, double* value) {
      const char* end = field.data() + field.size();
      const auto [ptr, ec] = std::from_chars(field.data(), end, *value);
      return ec == std::errc() && ptr == end;
    };
    if (!number(parts[1], &section.length) || !(section.length > 0.0) ||
        section.length > kMaxLength) {
      throw OptionError(
          "sections", where + ": the length must be a number in (0, " + Number(kMaxLength) + "] m");
    }
    if (parts.size() == 3) {
      double segments = 0.0;
      if (!number(parts[2], &segments) || segments != std::floor(segments) || segments < 1.0 ||
          segments > 10000.0) {
        throw OptionError("sections", where + ": the segments must be a whole number in 1..10000");
      }
      section.segments = static_cast<int>(segments);
    }
    sections.push_back(section);
  }
  if (sections.empty()) throw OptionError("sections", ": '" + text + "' lists no section");
  return sections;
}

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

namespace {

// The span, pretension and touchdown range of a line of the seed chain alone.
void PlanChainSpan(const TemplateRequest& request, const TemplateKind& kind,
                   TemplateLayout& layout) {
  const double depth = request.depth;
  const double length = request.length;
  const mooring_fem::SectionProperties seed = SeedLine(depth, length);
  const mooring_fem::CatenaryLineProperties line{seed.length, seed.weight_per_length,
                                                 seed.axial_stiffness};
  const double height = depth - kTemplateFairleadDepth;
  mooring_fem::TouchdownRange range;
  try {
    range = mooring_fem::SolveTouchdownRange(line, height);
  } catch (const Error& e) {
    throw OptionError(
        "length", ": " + Number(length) + " m in " + Number(depth) + " m of water: " + e.what());
  }
  const double radius_offset = kind.fairlead_radius;  // radial lines
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
      throw OptionError("pretension",
                        ": " + Number(t) + " N is not above " + Kilonewtons(range.min_tension) +
                            ", the weight in water of the line hanging straight down from the "
                            "fairlead to the seabed (a line touching down pulls more)");
    }
    if (t > range.max_tension) {
      throw OptionError("pretension", ": " + Number(t) + " N is above " +
                                          Kilonewtons(range.max_tension) + ", where " +
                                          upper_limit);
    }
    layout.span = t == range.max_tension ? range.max_span
                                         : mooring_fem::SpanForFairleadTension(line, height, t);
  } else {
    const double r = *request.radius;
    const double span = r - radius_offset;
    if (!(span > range.min_span)) {
      throw OptionError("radius",
                        ": " + Number(r) + " m is too small: the anchors must be more than " +
                            Metres(range.min_span + radius_offset) +
                            " from the reference point, or the line lies slack on the seabed (no "
                            "horizontal tension)");
    }
    if (span > range.max_span) {
      throw OptionError("radius", ": " + Number(r) + " m is too large: beyond " +
                                      Metres(range.max_span + radius_offset) +
                                      " from the reference point " + upper_limit);
    }
    layout.span = span;
  }
  layout.anchor_radius = layout.span + radius_offset;
  layout.pretension = mooring_fem::SolveCatenary(line, layout.span, height).fairlead_tension;
}

// The span, pretension and touchdown range of a line of sections (composite_catenary.h).
void PlanSectionsSpan(const TemplateRequest& request, const TemplateKind& kind,
                      TemplateLayout& layout) {
  const mooring_fem::MooringParameters spec = CompositeSpec(request.depth, request.sections);
  const mooring_fem::LineProperties lp = mooring_fem::MakeLineProperties(spec, spec.lines.front());
  const mooring_fem::CompositeLine line = mooring_fem::CatenaryLineOf(lp);
  double length = 0.0;
  for (const auto& section : line.sections) length += section.length;
  const double height = request.depth - kTemplateFairleadDepth;
  if (!(length > height)) {
    throw OptionError("sections", ": the line, " + Metres(length) + " long, does not reach the " +
                                      "seabed " + Metres(height) + " below the fairlead");
  }
  // Slack below: the top `height` of the line hanging straight down (its weight in water).
  double hanging = 0.0;
  double left = height;
  for (std::size_t i = line.sections.size(); i-- > 0 && left > 0.0;) {
    hanging += line.sections[i].weight_per_length * std::min(left, line.sections[i].length);
    left -= line.sections[i].length;
    if (left > 0.0 && i > 0) hanging += line.joint_weights[i - 1];
  }
  const auto solve = [&](double span) -> std::optional<mooring_fem::CompositeCatenary> {
    try {
      return mooring_fem::SolveCompositeCatenary(line, span, height);
    } catch (const Error&) {
      return std::nullopt;
    }
  };
  const double slack_span = length - height;
  double max_span = std::sqrt(length * length - height * height) * (1.0 - 1e-9);
  std::string upper_limit =
      "the line is pulled straight: its anchor as far from its fairlead as it is long "
      "(unstretched)";
  layout.max_pretension_limit = "the line pulled straight";
  if (const auto taut = solve(max_span); !taut || !(taut->grounded_length > 0.0)) {
    // The largest span at which the line still rests on the seabed.
    double lo = slack_span, hi = max_span;
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (lo + hi);
      const auto at = solve(mid);
      (at && at->grounded_length > 0.0 ? lo : hi) = mid;
    }
    max_span = lo;
    upper_limit =
        "the whole line is lifted off the seabed and pulls its anchor up (a drag anchor holds "
        "no uplift)";
    layout.max_pretension_limit = "the whole line lifted off the seabed";
  }
  const auto at_max = solve(max_span);
  if (!at_max) {
    throw OptionError("sections",
                      ": no catenary for the line in " + Number(request.depth) + " m of water");
  }
  layout.min_pretension = hanging;
  layout.max_pretension = at_max->fairlead_tension;
  const double radius_offset = kind.fairlead_radius;  // radial lines
  if (request.pretension) {
    const double t = *request.pretension;
    if (!(t > layout.min_pretension)) {
      throw OptionError("pretension",
                        ": " + Number(t) + " N is not above " + Kilonewtons(layout.min_pretension) +
                            ", the weight in water of the line hanging straight down from the "
                            "fairlead to the seabed (a line touching down pulls more)");
    }
    if (t > layout.max_pretension) {
      throw OptionError("pretension", ": " + Number(t) + " N is above " +
                                          Kilonewtons(layout.max_pretension) + ", where " +
                                          upper_limit);
    }
    // The tension grows with the span; near the slack end the solver may find nothing
    // (the tension is then below any asked for).
    double lo = slack_span, hi = max_span;
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (lo + hi);
      const auto at = solve(mid);
      (!at || at->fairlead_tension < t ? lo : hi) = mid;
    }
    layout.span = hi;
  } else {
    const double r = *request.radius;
    const double span = r - radius_offset;
    if (!(span > slack_span)) {
      throw OptionError("radius",
                        ": " + Number(r) + " m is too small: the anchors must be more than " +
                            Metres(slack_span + radius_offset) +
                            " from the reference point, or the line lies slack on the seabed (no "
                            "horizontal tension)");
    }
    if (span > max_span) {
      throw OptionError("radius", ": " + Number(r) + " m is too large: beyond " +
                                      Metres(max_span + radius_offset) +
                                      " from the reference point " + upper_limit);
    }
    layout.span = span;
  }
  const auto at_span = solve(layout.span);
  if (!at_span) {
    throw OptionError("sections", ": no catenary for the line with its anchor " +
                                      Metres(layout.span) + " from its fairlead");
  }
  layout.anchor_radius = layout.span + radius_offset;
  layout.pretension = at_span->fairlead_tension;
}

}  // namespace

TemplateLayout PlanTemplate(const TemplateRequest& request) {
  const TemplateKind& kind = FindTemplateKind(request.kind);
  const int n = request.lines;
  if (n < 3) {
    throw OptionError("lines",
                      ": " + std::to_string(n) +
                          " must be >= 3 (fewer lines cannot hold the vessel in every direction)");
  }
  if (n > kMaxTemplateLines) {
    throw OptionError("lines", ": " + std::to_string(n) +
                                   " must be <= " + std::to_string(kMaxTemplateLines) +
                                   " (moorings in service have at most a few dozen lines)");
  }
  const double depth = request.depth;
  if (!(depth > 0.0)) throw OptionError("depth", ": " + Number(depth) + " m must be > 0");
  if (!(depth > kTemplateFairleadDepth)) {
    throw OptionError("depth", ": " + Number(depth) + " m must be deeper than the fairleads, " +
                                   Number(kTemplateFairleadDepth) +
                                   " m down at the FPSO's draught");
  }
  if (depth > kMaxDepth) {
    throw OptionError("depth", ": " + Number(depth) + " m must be <= " + Number(kMaxDepth) +
                                   " (the deepest ocean is 11 km)");
  }
  if (!request.sections.empty() && request.length != 0.0) {
    throw OptionError(std::vector<std::string>{"length", "sections"},
                      ": give exactly one of them (both given)");
  }
  if (request.sections.empty() && (!(request.length > 0.0) || request.length > kMaxLength)) {
    throw OptionError("length", ": " + Number(request.length) + " m must be in (0, " +
                                    Number(kMaxLength) + "] m");
  }
  if (request.groups != 0) {
    const int g = request.groups;
    if (g < 3) {
      throw OptionError(
          "groups", ": " + std::to_string(g) +
                        " must be >= 3 (fewer groups cannot hold the vessel in every direction)");
    }
    if (n % g != 0) {
      throw OptionError("groups", ": " + std::to_string(g) + " does not divide the " +
                                      std::to_string(n) + " lines into equal groups");
    }
    const double spread = request.group_spread_deg;
    if (!(spread > 0.0) || !((n / g - 1) * spread < 360.0 / g)) {
      throw OptionError("group_spread", ": " + Number(spread) +
                                            " deg must be > 0 and keep each group of " +
                                            std::to_string(n / g) + " lines within its " +
                                            Number(360.0 / g) + " deg (groups apart)");
    }
  }
  if (request.pretension.has_value() == request.radius.has_value()) {
    throw OptionError(std::vector<std::string>{"pretension", "radius"},
                      std::string(": give exactly one of them (") +
                          (request.pretension ? "both" : "neither") + " given)");
  }

  TemplateLayout layout;
  if (request.sections.empty()) {
    PlanChainSpan(request, kind, layout);
  } else {
    PlanSectionsSpan(request, kind, layout);
  }

  for (int k = 0; k < n; ++k) {
    TemplateLine l;
    if (request.groups == 0) {
      l.bearing_deg = (k + kind.bearing_offset_steps) * 360.0 / n;
    } else {  // group k / m round its centre, the lines of a group spread about it
      const int m = n / request.groups;
      l.bearing_deg = (k / m + kind.bearing_offset_steps) * 360.0 / request.groups +
                      (k % m - 0.5 * (m - 1)) * request.group_spread_deg;
      if (l.bearing_deg < 0.0) l.bearing_deg += 360.0;
    }
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
  const bool composite = !request.sections.empty();
  const bool grouped = request.groups != 0;
  // What a line is made of, from the anchor up ("chain, polyester and chain"), and its
  // unstretched length.
  std::string what;
  double length = request.length;
  bool uses_chain = !composite, uses_rope = false;
  if (composite) {
    length = 0.0;
    for (std::size_t i = 0; i < request.sections.size(); ++i) {
      const std::string& type = request.sections[i].type;
      what += (i == 0 ? "" : i + 1 == request.sections.size() ? " and " : ", ") + type;
      length += request.sections[i].length;
      (type == "chain" ? uses_chain : uses_rope) = true;
    }
  }
  std::ostringstream y;
  y << "# yaml-language-server: $schema=moorsim.schema.json\n"
       "# (`moorsim schema > moorsim.schema.json` writes that schema next to this file, for\n"
       "# editors that check and complete scenarios as they are typed.)\n"
       "#\n"
       "# A starting scenario to edit, written by\n"
       "#   "
    << strict_yaml::OneLine(command)
    << "\n"
       "# The seed FPSO (docs/design.md section 9), "
    << (turret ? "turret-moored" : "spread-moored") << ", on " << n << " identical "
    << (composite ? "lines of " + what : std::string("chain lines")) << " in\n# "
    << Number(request.depth) << " m of water, "
    << (grouped ? "in " + std::to_string(request.groups) + " groups of " +
                      std::to_string(n / request.groups) + " lines " +
                      Number(request.group_spread_deg) + " deg apart"
                : std::string("their bearings evenly spread"))
    << ", every anchor placed on the\n"
       "# elastic catenary (seabed contact, stretch, the lines' weight in water) so that every\n"
       "# line has the same pretension. SI units throughout; Earth frame NED (x north, y east,\n"
       "# z down), body frame x forward, y starboard, z down. Lines are numbered from 1.\n"
       "name: "
    << request.kind << "_" << n << "_lines\n\n";

  const mooring_fem::Water water;  // sea water
  const mooring_fem::LineType chain = mooring_fem::SeedChain();
  const mooring_fem::SectionProperties seed = SeedLine(request.depth, 1000.0);
  // "      key: value" with its comment from column 37, as in the library files.
  const auto field = [&y](const std::string& key, const std::string& value,
                          const std::string& comment) {
    const std::string text = "      " + key + ": " + value;
    y << text;
    if (!comment.empty()) {
      y << std::string(text.size() < 36 ? 36 - text.size() : 1, ' ') << "# " << comment;
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
       "  line_types:\n";
  if (uses_chain) y << "    - name: " << chain.name << "\n";
  if (uses_chain) {
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
    y << "      # For the design checks (docs/design-checks.md): 275 kg/m is a studless chain of\n"
         "      # 117.6 mm bar by its weight (0.0199 d^2 kg/m, d in mm); grade R3's breaking load\n"
         "      # 0.0223 d^2 (44 - 0.08 d) kN, and DNV-OS-E301's studless curve on its two bars.\n"
         "      # Give your chain's grade and certificate values.\n";
    field("minimum_breaking_load", "1.066e7", "[N]");
    field("fatigue", "{curve: studless_chain, nominal_area: 0.02171}", "two bars [m^2]");
  }
  if (uses_rope) {
    const mooring_fem::LineType rope = mooring_fem::PolyesterRope();
    const mooring_fem::Water sea;
    const double displaced = sea.density * std::numbers::pi / 4.0 * rope.diameter * rope.diameter;
    y << "    # A generic 200 mm polyester rope, linear-elastic at its working slope (give its\n"
         "    # measured curve as tension_strain, scenarios/README.md).\n"
         "    - name: "
      << rope.name << "\n";
    field("diameter", Number(rope.diameter),
          "[m]; displaces " + Number(std::round(displaced * 10.0) / 10.0) + " kg/m of sea water");
    field("mass_per_length", Number(rope.mass_per_length),
          "dry [kg/m]: " + Number(std::round((rope.mass_per_length - displaced) * sea.gravity)) +
              " N/m in water");
    field("axial_stiffness", Number(rope.axial_stiffness), "EA [N]");
    field("axial_damping_ratio", Number(rope.axial_damping_ratio.value()), "");
    field("drag_normal", Number(rope.drag_normal), "C_DN [-]");
    field("drag_tangential", Number(rope.drag_tangential), "C_DT [-]");
    field("added_mass_normal", Number(rope.added_mass_normal), "C_MN [-]");
    y << "      # For the design checks: a generic breaking load for a 200 mm polyester rope and\n"
         "      # API RP 2SM's curve; give your rope's certificate value.\n";
    field("minimum_breaking_load", "9.0e6", "[N]");
    field("fatigue", "{curve: polyester}", "");
  }
  if (!composite) {
    y << "\n  defaults: {segments: 50}          # equal segments per line (docs/line-model.md: "
         "the choice of segments)\n";
  }
  y << "\n";

  const double height = request.depth - kTemplateFairleadDepth;
  y << "  # Every line: " << Number(length) << " m unstretched, its fairlead " << Number(height)
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
         "  # deep (the draught), each on the ray toward its own anchor at heading 0;\n";
    if (grouped) {
      y << "  # the groups toward (g - 1) 360/" << request.groups << " deg, the lines of a group "
        << Number(request.group_spread_deg) << " deg apart.\n";
    } else {
      y << "  # line k toward (k - 1) 360/" << n << " deg.\n";
    }
  } else {
    y << "  # Fairleads: body frame [m] fixed to the hull on the 22 m circle (half the beam)\n"
         "  # round the reference point, 12 m deep (the draught);\n"
      << (grouped
              ? "  # the groups toward (g - 1/2) 360/" + std::to_string(request.groups) +
                    " deg, the lines of a group " + Number(request.group_spread_deg) + " deg apart"
              : "  # line k toward (k - 1/2) 360/" + std::to_string(n) + " deg")
      << ", so that no line runs straight ahead. Each line is\n"
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
      << (composite ? "" : "      type: chain_seed\n") << "      anchor: [" << Number(l.anchor.x())
      << ", " << Number(l.anchor.y()) << ", " << Number(l.anchor.z()) << "]\n"
      << "      fairlead: [" << Number(l.fairlead_body.x()) << ", " << Number(l.fairlead_body.y())
      << ", " << Number(l.fairlead_body.z()) << "]\n";
    if (!composite) {
      y << "      length: " << Number(request.length) << "\n";
      continue;
    }
    y << "      sections:                     # from the anchor up\n";
    for (const TemplateSection& section : request.sections) {
      const std::string_view name = section.type == "chain" ? kTemplateLineTypes[0].scenario_name
                                                            : kTemplateLineTypes[1].scenario_name;
      y << "        - {type: " << name << ", length: " << Number(section.length)
        << ", segments: " << SegmentsOf(section) << "}\n";
    }
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
