// `moorsim static`: the mooring's static loads on the vessel at a given pose, from the FEM
// lines settled to rest.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "core/version.h"
#include "detectors/registry.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "runner/scenario_plant.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "simulation/simulation.h"
#include "tools/commands.h"

namespace moorsim::cli {

namespace {

struct StaticOptions {
  std::string scenario;
  std::string offset = "0,0,0";
  std::string broken;
  bool broken_given = false;
  bool json = false;
  std::vector<std::string> sets;
};

struct StaticLineResult {
  int id = 0;
  bool broken = false;
  Vec3 force = Vec3::Zero();
  double grounded_length = 0.0;
  double catenary_tension = 0.0;  ///< NaN: none (a line with a free point end)
  bool at_vessel = true;          ///< its upper end at the vessel (else at a free point)
};

int RunStatic(const StaticOptions& o) {
  const scenarios::Scenario scenario = scenarios::LoadScenario(o.scenario, o.sets);
  const std::vector<double> offset = ParseNumberList("--offset", o.offset);
  if (offset.size() != 3) {
    throw InputError("--offset: '" + o.offset + "' must be X,Y,PSI_DEG (three numbers)");
  }
  const mooring_fem::PlanarPose pose{offset[0], offset[1], offset[2] * std::numbers::pi / 180.0};
  const int num_lines = static_cast<int>(scenario.mooring.lines.size());
  std::set<int> broken;
  if (o.broken_given) {
    for (double k : ParseNumberList("--broken", o.broken)) {
      if (k != std::floor(k) || k < 1 || k > num_lines) {
        throw InputError("--broken: line " + FormatNumber(k) + " does not exist (lines are 1.." +
                         std::to_string(num_lines) + ")");
      }
      if (!broken.insert(static_cast<int>(k)).second) {
        throw InputError("--broken: line " + FormatNumber(k) + " is given twice in '" + o.broken +
                         "'");
      }
    }
  }

  // A line parted at its fairlead puts no load on the vessel: leave it out of the FEM.
  mooring_fem::MooringParameters spec = scenarios::ToMooringParameters(scenario.mooring);
  std::erase_if(spec.lines,
                [&](const mooring_fem::LineParameters& l) { return broken.count(l.id) > 0; });
  std::vector<StaticLineResult> results(num_lines);
  for (int i = 0; i < num_lines; ++i) {
    results[i].id = scenario.mooring.lines[i].id;
    results[i].broken = broken.count(results[i].id) > 0;
    if (results[i].broken) results[i].grounded_length = scenario.mooring.lines[i].Length();
  }
  double residual = 0.0;
  std::vector<Vec3> points;  // the free points at rest
  if (!spec.lines.empty()) {
    mooring_fem::MooringSystem mooring(spec);
    std::vector<Vec3> positions;
    std::vector<PointKinematics> fairleads(mooring.num_lines());
    for (int i = 0; i < mooring.num_lines(); ++i) {
      positions.push_back(mooring_fem::FairleadPosition(pose, mooring.line(i).fairlead_body));
      fairleads[i].position = positions.back();
    }
    std::vector<double> x(mooring.StateSize());
    try {
      mooring.CatenaryState(positions, x.data());
    } catch (const Error& e) {  // the pose asked for is not one the mooring can reach
      throw InputError("--offset " + o.offset + ": " + e.what());
    }
    try {
      residual = mooring.SettleStatic(positions, x.data());
    } catch (const InputError& e) {  // a free point that cannot be at rest where it is
      scenarios::PlaceAtKey(scenario, e, "mooring.points[");
    }
    for (int p = 0; p < mooring.num_points(); ++p)
      points.push_back(mooring.PointPosition(x.data(), p));
    const std::vector<mooring_fem::LineLoad> loads = mooring.LineLoads(x.data(), fairleads);
    for (int i = 0; i < mooring.num_lines(); ++i) {
      const mooring_fem::LineProperties& lp = mooring.line(i);
      StaticLineResult& r = results[lp.id - 1];
      r.force = loads[i].upper_end_force;
      r.grounded_length = loads[i].grounded_length;
      // The catenary from the anchor on the seabed to the fairlead; none for a line with a
      // free point end or from an anchor held in the water.
      r.at_vessel = lp.upper_point < 0;
      const bool held = scenario.mooring.lines[lp.id - 1].anchor_in_water;
      r.catenary_tension =
          lp.lower_point < 0 && lp.upper_point < 0 && !held
              ? mooring_fem::CatenaryFairleadTension(lp, positions[i], mooring.seabed().surface)
              : kNaN;
    }
  }

  Vec3 net = Vec3::Zero();  // Fx, Fy, Mz about the vessel's reference point
  for (const auto& line : scenario.mooring.lines) {
    const StaticLineResult& r = results[line.id - 1];
    if (!r.at_vessel) continue;  // its force is on a free point
    const Vec3 arm =
        mooring_fem::FairleadPosition(pose, line.fairlead_body) - Vec3(pose.x, pose.y, 0);
    net += Vec3(r.force.x(), r.force.y(), arm.x() * r.force.y() - arm.y() * r.force.x());
  }

  if (o.json) {
    nlohmann::json out;
    out["scenario"] = scenario.source_path;
    out["version"] = moorsim::kVersion;
    out["method"] = "fem_static";
    out["offset"] = {pose.x, pose.y, offset[2]};
    out["broken"] = std::vector<int>(broken.begin(), broken.end());
    out["max_residual_force"] = residual;
    nlohmann::json lines = nlohmann::json::array();
    for (const StaticLineResult& r : results) {
      lines.push_back({{"id", r.id},
                       {"broken", r.broken},
                       {"fairlead_tension", r.force.norm()},
                       {"horizontal_tension", std::hypot(r.force.x(), r.force.y())},
                       {"vertical_tension", r.force.z()},
                       {"grounded_length", r.grounded_length},
                       {"catenary_fairlead_tension", r.catenary_tension}});
    }
    out["lines"] = lines;
    nlohmann::json at_rest = nlohmann::json::array();
    for (std::size_t p = 0; p < points.size(); ++p) {
      at_rest.push_back({{"name", scenario.mooring.points[p].name},
                         {"position", {points[p].x(), points[p].y(), points[p].z()}}});
    }
    out["points"] = at_rest;
    out["net_force"] = {net.x(), net.y(), net.z()};
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("moorsim %s static: %s, vessel at x %.3f m, y %.3f m, heading %.3f deg\n",
              moorsim::kVersion, scenario.source_path.c_str(), pose.x, pose.y, offset[2]);
  std::printf("FEM lines settled to rest (largest residual node force %.2e N)\n\n", residual);
  std::printf("%4s %14s %14s %14s %10s %16s\n", "line", "tension [kN]", "horiz. [kN]", "vert. [kN]",
              "ground [m]", "catenary T [kN]");
  for (const StaticLineResult& r : results) {
    if (r.broken) {
      std::printf("%4d %14s\n", r.id, "broken");
      continue;
    }
    std::printf("%4d %14.2f %14.2f %14.2f %10.1f ", r.id, r.force.norm() / 1e3,
                std::hypot(r.force.x(), r.force.y()) / 1e3, r.force.z() / 1e3, r.grounded_length);
    if (std::isnan(r.catenary_tension)) {
      std::printf("%16s\n", "-");
    } else {
      std::printf("%16.2f\n", r.catenary_tension / 1e3);
    }
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (p == 0) std::printf("\nfree points at rest (Earth frame NED):\n");
    std::printf("  %-20s x %10.3f m, y %10.3f m, z %10.3f m\n",
                scenario.mooring.points[p].name.c_str(), points[p].x(), points[p].y(),
                points[p].z());
  }
  std::printf("\nnet force on the vessel (Earth frame): Fx %.2f kN, Fy %.2f kN, Mz %.2f kN m\n",
              net.x() / 1e3, net.y() / 1e3, net.z() / 1e3);
  return 0;
}

}  // namespace

Command AddStaticCommand(CLI::App& app) {
  auto o = std::make_shared<StaticOptions>();
  CLI::App* sub =
      app.add_subcommand("static", "static mooring loads on the vessel at a pose (FEM at rest)");
  sub->footer(
      "\nHow it is computed: every line is first placed on the analytic elastic catenary\n"
      "(frictionless seabed) between its anchor and its fairlead, then Newton's method on the\n"
      "sparse FEM stiffness drives every node's net force to zero, so the numbers are the\n"
      "FEM lines settled to rest (same segments, seabed contact and weights as in a run),\n"
      "not the catenary formula. Fairlead tension is the magnitude of the force the line\n"
      "exerts on the vessel at the fairlead (what a load cell there reads); vertical_tension\n"
      "is its downward component; grounded_length is the seabed's share of the line's weight\n"
      "divided by the weight per metre. The analytic catenary tension is printed alongside.\n"
      "A line up to a free point (mooring.points) shows the tension at its upper end, on the\n"
      "point, and no catenary; the free points are moved to rest with the lines.\n"
      "Units: N, m, N m; Earth frame NED (x north, y east, z down).");
  sub->add_option("scenario", o->scenario, "scenario YAML file")->required();
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("--offset", o->offset,
                  "vessel pose X,Y,PSI_DEG: north and east offset [m] of the reference point "
                  "and heading [deg] (default 0,0,0)");
  CLI::Option* broken =
      sub->add_option("--broken", o->broken, "lines K[,K...] parted at the fairlead (1-based)");
  sub->add_flag("--json", o->json, "print one JSON object (docs/design.md section 7)");
  return [o, broken] {
    o->broken_given = broken->count() > 0;
    return RunStatic(*o);
  };
}

Command AddValidateCommand(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto resolved = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "validate", "load and check a scenario, report every error in it, then exit");
  sub->add_option("scenario", *path, "scenario YAML file")->required();
  sub->add_flag("--resolved", *resolved,
                "print the scenario with its bases (`base:`) merged, as runs record it");
  AddPluginOption(sub);
  sub->footer(
      "\nEvery error of the file is one line \"<file>:<line>:<col>: <key>: <what>\" (exit 2),\n"
      "in the file where the value was written (a base's or this one's). Checks between\n"
      "values (a line that must reach its fairlead, ...) run once every value reads.\n\n" +
      detectors::DetectorHelp());
  return [path, resolved] {
    const scenarios::Scenario s = scenarios::LoadScenario(*path);
    runner::CheckDetectors(s);
    if (*resolved) {
      std::fwrite(s.text.data(), 1, s.text.size(), stdout);
    } else {
      std::printf("%s: ok (%s, %zu lines)\n", path->c_str(), s.name.c_str(),
                  s.mooring.lines.size());
    }
    return 0;
  };
}

}  // namespace moorsim::cli
