// `moorsim template`: writes a commented starting scenario whose anchors are placed from
// the elastic catenary (scenarios/template.h), checked by the loader before it is written.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "core/error.h"
#include "runner/run.h"
#include "scenarios/load.h"
#include "scenarios/strict_yaml.h"
#include "scenarios/template.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct TemplateOptions {
  std::string kind;
  std::string lines;
  std::string depth;
  std::optional<std::string> length;
  std::optional<std::string> pretension;
  std::optional<std::string> radius;
  std::optional<std::string> sections;
  std::optional<std::string> groups;
  std::optional<std::string> group_spread;
  std::optional<std::string> out;
  std::optional<std::string> hydrodynamics;
  bool force = false;
};

/// The seed FPSO's WAMIT data in the source tree (the data are not installed).
const char* const kSeedHydrodynamics = MOORSIM_SEED_HYDRODYNAMICS;

int RunTemplate(const TemplateOptions& o) {
  scenarios::TemplateRequest request;
  request.kind = o.kind;
  const double lines = ParseNumber("--lines", o.lines);
  if (lines != std::floor(lines) || std::abs(lines) > 1e9) {
    throw InputError("--lines: '" + o.lines + "' must be a whole number");
  }
  request.lines = static_cast<int>(lines);
  request.depth = ParseNumber("--depth", o.depth);
  std::string command =
      "moorsim template " + o.kind + " --lines " + o.lines + " --depth " + o.depth;
  if (o.length.has_value() == o.sections.has_value()) {
    throw InputError(std::string("--length, --sections: give exactly one of them (") +
                     (o.length ? "both" : "neither") + " given)");
  }
  if (o.length) {
    request.length = ParseNumber("--length", *o.length);
    command += " --length " + *o.length;
  }
  if (o.sections) {
    request.sections = scenarios::ParseTemplateSections(*o.sections);
    command += " --sections " + *o.sections;
  }
  if (o.groups) {
    const double groups = ParseNumber("--groups", *o.groups);
    if (groups != std::floor(groups) || std::abs(groups) > 1e9) {
      throw InputError("--groups: '" + *o.groups + "' must be a whole number");
    }
    request.groups = static_cast<int>(groups);
    command += " --groups " + *o.groups;
  }
  if (o.group_spread) {
    if (!o.groups) throw InputError("--group-spread: only with --groups");
    request.group_spread_deg = ParseNumber("--group-spread", *o.group_spread);
    command += " --group-spread " + *o.group_spread;
  }
  if (o.pretension) {
    request.pretension = ParseNumber("--pretension", *o.pretension);
    command += " --pretension " + *o.pretension;
  }
  if (o.radius) {
    request.radius = ParseNumber("--radius", *o.radius);
    command += " --radius " + *o.radius;
  }
  const scenarios::TemplateLayout layout = scenarios::PlanTemplate(request);

  // Written absolute, so that the file loads wherever it is written or moved to.
  const std::string stem =
      o.hydrodynamics ? RequireText("--hydrodynamics", *o.hydrodynamics) : kSeedHydrodynamics;
  const std::string absolute = std::filesystem::absolute(stem).lexically_normal().string();
  for (const char* extension : {".1", ".hst"}) {
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(absolute + extension, ignored)) {
      throw InputError("--hydrodynamics: '" + stem + "': no WAMIT file '" + absolute + extension +
                       "' (give the stem of the vessel's WAMIT output; the seed FPSO's is "
                       "data/fpso_wamit/fpso in moorsim's source tree)");
    }
  }
  // Quoted: a path may hold ": ", " #", a leading "*" or "&", or a line break.
  request.hydrodynamics = scenarios::strict_yaml::DoubleQuoted(absolute);
  if (o.hydrodynamics) command += " --hydrodynamics " + *o.hydrodynamics;

  std::string source_name = "template.yaml";
  if (o.out) {
    source_name = RequireText("--out", *o.out);
    CheckScenarioOut(source_name, o.force);
  }
  const std::string text = scenarios::WriteTemplate(request, layout, command);
  try {
    scenarios::ParseScenario(text, source_name);
  } catch (const InputError& e) {  // the template's own fault, not the user's
    throw Error(std::string("the written scenario does not load: ") + e.what());
  }
  if (!o.out) {
    std::cout << text;
    return 0;
  }
  // Written whole or not at all: on a full disk an existing file stays as it was.
  runner::WriteFileAtomically(source_name, text);
  std::printf("%s: %s mooring, %zu lines, pretension %.1f kN, anchors %.1f m from the vessel\n",
              source_name.c_str(), o.kind.c_str(), layout.lines.size(), layout.pretension / 1e3,
              layout.anchor_radius);
  return 0;
}

}  // namespace

Command AddTemplateCommand(CLI::App& app) {
  auto o = std::make_shared<TemplateOptions>();
  CLI::App* sub = app.add_subcommand(
      "template", "write a commented starting scenario, anchors placed from the catenary");
  std::string kinds;
  for (const scenarios::TemplateKind& kind : scenarios::kTemplateKinds) {
    kinds += "  " + std::string(kind.name) + ": " + std::string(kind.description) + "\n";
  }
  sub->footer(
      "\nKinds:\n" + kinds +
      "\nThe seed FPSO on N identical lines of the seed chain (80 mm, 275 kg/m, EA 2.28785e8 N)\n"
      "--length long, or of --sections (e.g. chain:400,polyester:1650,chain:150; the rope is a\n"
      "generic 200 mm polyester, 40 kg/m, EA 2e8 N; segments one per 40 m unless given),\n"
      "bearings 360/N deg apart or in --groups (G groups 360/G deg apart, the lines of a group\n"
      "--group-spread deg apart), each line radial from the vessel's reference point, fairleads\n"
      "12 m deep. Every anchor is placed on the seabed where the elastic catenary (seabed\n"
      "contact, stretch, the lines' weight in water) gives the fairlead tension --pretension,\n"
      "or at --radius with the resulting pretension written in a comment; give exactly one.\n"
      "The pretension must lie in the touchdown range: above the weight in water of the line\n"
      "hanging straight down to the seabed (below it the line lies slack), at most the tension\n"
      "that lifts the whole line off the seabed (beyond it the anchor is pulled up) or, for a\n"
      "short line in deep water, pulls it straight; --radius likewise. The rest (waves, the\n"
      "thesis PI, sensors, 1000 s, seed 1, no failure) as in the library scenarios; the file\n"
      "loads and runs as it is. The WAMIT path is written absolute.\n" +
      std::string(kScenarioOutNote) + "\nUnits: N, m.");
  sub->add_option("kind", o->kind, "spread or turret")->required();
  sub->add_option("--lines", o->lines, "number of lines N (3..64)")->required();
  sub->add_option("--depth", o->depth, "water depth [m]")->required();
  sub->add_option("--length", o->length, "unstretched length of every line of chain [m]");
  sub->add_option("--sections", o->sections,
                  "instead of --length: every line's sections from the anchor up, "
                  "TYPE:LENGTH[:SEGMENTS],... (types: chain, polyester)");
  sub->add_option("--groups", o->groups, "the lines in this many groups (>= 3)");
  sub->add_option("--group-spread", o->group_spread,
                  "with --groups: degrees between the lines of a group (default 5)");
  sub->add_option("--pretension", o->pretension, "fairlead tension of every line at rest [N]");
  sub->add_option("--radius", o->radius,
                  "anchors' horizontal distance from the vessel's reference point [m]");
  sub->add_option("--out", o->out, "write the scenario to this file (default: stdout)");
  sub->add_flag("--force", o->force, "with --out: replace an existing file");
  sub->add_option("--hydrodynamics", o->hydrodynamics,
                  "WAMIT output stem of the vessel (default: the seed FPSO's data)");
  return [o] { return RunTemplate(*o); };
}

}  // namespace moorsim::cli
