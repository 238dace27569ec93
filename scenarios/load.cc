#include "scenarios/load.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/environment.h"
#include "mooring_fem/seabed.h"
#include "scenarios/convert.h"
#include "scenarios/depth_grid.h"
#include "scenarios/plant_builder.h"
#include "scenarios/strict_yaml.h"

namespace moorsim::scenarios {
namespace {

using namespace strict_yaml;  // NOLINT(google-build-using-namespace): the shared reader

// ---------------------------------------------------------------------------------------
// The schema, one function per block (documented in load.h and README.md).

// Neither axial_damping nor axial_damping_ratio given: half of a segment's critical
// damping stops the stiff axial modes from ringing and is invisible at wave periods.
constexpr double kDefaultAxialDampingRatio = 0.5;

// An angle under a *_deg key, in radians (the schema bounds the degrees as written to a
// full turn either way: beyond it is a unit mistake or a typo).
double AngleDegrees(const Reader& r) { return Radians(r.As<double>()); }

void ParseWater(const Reader& r, Water& water) {
  r.CheckKeys();
  r.Optional("density", water.density);
  r.Optional("gravity", water.gravity);
  water.depth = r.Required<double>("depth");
}

void ParseSeabed(const Reader& r, Seabed& seabed) {
  r.CheckKeys();
  r.Optional("stiffness", seabed.stiffness);
  r.Optional("damping", seabed.damping);
  r.Optional("contact_smoothing", seabed.contact_smoothing);
  r.Optional("friction_velocity", seabed.friction_velocity);
  if (std::optional<Reader> slope = r.Find("slope_deg")) seabed.slope = AngleDegrees(*slope);
  if (std::optional<Reader> direction = r.Find("slope_direction_deg")) {
    seabed.slope_direction = AngleDegrees(*direction);
  }
  if (std::optional<Reader> grid = r.Find("grid")) {
    // A relative path is relative to the folder of the file it is written in.
    std::filesystem::path file = grid->As<std::string>();
    if (file.is_relative()) file = std::filesystem::path(grid->File()).parent_path() / file;
    try {
      seabed.grid = ReadDepthGrid(file.lexically_normal().string());
    } catch (const InputError& error) {
      grid->Fail(error.what());
    }
  }
}

void ParseCurrent(const Reader& r, CurrentProfile& current) {
  r.CheckKeys();
  if (std::optional<Reader> file = r.Find("file")) {
    for (const char* key : {"direction_deg", "profile"}) {
      if (std::optional<Reader> k = r.Find(key)) k->Fail("give a profile or a file, not both");
    }
    // A relative path is relative to the folder of the file it is written in.
    std::filesystem::path path = file->As<std::string>();
    if (path.is_relative()) path = std::filesystem::path(file->File()).parent_path() / path;
    auto table = std::make_shared<mooring_fem::CurrentTable>();
    try {
      *table = ReadCurrentTable(path.lexically_normal().string());
    } catch (const InputError& error) {
      file->Fail(error.what());
    }
    if (std::optional<Reader> period = r.Find("period")) {
      table->period = period->As<double>();
      try {
        mooring_fem::CheckCurrentTable(*table);
      } catch (const InputError& error) {
        period->Fail(error.what());
      }
    }
    current.table = std::move(table);
    return;
  }
  if (std::optional<Reader> period = r.Find("period")) {
    period->Fail("repeats a current table: give it with file");
  }
  current.direction = AngleDegrees(r.Needed("direction_deg"));
  const Reader profile = r.Needed("profile");
  const std::vector<Reader> points = profile.Items();
  if (points.empty()) profile.Fail("[] must hold at least one {depth, speed} point");
  profile.ForEachItem([&](const Reader& point, std::size_t) {
    point.CheckKeys();
    current.depth.push_back(point.Required<double>("depth"));
    current.speed.push_back(point.Required<double>("speed"));
  });
}

LineType ParseLineType(const Reader& r) {
  r.CheckKeys();
  LineType type;
  type.name = r.Required<std::string>("name");
  type.diameter = r.Required<double>("diameter");
  type.mass_per_length = r.Required<double>("mass_per_length");
  if (const std::optional<Reader> curve = r.Find("tension_strain")) {
    if (std::optional<Reader> ea = r.Find("axial_stiffness")) {
      ea->Fail("give axial_stiffness or tension_strain, not both");
    }
    const std::vector<Reader> points = curve->Items();
    if (points.empty()) curve->Fail("[] must hold at least one {strain, tension} point");
    curve->ForEachItem([&](const Reader& point, std::size_t k) {
      point.CheckKeys();
      const mooring_fem::StrainTension p{point.Required<double>("strain"),
                                         point.Required<double>("tension")};
      const mooring_fem::StrainTension before =
          type.tension_strain.empty() ? mooring_fem::StrainTension{} : type.tension_strain.back();
      if (!(p.strain > before.strain && p.tension > before.tension)) {
        point.Fail("strain " + FormatNumber(p.strain) + " and tension " + WithUnit(p.tension, "N") +
                   " must both exceed the point before's (" +
                   (k == 0
                        ? std::string("0 and 0 N")
                        : FormatNumber(before.strain) + " and " + WithUnit(before.tension, "N")) +
                   ")");
      }
      type.tension_strain.push_back(p);
    });
  } else {
    type.axial_stiffness = r.Needed("axial_stiffness").As<double>();
  }
  const std::optional<double> dynamic = r.Maybe<double>("dynamic_axial_stiffness");
  const std::optional<double> creep = r.Maybe<double>("creep_time");
  const bool dynamic_given = r.Find("dynamic_axial_stiffness").has_value();
  if (dynamic_given != r.Find("creep_time").has_value()) {
    r.Child(dynamic_given ? "dynamic_axial_stiffness" : "creep_time")
        .Fail("a visco-elastic rope needs both dynamic_axial_stiffness and creep_time");
  }
  if (dynamic && creep) {
    if (!type.tension_strain.empty()) {
      r.Child("dynamic_axial_stiffness")
          .Fail("a visco-elastic rope takes axial_stiffness, not a tension_strain table");
    }
    if (!(*dynamic > type.axial_stiffness)) {
      r.Child("dynamic_axial_stiffness")
          .Fail(WithUnit(*dynamic, "N") + " must exceed the quasi-static axial_stiffness " +
                WithUnit(type.axial_stiffness, "N"));
    }
    type.visco_elastic = mooring_fem::ViscoElastic{*dynamic, *creep};
    type.visco_elastic->dynamic_stiffness_slope =
        r.Maybe<double>("dynamic_axial_stiffness_slope").value_or(0.0);
  } else if (r.Find("dynamic_axial_stiffness_slope")) {
    r.Child("dynamic_axial_stiffness_slope")
        .Fail(
            "a dynamic stiffness slope needs a visco-elastic rope (dynamic_axial_stiffness "
            "and creep_time)");
  }
  type.axial_damping = r.Maybe<double>("axial_damping");
  type.axial_damping_ratio = r.Maybe<double>("axial_damping_ratio");
  if (!type.axial_damping && !type.axial_damping_ratio) {
    type.axial_damping_ratio = kDefaultAxialDampingRatio;
  }
  type.drag_normal = r.Required<double>("drag_normal");
  type.drag_tangential = r.Required<double>("drag_tangential");
  type.added_mass_normal = r.Required<double>("added_mass_normal");
  r.Optional("added_mass_tangential", type.added_mass_tangential);
  r.Optional("friction_axial", type.friction_axial);
  r.Optional("friction_lateral", type.friction_lateral);
  r.Optional("minimum_breaking_load", type.minimum_breaking_load);
  if (const std::optional<Reader> fatigue = r.Find("fatigue")) {
    fatigue->CheckKeys();
    const std::optional<analysis::TnPreset> preset = fatigue->Maybe<analysis::TnPreset>("curve");
    analysis::TnCurve curve = preset ? analysis::TnCurveOf(*preset) : analysis::TnCurve{};
    if (!fatigue->Find("curve")) {
      for (const char* key : {"a", "m"}) {
        if (!fatigue->Find(key))
          fatigue->Fail(std::string("give a curve, or a and m (") + key + " missing)");
      }
    }
    fatigue->Optional("a", curve.a);
    fatigue->Optional("m", curve.m);
    fatigue->Optional("range", curve.range);
    fatigue->Optional("mean_load_slope", curve.mean_load_slope);
    if (curve.range == analysis::TnRange::kNormalised || curve.mean_load_slope > 0.0) {
      if (!(type.minimum_breaking_load > 0.0)) {
        fatigue->Fail(
            "a curve on the breaking load (normalised, or with a mean-load term) "
            "needs the type's minimum_breaking_load");
      }
    }
    type.fatigue_area =
        fatigue->Maybe<double>("nominal_area")
            .value_or(analysis::NominalArea(preset.value_or(analysis::TnPreset::kSixStrandRope),
                                            type.diameter));
    type.fatigue_curve = curve;
  }
  type.mark = r.mark();
  return type;
}

PointSpec ParsePoint(const Reader& r) {
  r.CheckKeys();
  PointSpec point;
  point.name = r.Required<std::string>("name");
  point.position = r.Required<Vec3>("position");
  r.Optional("mass", point.body.mass);
  r.Optional("volume", point.body.volume);
  r.Optional("added_mass", point.body.added_mass);
  r.Optional("drag_area", point.body.drag_area);
  point.mark = r.mark();
  return point;
}

// A line's end: the fixed position under `fixed` (anchor, fairlead) or the free point named
// under `point` (from, to): one of them. Returns the point's index, or -1.
int ParseLineEnd(const Reader& r, const char* fixed, const char* point, Vec3* position,
                 std::string* name, const std::vector<PointSpec>& points) {
  const std::optional<Reader> at_point = r.Find(point);
  if (!at_point) {
    const std::optional<Reader> at = r.Find(fixed);
    if (!at) {
      r.Fail(std::string("needs ") + fixed + " or " + point + " (a free point's name)");
    }
    *position = at->As<Vec3>();
    return -1;
  }
  if (r.Find(fixed)) {
    r.Child(fixed).Fail(std::string("give a line's end either ") + fixed + " or " + point +
                        ", not both");
  }
  *name = at_point->As<std::string>();
  std::vector<std::string> known;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k].name == *name) return static_cast<int>(k);
    known.push_back(points[k].name);
  }
  at_point->Fail(
      "unknown point '" + *name + "' (" +
      (known.empty() ? std::string("mooring.points lists none") : "known: " + JoinSorted(known)) +
      ")");
}

LineSpec ParseLine(const Reader& r, int entry, int default_segments,
                   const std::vector<PointSpec>& points) {
  r.CheckKeys();
  LineSpec line;
  line.entry = entry;
  line.id = entry;
  r.Optional("id", line.id);
  line.lower_point = ParseLineEnd(r, "anchor", "from", &line.anchor, &line.from, points);
  if (std::optional<Reader> held = r.Find("anchor_in_water")) {
    line.anchor_in_water = held->As<bool>();
    if (line.anchor_in_water && line.lower_point >= 0) {
      held->Fail("the line starts at a free point ('" + line.from +
                 "'), not at an anchor to hold in the water");
    }
  }
  line.upper_point = ParseLineEnd(r, "fairlead", "to", &line.fairlead_body, &line.to, points);
  line.mark = r.mark();
  const std::optional<Reader> sections = r.Find("sections");
  if (!sections) {  // a line of one type
    if (r.Find("bodies")) {
      r.Child("bodies").Fail("bodies sit on the joints between sections: give the line's sections");
    }
    const Reader length = r.Needed("length");
    mooring_fem::LineSection section{r.Needed("type").As<std::string>(), length.As<double>(),
                                     default_segments};
    r.Optional("segments", section.segments);
    line.sections = {section};
    line.length_mark = length.mark();
    return line;
  }
  for (const char* key : {"type", "length", "segments"}) {
    if (std::optional<Reader> alone = r.Find(key)) {
      alone->Fail("give a line either type, length and segments or its sections, not both");
    }
  }
  line.length_mark = sections->mark();
  line.written_in_sections = true;
  sections->ForEachItem([&](const Reader& item, std::size_t) {
    item.CheckKeys();
    line.sections.push_back({item.Required<std::string>("type"), item.Required<double>("length"),
                             item.Required<int>("segments")});
  });
  if (line.sections.empty()) {
    sections->Fail("lists no section: a line needs one or more (or type, length and segments)");
  }
  if (const std::optional<Reader> bodies = r.Find("bodies")) {
    line.joints.assign(line.sections.size() - 1, {});
    std::vector<bool> taken(line.joints.size(), false);
    bodies->ForEachItem([&](const Reader& item, std::size_t) {
      item.CheckKeys();
      const int joint = item.Required<int>("joint");
      if (joint < 1 || joint > static_cast<int>(line.joints.size())) {
        item.Child("joint").Fail(std::to_string(joint) + " is not a joint of the line: its " +
                                 std::to_string(line.sections.size()) +
                                 " sections meet at joints 1.." +
                                 std::to_string(line.joints.size()));
      }
      if (taken[joint - 1]) {
        item.Child("joint").Fail(std::to_string(joint) + " has a body already");
      }
      taken[joint - 1] = true;
      mooring_fem::PointBody& body = line.joints[joint - 1];
      item.Optional("mass", body.mass);
      item.Optional("volume", body.volume);
      item.Optional("added_mass", body.added_mass);
      item.Optional("drag_area", body.drag_area);
    });
  }
  return line;
}

void ParseMooring(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  MooringSpec& mooring = scenario.mooring;
  ParseWater(r.Child("water"), mooring.water);
  if (std::optional<Reader> seabed = r.Find("seabed")) ParseSeabed(*seabed, mooring.seabed);
  if (std::optional<Reader> current = r.Find("current")) {
    if (mooring.current.key == "environment.current") {
      current->Fail("the current is given twice; keep it under environment.current only");
    }
    ParseCurrent(*current, mooring.current);
  }
  r.Child("line_types").ForEachItem([&](const Reader& type, std::size_t) {
    mooring.line_types.push_back(ParseLineType(type));
  });
  if (std::optional<Reader> defaults = r.Find("defaults")) {
    defaults->CheckKeys();
    defaults->Optional("segments", mooring.defaults.segments);
  }
  if (std::optional<Reader> points = r.Find("points")) {
    points->ForEachItem([&](const Reader& point, std::size_t i) {
      mooring.points.push_back(ParsePoint(point));
      for (std::size_t j = 0; j < i; ++j) {
        if (mooring.points[j].name == mooring.points[i].name) {
          point.Child("name").Fail("'" + mooring.points[i].name + "' is already the name of " +
                                   ItemPath("mooring.points", j));
        }
      }
    });
  }
  r.Child("lines").ForEachItem([&](const Reader& line, std::size_t i) {
    mooring.lines.push_back(
        ParseLine(line, static_cast<int>(i) + 1, mooring.defaults.segments, mooring.points));
  });
}

void ParseName(const Reader& r, Scenario& scenario) { scenario.name = r.As<std::string>(); }

void ParseSolver(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  SolverSpec& solver = scenario.solver;
  r.Optional("rtol", solver.rtol);
  r.Optional("atol_position", solver.atol_position);
  r.Optional("atol_velocity", solver.atol_velocity);
  r.Optional("max_order", solver.max_order);
  r.Optional("stability_limit_detection", solver.stability_limit_detection);
  r.Optional("max_step", solver.max_step);
  r.Optional("max_steps", solver.max_steps);
  r.Optional("linear_solver", solver.linear_solver);
}

// Angles under *_deg keys.
double Degrees(const Reader& r, std::string_view key, double fallback_rad) {
  if (std::optional<Reader> degrees = r.Find(key)) return AngleDegrees(*degrees);
  return fallback_rad;
}

void ParseVessel(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  VesselSpec v;
  v.hydrodynamics = r.Required<std::string>("hydrodynamics");
  r.Optional("length_scale", v.length_scale);
  r.Optional("mass", v.mass);
  r.Optional("centre_of_gravity", v.centre_of_gravity);
  r.Optional("radii_of_gyration", v.radii_of_gyration);
  if (std::optional<Reader> d = r.Find("damping")) {
    d->CheckKeys();
    d->Optional("surge_time", v.damping.surge_time);
    d->Optional("sway_time", v.damping.sway_time);
    d->Optional("yaw_time", v.damping.yaw_time);
    d->Optional("heave_ratio", v.damping.heave_ratio);
    d->Optional("roll_ratio", v.damping.roll_ratio);
    d->Optional("pitch_ratio", v.damping.pitch_ratio);
  }
  if (std::optional<Reader> p = r.Find("initial_pose")) {
    p->CheckKeys();
    p->Optional("x", v.initial_pose.x());
    p->Optional("y", v.initial_pose.y());
    v.initial_pose.z() = Degrees(*p, "heading_deg", 0.0);
  }
  if (std::optional<Reader> list = r.Find("thrusters")) {
    const std::vector<Reader> items = list->Items();
    if (items.empty())
      list->Fail("[] must hold at least one thruster (omit it for the seed layout)");
    list->ForEachItem([&](const Reader& t, std::size_t) {
      t.CheckKeys();
      ThrusterEntry e;
      e.name = t.Required<std::string>("name");
      e.x = t.Required<double>("x");
      e.y = t.Required<double>("y");
      e.angle = Degrees(t, "angle_deg", 0.0);
      t.Optional("azimuth", e.azimuth);
      e.max_thrust = t.Required<double>("max_thrust");
      t.Optional("min_thrust", e.min_thrust);
      t.Optional("weight", e.weight);
      t.Optional("time_constant", e.time_constant);
      t.Optional("rate_limit", e.rate_limit);
      v.thrusters.push_back(e);
    });
  }
  if (std::optional<Reader> h = r.Find("hull")) {
    h->CheckKeys();
    h->Optional("length", v.hull.length);
    h->Optional("beam", v.hull.beam);
    h->Optional("draught", v.hull.draught);
    h->Optional("displaced_volume", v.hull.displaced_volume);
    h->Optional("wetted_surface", v.hull.wetted_surface);
    h->Optional("cross_flow_drag_coefficient", v.hull.cross_flow_drag_coefficient);
    v.hull.form_factor = h->Maybe<double>("form_factor");
    h->Optional("kinematic_viscosity", v.hull.kinematic_viscosity);
  }
  if (std::optional<Reader> w = r.Find("windage")) {
    w->CheckKeys();
    w->Optional("frontal_area", v.windage.frontal_area);
    w->Optional("lateral_area", v.windage.lateral_area);
    v.windage.length = w->Maybe<double>("length");
    w->Optional("lateral_centroid", v.windage.lateral_centroid);
    w->Optional("air_density", v.windage.air_density);
  }
  if (std::optional<Reader> t = r.Find("turret")) {
    t->CheckKeys();
    TurretSpec& turret = v.turret;
    t->Optional("bearing", turret.bearing);
    t->Optional("x", turret.x);
    t->Optional("y", turret.y);
    turret.radius = t->Maybe<double>("radius");
    t->Optional("inertia", turret.inertia);
    t->Optional("friction_coefficient", turret.friction_coefficient);
    turret.bearing_radius = t->Maybe<double>("bearing_radius");
    t->Optional("damping", turret.damping);
    t->Optional("slip_rate", turret.slip_rate);
    if (std::optional<Reader> heading = t->Find("initial_heading_deg")) {
      turret.initial_heading = AngleDegrees(*heading);
    }
  }
  scenario.vessel = v;
}

void ParseEnvironment(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  EnvironmentSpec& e = scenario.environment;
  if (std::optional<Reader> w = r.Find("waves")) {
    w->CheckKeys();
    e.waves.enabled = true;
    if (std::optional<Reader> trains = w->Find("trains")) {
      for (const char* key :
           {"hs", "tp", "gamma", "direction_toward_deg", "spreading", "components"}) {
        if (std::optional<Reader> k = w->Find(key)) {
          k->Fail("give the JONSWAP sea (hs, tp, ...) or trains, not both");
        }
      }
      if (trains->Items().empty()) trains->Fail("[] must hold at least one regular wave");
      trains->ForEachItem([&](const Reader& train, std::size_t) {
        train.CheckKeys();
        vessel::WaveComponent c;
        c.omega = 2.0 * std::numbers::pi / train.Required<double>("period");
        c.amplitude = train.Required<double>("amplitude");
        c.phase = AngleDegrees(train.Child("phase_deg"));
        c.direction = AngleDegrees(train.Child("direction_toward_deg"));
        e.waves.trains.push_back(c);
      });
    } else {
      w->Attempt([&] { e.waves.significant_height = w->Needed("hs").As<double>(); });
      w->Attempt([&] { e.waves.peak_period = w->Needed("tp").As<double>(); });
      w->Optional("gamma", e.waves.gamma);
      e.waves.direction_toward = AngleDegrees(w->Needed("direction_toward_deg"));
      e.waves.spreading = w->Maybe<double>("spreading");
      w->Optional("components", e.waves.components);
    }
    w->Optional("on_lines", e.waves.on_lines);
    w->Optional("stretching", e.waves.stretching);
  }
  if (std::optional<Reader> w = r.Find("wind")) {
    w->CheckKeys();
    e.wind.enabled = true;
    e.wind.speed = w->Required<double>("speed");
    e.wind.direction_from = AngleDegrees(w->Child("direction_from_deg"));
    w->Optional("gust", e.wind.gust);
    w->Optional("components", e.wind.components);
  }
  if (std::optional<Reader> c = r.Find("current")) {
    scenario.mooring.current.key = "environment.current";
    ParseCurrent(*c, scenario.mooring.current);
  }
  r.Optional("hull_viscous_drag", e.hull_viscous_drag);
}

void ParseController(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  ControllerSpec& c = scenario.controller;
  c.type = r.Required<vessel::ControllerType>("type");
  r.Optional("rate_hz", c.rate);
  if (std::optional<Reader> p = r.Find("setpoint")) {
    p->CheckKeys();
    c.setpoint = Vec3(p->Required<double>("x"), p->Required<double>("y"),
                      AngleDegrees(p->Child("heading_deg")));
  }
  r.Optional("kp", c.kp);
  r.Optional("ki", c.ki);
  r.Optional("kd", c.kd);
  r.Optional("natural_period", c.natural_period);
  r.Optional("damping_ratio", c.damping_ratio);
  if (std::optional<Reader> h = r.Find("heading")) {
    h->CheckKeys();
    c.heading = ControllerSpec::HeadingLoop{h->Required<double>("natural_period"),
                                            h->Required<double>("damping_ratio")};
  }
}

void ParseNoise(const Reader& r, ChannelNoiseSpec& n) {
  r.CheckKeys();
  r.Optional("std_dev", n.std_dev);
  r.Optional("bias_walk", n.bias_walk);
  r.Optional("bias_time_constant", n.bias_time_constant);
  r.Optional("initial_bias", n.initial_bias);
  r.Optional("outlier_probability", n.outlier_probability);
  r.Optional("outlier_std_dev", n.outlier_std_dev);
}

/// A `faults:` list of one sensor (SensorsSpec::Fault): a cell's names its line, a GNSS
/// fault may name its channel.
enum class FaultTarget { kGnss, kGyro, kCell };
void ParseFaults(const Reader& r, FaultTarget target, std::vector<SensorsSpec::Fault>& faults) {
  r.ForEachItem([&](const Reader& item, std::size_t) {
    item.CheckKeys();
    SensorsSpec::Fault fault;
    fault.mode = item.Required<vessel::SensorFault::Mode>("mode");
    fault.time = item.Required<double>("time");
    fault.end = item.Maybe<double>("end");
    item.Optional("offset", fault.offset);
    item.Optional("rate", fault.rate);
    item.Optional("factor", fault.factor);
    item.Optional("gain", fault.gain);
    if (target == FaultTarget::kCell) fault.line = item.Required<int>("line");
    if (target == FaultTarget::kGnss) item.Optional("channel", fault.channel);
    faults.push_back(fault);
  });
}

void ParseSensors(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  SensorsSpec& s = scenario.sensors;
  if (std::optional<Reader> g = r.Find("gnss")) {
    g->CheckKeys();
    g->Optional("rate_hz", s.gnss_rate);
    if (std::optional<Reader> n = g->Find("north")) ParseNoise(*n, s.north);
    if (std::optional<Reader> n = g->Find("east")) ParseNoise(*n, s.east);
    g->Optional("dropout_probability", s.gnss_dropout_probability);
    g->Optional("dropout_mean_duration", s.gnss_dropout_mean_duration);
    if (std::optional<Reader> faults = g->Find("faults"))
      ParseFaults(*faults, FaultTarget::kGnss, s.gnss_faults);
  }
  if (std::optional<Reader> g = r.Find("gyro")) {
    g->CheckKeys();
    g->Optional("rate_hz", s.gyro_rate);
    if (std::optional<Reader> n = g->Find("heading")) ParseNoise(*n, s.heading);
    g->Optional("dropout_probability", s.gyro_dropout_probability);
    if (std::optional<Reader> faults = g->Find("faults"))
      ParseFaults(*faults, FaultTarget::kGyro, s.gyro_faults);
  }
  if (std::optional<Reader> t = r.Find("tension_cells")) {
    t->CheckKeys();
    s.tension_cells = true;
    t->Optional("rate_hz", s.tension_rate);
    if (std::optional<Reader> n = t->Find("noise")) ParseNoise(*n, s.tension_noise);
    if (std::optional<Reader> faults = t->Find("faults"))
      ParseFaults(*faults, FaultTarget::kCell, s.tension_faults);
  }
}

void ParseFailure(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  FailureSpec& f = scenario.failure;
  f.line = r.Required<int>("line");
  f.time = r.Required<double>("time");
  r.Optional("mode", f.mode);
  r.Optional("node", f.node);
  f.arc_length = r.Maybe<double>("arc_length");
}

void ParseDetectors(const Reader& r, Scenario& scenario) {
  r.ForEachItem([&](const Reader& item, std::size_t) {
    if (!item.IsMap()) item.Fail(item.Text() + " must be a map {type: ..., <parameter>: <number>}");
    item.CheckKeys();
    DetectorEntry entry;
    entry.type = item.Required<std::string>("type");
    item.Optional("label", entry.label);
    item.Optional("plugin", entry.plugin);
    if (item.Find("plugin") && entry.plugin.empty()) {
      item.Child("plugin").Fail("the plugin's path is empty");
    }
    // Every other key is a parameter of the detector type (a number; the registry checks
    // its name and range when the detectors are built).
    for (const std::string& key : item.Keys()) {
      if (key != "type" && key != "label" && key != "plugin") {
        if (std::optional<double> value = item.Maybe<double>(key)) entry.parameters[key] = *value;
      }
    }
    if (entry.label.empty()) entry.label = entry.type;
    scenario.detectors.push_back(entry);
  });
}

void ParseDetection(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  DetectionSpec& d = scenario.detection;
  r.Optional("observer", d.observer);
  r.Optional("training_seed", d.training_seed);
  r.Optional("pairs", d.pairs);
  r.Optional("measurement_variance", d.measurement_variance);
  d.switch_rate = r.Maybe<double>("switch_rate");
  d.sensor_checks = r.Maybe<bool>("sensor_checks");
  if (d.sensor_checks.value_or(false) && d.observer == simulation::ObserverType::kPassive) {
    r.Child("sensor_checks")
        .Fail("the passive observers make no sensor checks (they need observer: ekf)");
  }
  if (const auto m = r.Find("model")) {
    m->CheckKeys();
    d.model.wave_motion_std = m->Maybe<Vec3>("wave_motion_std");
    d.model.bias_std = m->Maybe<Vec3>("bias_std");
    d.model.bias_time_constant = m->Maybe<Vec3>("bias_time_constant");
    d.model.force_noise = m->Maybe<Vec3>("force_noise");
    d.model.mooring_damping_ratio = m->Maybe<Vec3>("mooring_damping_ratio");
  }
}

void ParseSimulation(const Reader& r, Scenario& scenario) {
  r.CheckKeys();
  SimulationSpec& s = scenario.simulation;
  r.Optional("duration", s.duration);
  r.Optional("output_rate_hz", s.output_rate);
  r.Optional("seed", s.seed);
  r.Optional("statistics_from", s.statistics_from);
}

// The top level: a reader per section (the schema lists the keys; `base` was resolved
// before reading).
struct Section {
  std::string_view key;
  void (*parse)(const Reader&, Scenario&);
};

constexpr Section kSections[] = {
    {"controller", ParseController},
    {"detection", ParseDetection},
    {"detectors", ParseDetectors},
    {"environment", ParseEnvironment},
    {"failure", ParseFailure},
    {"mooring", ParseMooring},
    {"name", ParseName},
    {"sensors", ParseSensors},
    {"simulation", ParseSimulation},
    {"solver", ParseSolver},
    {"vessel", ParseVessel},
};

void ParseDocument(const Reader& root, Scenario& scenario) {
  root.CheckKeys();
  for (const Section& section : kSections) {
    root.Attempt([&] {
      if (std::optional<Reader> value = root.Find(section.key)) section.parse(*value, scenario);
    });
  }
  // A vessel with load cells and no `detectors:` runs the detector made for them.
  if (!root.Find("detectors") && scenario.vessel && scenario.sensors.tension_cells) {
    scenario.detectors.push_back(
        {.type = "fused", .label = "fused", .parameters = {}, .plugin = {}});
  }
}

// ---------------------------------------------------------------------------------------
// Semantic checks.

class Checker {
 public:
  explicit Checker(const Scenario& scenario)
      : file_(scenario.source_path.empty() ? "scenario" : scenario.source_path),
        marks_(scenario.marks),
        origins_(scenario.origins) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& what) const {
    const auto [file, mark] = Locate(path);
    ThrowAt(file, mark, path, what);
  }

  void InRange(const std::string& path, int value, int low, int high) const {
    if (value < low || value > high) {
      Fail(path, std::to_string(value) + " must be in " + std::to_string(low) + ".." +
                     std::to_string(high));
    }
  }

  // A range that depends on other values (each key's own range is the schema's). `why`
  // (may be empty) says where the bound comes from; it follows the rule in parentheses.
  void Between(const std::string& path, double value, double low, double high,
               std::string_view unit, std::string_view why = {}) const {
    if (!(value >= low && value <= high)) {
      Fail(path, WithUnit(value, unit) + " must be in [" + FormatNumber(low) + ", " +
                     FormatNumber(high) + "]" + Why(why));
    }
  }

 private:
  // A value that was not written (a default) is reported at the nearest enclosing block
  // that was: "mooring.lines[2].id" falls back to the entry "mooring.lines[2]". Values
  // written in a base scenario are reported in that file.
  std::pair<std::string, SourceMark> Locate(std::string path) const {
    while (!path.empty()) {
      if (const auto found = marks_.find(path); found != marks_.end()) {
        return {FileOf(path), found->second};
      }
      const std::size_t cut = path.find_last_of(".[");
      path.resize(cut == std::string::npos ? 0 : cut);
    }
    return {file_, {}};
  }

  std::string FileOf(const std::string& path) const {
    const auto* origin = DeepestUnder(
        origins_, path, [](const auto& entry) -> const std::string& { return entry.first; });
    return origin ? origin->second : file_;
  }

  static std::string Why(std::string_view why) {
    return why.empty() ? "" : " (" + std::string(why) + ")";
  }

  std::string file_;
  const std::map<std::string, SourceMark>& marks_;
  const std::map<std::string, std::string>& origins_;
};

// Bounds between values (each key's own range is in the schema, scenarios/schema.cc).
constexpr double kMaxOutputRows = 1e9;  // simulation.duration x output_rate_hz
// An anchor lies on the seabed: the static catenary that starts every run and the
// detectors' quasi-static line model both take the seabed from the anchor.
constexpr double kAnchorAboveSeabed = 1.0;  // [m]
// Rounding of an anchor's depth written for a sloping seabed (to the centimetre).
constexpr double kAnchorBelowSeabed = 0.01;  // [m]

void CheckCurrent(const Checker& check, const CurrentProfile& current) {
  const std::string profile = current.key + ".profile";
  if (current.depth.size() != current.speed.size()) {
    check.Fail(profile, std::to_string(current.depth.size()) + " depths and " +
                            std::to_string(current.speed.size()) +
                            " speeds differ in number; every point needs both");
  }
  for (std::size_t i = 0; i < current.depth.size(); ++i) {
    const std::string point = ItemPath(profile, i);
    if (i > 0 && !(current.depth[i] > current.depth[i - 1])) {
      check.Fail(point + ".depth", WithUnit(current.depth[i], "m") +
                                       " must be greater than the previous point's depth " +
                                       WithUnit(current.depth[i - 1], "m"));
    }
  }
}

// Water displaced per metre by a line of the type [kg/m].
double DisplacedMass(const LineType& type, const Water& water) {
  return water.density * std::numbers::pi * type.diameter * type.diameter / 4.0;
}

// `buoyant_allowed`: no line of one type from an anchor to the vessel uses the type.
void CheckLineType(const Checker& check, const LineType& type, const std::string& path,
                   const Water& water, bool buoyant_allowed) {
  // A line no heavier than the water it displaces has no submerged weight: no catenary,
  // nothing holds it on the seabed.
  const double displaced = DisplacedMass(type, water);
  if (!buoyant_allowed && !(type.mass_per_length > displaced)) {
    check.Fail(path + ".mass_per_length",
               WithUnit(type.mass_per_length, "kg/m") + " must exceed the displaced water mass " +
                   Significant(displaced, 4) + " kg/m (the line would float)");
  }
  if (type.axial_damping && type.axial_damping_ratio) {
    check.Fail(path + ".axial_damping_ratio",
               FormatNumber(*type.axial_damping_ratio) + " cannot be combined with axial_damping " +
                   WithUnit(*type.axial_damping, "N s") + "; give one of them");
  }
}

void CheckLineTypes(const Checker& check, const MooringSpec& mooring) {
  for (std::size_t i = 0; i < mooring.line_types.size(); ++i) {
    const std::string path = ItemPath("mooring.line_types", i);
    for (std::size_t j = 0; j < i; ++j) {
      if (mooring.line_types[j].name == mooring.line_types[i].name) {
        check.Fail(path + ".name", "'" + mooring.line_types[i].name + "' is already the name of " +
                                       ItemPath("mooring.line_types", j));
      }
    }
    // A buoyant type is for sections of composite lines and lines between free points (whose
    // weight CheckLines and CheckPoints check as a whole); one no line uses floats nothing.
    bool alone = false;
    for (const LineSpec& line : mooring.lines) {
      for (const mooring_fem::LineSection& section : line.sections) {
        if (section.type != mooring.line_types[i].name) continue;
        // Buoyant sections may hang between heavier ones, and lines between free points
        // float or sink as a whole (CheckPoints).
        const bool between_points = line.lower_point >= 0 || line.upper_point >= 0;
        if (line.sections.size() == 1 && !between_points) alone = true;
      }
    }
    CheckLineType(check, mooring.line_types[i], path, mooring.water, !alone);
  }
}

// Messages name a line's entry as written; lines may already be sorted by id.
std::string LinePath(const LineSpec& line, std::size_t index) {
  return ItemPath("mooring.lines", line.entry > 0 ? line.entry - 1 : index);
}

// The fairlead's Earth position with the vessel at x, y [m], heading psi [rad].
Vec3 FairleadAt(const Vec3& body, double x, double y, double psi) {
  const double c = std::cos(psi);
  const double s = std::sin(psi);
  return Vec3(x + c * body.x() - s * body.y(), y + s * body.x() + c * body.y(), body.z());
}

// What keeps `line` from being held with its fairlead at `fairlead` (a message tail
// starting with the length), or "" if nothing does. It must reach: the straight
// anchor-fairlead distance, stretched by at most the elastic catenary's strain limit (10 %:
// a shorter line is a taut leg, stretched at rest, as polyester taut moorings are), is the
// least length that does. It must not be slack: a line as
// long as the horizontal distance plus the fairlead's height above the anchor lies on the
// seabed with no horizontal tension (the catenary's parameter H/w goes to 0), holds
// nothing and has no unique static shape. The tension grows smoothly between the two.
std::string LineGeometryProblem(const LineSpec& line, const Vec3& fairlead) {
  const double distance = (line.anchor - fairlead).norm();
  const double length = line.Length();
  if (length * (1.0 + mooring_fem::kMaxCatenaryStrain) < distance) {
    return WithUnit(length, "m") + " is shorter than the anchor-fairlead distance " +
           Fixed(distance, 1) + " m";
  }
  const double span = (line.anchor - fairlead).head<2>().norm();
  const double height = line.anchor.z() - fairlead.z();
  // A line from an anchor held in the water may hang below it.
  if (!line.anchor_in_water && !(length < span + height)) {
    return WithUnit(length, "m") +
           " must be shorter than the horizontal anchor-fairlead distance plus the fairlead's "
           "height above the anchor, " +
           Fixed(span, 1) + " + " + Fixed(height, 1) + " = " + Fixed(span + height, 1) +
           " m (a longer line lies slack on the seabed, with no horizontal tension)";
  }
  return "";
}

void CheckSeabed(const Checker& check, const Seabed& seabed) {
  if (!seabed.grid.empty() && seabed.slope != 0.0) {
    check.Fail("mooring.seabed.grid",
               "a depth grid cannot be combined with slope_deg; give one of them");
  }
}

void CheckLines(const Checker& check, const MooringSpec& mooring) {
  const mooring_fem::SeabedSurface seabed(mooring.seabed, mooring.water.depth);
  const std::vector<LineSpec>& lines = mooring.lines;
  if (lines.empty()) check.Fail("mooring.lines", "[] must list at least one line");
  const int count = static_cast<int>(lines.size());
  std::vector<std::string> type_names;
  for (const LineType& type : mooring.line_types) type_names.push_back(type.name);

  for (std::size_t i = 0; i < lines.size(); ++i) {
    const LineSpec& line = lines[i];
    const std::string path = LinePath(line, i);
    for (std::size_t j = 0; j < i; ++j) {
      if (lines[j].id == line.id) {
        check.Fail(path + ".id",
                   std::to_string(line.id) + " is already the id of " + LinePath(lines[j], j));
      }
    }
    if (line.id < 1 || line.id > count) {
      check.Fail(path + ".id", std::to_string(line.id) + " must be in 1.." + std::to_string(count) +
                                   " (ids number the " + std::to_string(count) + " lines from 1)");
    }
    for (std::size_t k = 0; k < line.sections.size(); ++k) {
      const std::string& type = line.sections[k].type;
      if (std::find(type_names.begin(), type_names.end(), type) == type_names.end()) {
        check.Fail(
            line.written_in_sections ? ItemPath(path + ".sections", k) + ".type" : path + ".type",
            "unknown line type '" + type + "' (known: " + JoinSorted(type_names) + ")");
      }
    }

    if (line.lower_point >= 0 || line.upper_point >= 0) continue;  // CheckPoints
    const double depth = seabed.DepthAt(line.anchor.x(), line.anchor.y());
    const std::string seabed_there =
        (seabed.flat() ? "the seabed at depth " : "the seabed there, at depth ") +
        Significant(depth, 6) + " m";
    if (line.anchor.z() > depth + kAnchorBelowSeabed) {
      check.Fail(path + ".anchor",
                 "z = " + WithUnit(line.anchor.z(), "m") + " is below " + seabed_there);
    }
    // With the vessel at the origin and heading 0 the fairlead's Earth position is its
    // body position.
    const Vec3& fairlead = line.fairlead_body;
    if (line.anchor.z() < fairlead.z()) {
      check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") +
                                       " is above the fairlead at z = " +
                                       WithUnit(fairlead.z(), "m") + " (z points down)");
    }
    if (line.anchor.z() == fairlead.z()) {
      check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") +
                                       " is level with the fairlead; it must be below it (z "
                                       "points down)");
    }
    if (line.anchor_in_water) {
      if (!(line.anchor.z() > 0.0)) {
        check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") +
                                         " is not below the water surface (z points down, 0 at "
                                         "the surface)");
      }
    } else if (line.anchor.z() < depth - kAnchorAboveSeabed) {
      check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") + " is above " +
                                       seabed_there + " (an anchor lies on the seabed, within " +
                                       WithUnit(kAnchorAboveSeabed, "m") +
                                       "; one held in the water says anchor_in_water: true)");
    }
    if (const std::string problem = LineGeometryProblem(line, fairlead); !problem.empty()) {
      check.Fail(path + (line.written_in_sections ? ".sections" : ".length"), problem);
    }
    if (line.sections.size() > 1) {  // buoyant sections may hang between heavier ones
      const Water& water = mooring.water;
      double weight = 0.0;  // in water [N]
      for (const mooring_fem::LineSection& section : line.sections) {
        for (const LineType& type : mooring.line_types) {
          if (type.name != section.type) continue;
          weight +=
              (type.mass_per_length - DisplacedMass(type, water)) * water.gravity * section.length;
        }
      }
      for (const mooring_fem::PointBody& body : line.joints) {
        weight += (body.mass - water.density * body.volume) * water.gravity;
      }
      if (!(weight > 0.0)) {
        check.Fail(path + ".sections",
                   "the line weighs " + Significant(weight / 1e3, 4) +
                       " kN in water with its bodies: a line lighter than the water it "
                       "displaces would float");
      }
    }
  }
}

// The reach and slack rules of CheckLines again, with the vessel where `run` starts it and
// the fairleads where its turret starts them: a turret given its own initial heading holds
// them at that heading, turned about the turret centre from where the hull's would put
// them (the plant's OnTurret at the angle initial heading - hull heading).
void CheckLinesAtInitialPose(const Checker& check, const Scenario& scenario) {
  if (!scenario.vessel) return;
  const Vec3& pose = scenario.vessel->initial_pose;
  const TurretSpec& turret = scenario.vessel->turret;
  const double alpha = scenario.vessel->InitialTurretAngle();
  if (pose == Vec3::Zero() && alpha == 0.0) return;  // the origin: CheckLines has seen it
  const Vec3 centre(turret.x, turret.y, 0.0);
  std::string where = "at x " + WithUnit(pose.x(), "m") + ", y " + WithUnit(pose.y(), "m") +
                      ", heading " + Significant(pose.z() / kDegree, 10) + " deg";
  if (turret.bearing != vessel::TurretBearing::kLocked && turret.initial_heading) {
    where += ", turret heading " + Significant(*turret.initial_heading / kDegree, 10) + " deg";
  }
  const std::vector<LineSpec>& lines = scenario.mooring.lines;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].lower_point >= 0 || lines[i].upper_point >= 0) continue;
    const Vec3 on_turret = centre + FairleadAt(lines[i].fairlead_body - centre, 0.0, 0.0, alpha);
    const Vec3 fairlead = FairleadAt(on_turret, pose.x(), pose.y(), pose.z());
    if (const std::string problem = LineGeometryProblem(lines[i], fairlead); !problem.empty()) {
      check.Fail("vessel.initial_pose",
                 where + ", " + LinePath(lines[i], i) +
                     (lines[i].written_in_sections ? ".sections " : ".length ") + problem);
    }
  }
}

// Free points: in the water, apart from each other, each with a line; the lines at them long
// enough for a start; and every set of points joined by lines that reaches no anchor or
// fairlead heavier than the water it displaces (else it floats away).
void CheckPoints(const Checker& check, const MooringSpec& mooring) {
  const std::vector<PointSpec>& points = mooring.points;
  const std::vector<LineSpec>& lines = mooring.lines;
  const mooring_fem::SeabedSurface seabed(mooring.seabed, mooring.water.depth);
  const Water& water = mooring.water;
  const int np = static_cast<int>(points.size());
  constexpr double kApart = 0.01;  // [m]
  const auto not_below_seabed = [&](const std::string& key, const Vec3& r) {
    const double depth = seabed.DepthAt(r.x(), r.y());
    if (r.z() > depth + kAnchorBelowSeabed) {
      check.Fail(key, "z = " + WithUnit(r.z(), "m") + " is below the seabed there, at depth " +
                          Significant(depth, 6) + " m");
    }
  };
  for (int p = 0; p < np; ++p) {
    const std::string path = ItemPath("mooring.points", p) + ".position";
    const Vec3& r = points[p].position;
    if (!(r.z() > 0.0)) {
      check.Fail(path, "z = " + WithUnit(r.z(), "m") +
                           " is not below the water surface (z points down, 0 at the surface)");
    }
    not_below_seabed(path, r);
    for (int q = 0; q < p; ++q) {
      if ((points[q].position - r).norm() < kApart) {
        check.Fail(path, "coincides with " + ItemPath("mooring.points", q) +
                             " (points must be at least " + WithUnit(kApart, "m") + " apart)");
      }
    }
  }
  // Union-find over the points, joined by lines; a set is held if a line of it has a fixed
  // end. Weight in water of each set: its bodies and its lines.
  std::vector<int> parent(np);
  for (int p = 0; p < np; ++p) parent[p] = p;
  const auto root = [&](int p) {
    while (parent[p] != p) p = parent[p] = parent[parent[p]];
    return p;
  };
  std::vector<int> lines_at(np, 0);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const LineSpec& line = lines[i];
    if (line.lower_point < 0 && line.upper_point < 0) continue;
    const std::string path = LinePath(line, i);
    for (const int p : {line.lower_point, line.upper_point}) {
      if (p >= 0) ++lines_at[p];
    }
    if (line.lower_point >= 0 && line.lower_point == line.upper_point) {
      check.Fail(path + ".to", "'" + line.to + "' is the point the line starts from too");
    }
    if (line.lower_point >= 0 && line.upper_point >= 0) {
      parent[root(line.lower_point)] = root(line.upper_point);
    }
    if (line.lower_point >= 0 && line.upper_point < 0 && line.Segments() < 2) {
      check.Fail(path + (line.written_in_sections ? ".sections" : ".segments"),
                 "a line from a free point to the vessel needs 2 segments or more");
    }
    // Where its ends start: they must be apart.
    const Vec3 lower = line.lower_point >= 0 ? points[line.lower_point].position : line.anchor;
    const Vec3 upper =
        line.upper_point >= 0 ? points[line.upper_point].position : line.fairlead_body;
    if ((upper - lower).norm() < kApart) {
      check.Fail(path + (line.upper_point >= 0 ? ".to" : ".fairlead"),
                 "starts where the line's lower end does; its ends must be at least " +
                     WithUnit(kApart, "m") + " apart");
    }
    if (line.lower_point < 0) not_below_seabed(path + ".anchor", line.anchor);
  }
  for (int p = 0; p < np; ++p) {
    if (lines_at[p] == 0) {
      check.Fail(ItemPath("mooring.points", p),
                 "no line starts or ends at '" + points[p].name + "' (from, to)");
    }
  }
  std::vector<char> held(np, 0);
  std::vector<double> weight(np, 0.0);  // per set root [N]
  for (int p = 0; p < np; ++p) {
    const mooring_fem::PointBody& b = points[p].body;
    weight[root(p)] += (b.mass - water.density * b.volume) * water.gravity;
  }
  for (const LineSpec& line : lines) {
    if (line.lower_point < 0 && line.upper_point < 0) continue;
    const int r = root(line.lower_point >= 0 ? line.lower_point : line.upper_point);
    if (line.lower_point < 0 || line.upper_point < 0) held[r] = 1;
    for (const mooring_fem::LineSection& section : line.sections) {
      for (const LineType& type : mooring.line_types) {
        if (type.name != section.type) continue;
        weight[r] +=
            (type.mass_per_length - DisplacedMass(type, water)) * water.gravity * section.length;
      }
    }
    for (const mooring_fem::PointBody& body : line.joints) {
      weight[r] += (body.mass - water.density * body.volume) * water.gravity;
    }
  }
  for (int p = 0; p < np; ++p) {
    if (root(p) != p || held[p] || weight[p] > 0.0) continue;
    check.Fail(ItemPath("mooring.points", p),
               "'" + points[p].name + "' and the points and lines joined to it reach no anchor " +
                   "or fairlead and weigh " + Significant(weight[p] / 1e3, 4) +
                   " kN in water: they would float away");
  }
}

// The turret: on the hull, the fairleads on it, a physical bearing.
void CheckTurret(const Checker& check, const Scenario& scenario) {
  if (!scenario.vessel) return;
  const VesselSpec& v = *scenario.vessel;
  const TurretSpec& t = v.turret;
  if (t.initial_heading && t.bearing == vessel::TurretBearing::kLocked) {
    check.Fail("vessel.turret.initial_heading_deg",
               "a locked turret turns with the hull: give bearing free or friction, or leave "
               "initial_heading_deg out");
  }
  const double half_length = 0.5 * v.hull.length, half_beam = 0.5 * v.hull.beam;
  if (t.bearing == vessel::TurretBearing::kLocked && !t.radius) {
    // No turret that turns: the fairleads are points of the hull (a spread mooring may have
    // them at the bow and the stern), each within its waterplane rectangle L x B.
    const std::vector<LineSpec>& lines = scenario.mooring.lines;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const Vec3& f = lines[i].fairlead_body;
      if (lines[i].upper_point >= 0) continue;  // not at the vessel
      if (!(std::abs(f.x()) <= half_length && std::abs(f.y()) <= half_beam)) {
        check.Fail(LinePath(lines[i], i) + ".fairlead",
                   "(" + FormatNumber(f.x()) + ", " + FormatNumber(f.y()) +
                       ") m is off the hull: |x| must be <= hull.length / 2 = " +
                       WithUnit(half_length, "m") +
                       " and |y| <= hull.beam / 2 = " + WithUnit(half_beam, "m"));
      }
    }
    return;
  }
  const double radius = TurretRadius(scenario);
  // The turret's circle within the hull's waterplane rectangle L x B.
  if (!(std::abs(t.x) + radius <= half_length)) {
    check.Fail("vessel.turret.x",
               WithUnit(t.x, "m") + " puts the turret (radius " + WithUnit(radius, "m") +
                   ") outside the hull: |x| + radius must be <= hull.length / 2 = " +
                   WithUnit(half_length, "m"));
  }
  if (!(std::abs(t.y) + radius <= half_beam)) {
    check.Fail("vessel.turret.y",
               WithUnit(t.y, "m") + " puts the turret (radius " + WithUnit(radius, "m") +
                   ") outside the hull: |y| + radius must be <= hull.beam / 2 = " +
                   WithUnit(half_beam, "m"));
  }
  if (t.radius) {
    const std::vector<LineSpec>& lines = scenario.mooring.lines;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const double distance =
          std::hypot(lines[i].fairlead_body.x() - t.x, lines[i].fairlead_body.y() - t.y);
      if (distance > *t.radius * (1.0 + 1e-9)) {
        check.Fail("vessel.turret.radius",
                   WithUnit(*t.radius, "m") + " does not reach the fairlead of " +
                       LinePath(lines[i], i) + ", " + WithUnit(distance, "m") +
                       " from the turret centre (the fairleads are on the turret)");
      }
    }
  }
}

// The hull's particulars (the current load, vessel/hull_loads.h): a hull holds no more
// than its bounding box L x B x T.
void CheckHull(const Checker& check, const HullSpec& h) {
  const double box = h.length * h.beam * h.draught;
  if (!(h.displaced_volume <= box)) {
    check.Fail("vessel.hull.displaced_volume",
               WithUnit(h.displaced_volume, "m^3") + " must be <= length x beam x draught = " +
                   FormatNumber(box) + " m^3 (a block coefficient <= 1)");
  }
}

// The hull and superstructure above water (the wind load, vessel/hull_loads.h): the
// lateral area's centroid lies on the vessel.
void CheckWindage(const Checker& check, const VesselSpec& v) {
  const WindageSpec& w = v.windage;
  const double half = 0.5 * w.length.value_or(v.hull.length);
  check.Between("vessel.windage.lateral_centroid", w.lateral_centroid, -half, half, "m",
                w.length ? "on the vessel: within half of windage.length from midship"
                         : "on the vessel: within half of hull.length from midship");
}

void CheckVessel(const Checker& check, const VesselSpec& v) {
  for (const char* ext : {".1", ".hst"}) {
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(v.hydrodynamics + ext, ignored)) {
      check.Fail("vessel.hydrodynamics",
                 "'" + v.hydrodynamics + "': no WAMIT file '" + v.hydrodynamics + ext + "'");
    }
  }
  CheckHull(check, v.hull);
  CheckWindage(check, v);
  for (std::size_t i = 0; i < v.thrusters.size(); ++i) {
    const ThrusterEntry& t = v.thrusters[i];
    for (std::size_t j = 0; j < i; ++j) {
      if (v.thrusters[j].name == t.name) {
        check.Fail(ItemPath("vessel.thrusters", i) + ".name",
                   "'" + t.name + "' is used by thruster " + std::to_string(j + 1) + " too");
      }
    }
  }
}

void CheckEnvironment(const Checker& check, const Scenario& scenario) {
  const EnvironmentSpec& e = scenario.environment;
  if (!e.waves.enabled) return;
  if (!scenario.vessel && !e.waves.on_lines) {
    check.Fail("environment.waves",
               "waves need a vessel section (its RAOs and drift) or on_lines: true (the lines "
               "feel them)");
  }
  const double g = scenario.mooring.water.gravity;
  if (!e.waves.trains.empty()) {
    // Each regular wave's steepness 2 a / L, L = g T^2 / (2 pi) its deep-water length:
    // regular waves break at 1/7 (Michell 1893).
    for (std::size_t i = 0; i < e.waves.trains.size(); ++i) {
      const vessel::WaveComponent& c = e.waves.trains[i];
      const double steepness = 2.0 * c.amplitude * c.omega * c.omega / (2.0 * std::numbers::pi * g);
      if (!(steepness <= 1.0 / 7.0)) {
        check.Fail(ItemPath("environment.waves.trains", i) + ".amplitude",
                   WithUnit(c.amplitude, "m") + " is too steep for period " +
                       WithUnit(2.0 * std::numbers::pi / c.omega, "s") + ": 2 a / L = " +
                       Significant(steepness, 3) + " must be <= 1/7 (such waves break)");
      }
    }
    return;
  }
  const double hs = e.waves.significant_height;
  const double tp = e.waves.peak_period;
  // Steepness Hs / Lp, Lp = g Tp^2 / (2 pi) the deep-water length of the peak wave: waves
  // break at 1/7 (Michell 1893), and Hs is below the highest waves of the sea state.
  const double steepness = hs * 2.0 * std::numbers::pi / (g * tp * tp);
  if (!(steepness <= 1.0 / 7.0)) {
    check.Fail("environment.waves.hs",
               WithUnit(hs, "m") + " is too steep for tp " + WithUnit(tp, "s") +
                   ": Hs / (g Tp^2 / (2 pi)) = " + Significant(steepness, 3) +
                   " must be <= 1/7 (such waves break)");
  }
}

/// One sensor's faults: each mode's own size given and in range, no other mode's, a time
/// within the run and an end after it; no two faults that replace the reading (dead,
/// stuck) on one channel at once.
void CheckFaults(const Checker& check, const Scenario& scenario,
                 const std::vector<SensorsSpec::Fault>& faults, const std::string& sensor,
                 const std::string& unit) {
  using Mode = vessel::SensorFault::Mode;
  const auto path_of = [&](std::size_t i) {
    return sensor + ".faults[" + std::to_string(i + 1) + "]";
  };
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const SensorsSpec::Fault& f = faults[i];
    const std::string path = path_of(i);
    if (sensor == "sensors.tension_cells") {
      check.InRange(path + ".line", f.line, 1, static_cast<int>(scenario.mooring.lines.size()));
    }
    if (!(f.time < scenario.simulation.duration)) {
      check.Fail(path + ".time", WithUnit(f.time, "s") +
                                     " is not before the end of the run (simulation.duration " +
                                     WithUnit(scenario.simulation.duration, "s") + ")");
    }
    if (f.end && !(*f.end > f.time)) {
      check.Fail(path + ".end", WithUnit(*f.end, "s") + " must be after the fault's time (" +
                                    WithUnit(f.time, "s") + ")");
    }
    for (std::size_t k = 0; k < i; ++k) {
      const SensorsSpec::Fault& e = faults[k];
      const auto replacing = [](Mode m) { return m == Mode::kDead || m == Mode::kStuck; };
      const bool replaces = replacing(f.mode) && replacing(e.mode);
      const bool same_channel =
          f.line == e.line && (f.channel == e.channel || f.channel == GnssFaultChannel::kBoth ||
                               e.channel == GnssFaultChannel::kBoth);
      const bool overlap = f.time < e.end.value_or(std::numeric_limits<double>::infinity()) &&
                           e.time < f.end.value_or(std::numeric_limits<double>::infinity());
      if (replaces && same_channel && overlap) {
        check.Fail(path + ".time",
                   "the " + std::string(ChoiceName(f.mode)) + " fault at " + WithUnit(f.time, "s") +
                       " overlaps " + path_of(k) + " (" + std::string(ChoiceName(e.mode)) + " at " +
                       WithUnit(e.time, "s") +
                       ") on the same channel: each replaces the sensor's reading, so the two "
                       "cannot act at once (other faults add to them in the order listed)");
      }
    }
    // Each size belongs to one mode; a size that leaves the sensor as it is (its neutral
    // value, the default) is one not given.
    const FaultModeSize& own = FaultModeSizeOf(f.mode);
    for (const FaultModeSize& m : FaultModeSizes()) {
      if (&m != &own && m.size != nullptr && f.*m.size != m.neutral) {
        check.Fail(path + "." + std::string(vessel::SensorFaultSizeKey(m.mode)),
                   "only applies to mode '" + std::string(ChoiceName(m.mode)) + "' (the mode is '" +
                       std::string(ChoiceName(f.mode)) + "')");
      }
    }
    if (own.size != nullptr && f.*own.size == own.neutral) {
      std::string need(own.need);
      if (const std::size_t at = need.find("{unit}"); at != std::string::npos) {
        need.replace(at, 6, unit);
      }
      check.Fail(path + "." + std::string(vessel::SensorFaultSizeKey(own.mode)), need);
    }
  }
}

void CheckSensorFaults(const Checker& check, const Scenario& scenario) {
  const SensorsSpec& s = scenario.sensors;
  CheckFaults(check, scenario, s.gnss_faults, "sensors.gnss", "m");
  CheckFaults(check, scenario, s.gyro_faults, "sensors.gyro", "rad");
  CheckFaults(check, scenario, s.tension_faults, "sensors.tension_cells", "N");
}

void CheckFailure(const Checker& check, const Scenario& scenario) {
  const FailureSpec& f = scenario.failure;
  if (f.line == 0 && !scenario.marks.contains("failure")) return;
  const int lines = static_cast<int>(scenario.mooring.lines.size());
  check.InRange("failure.line", f.line, 1, lines);
  if (!(f.time < scenario.simulation.duration)) {
    check.Fail("failure.time", WithUnit(f.time, "s") +
                                   " is not before the end of the run (simulation.duration " +
                                   WithUnit(scenario.simulation.duration, "s") + ")");
  }
  const bool node_given = scenario.marks.contains("failure.node");
  if (f.mode != mooring_fem::FailureMode::kNode && (node_given || f.arc_length)) {
    check.Fail(
        node_given ? "failure.node" : "failure.arc_length",
        "only applies to mode 'node' (the mode is '" + std::string(ChoiceName(f.mode)) + "')");
  }
  if (f.mode == mooring_fem::FailureMode::kNode) {
    if (node_given == f.arc_length.has_value()) {
      check.Fail("failure.mode", "mode 'node' needs exactly one of node or arc_length");
    }
    const LineSpec* line = nullptr;
    for (const LineSpec& l : scenario.mooring.lines) {
      if (l.id == f.line) line = &l;
    }
    if (line != nullptr && node_given) {
      check.InRange("failure.node", f.node, 1, line->Segments() - 1);
    }
    if (line != nullptr && f.arc_length &&
        !(*f.arc_length > 0.0 && *f.arc_length < line->Length())) {
      check.Fail("failure.arc_length", WithUnit(*f.arc_length, "m") +
                                           " must be inside the line (0, " +
                                           WithUnit(line->Length(), "m") + ")");
    }
  }
}

void CheckDetectors(const Checker& check, const Scenario& scenario) {
  const std::vector<DetectorEntry>& d = scenario.detectors;
  for (std::size_t i = 0; i < d.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (d[i].label == d[j].label) {
        check.Fail(ItemPath("detectors", i), "label '" + d[i].label + "' is used by detectors[" +
                                                 std::to_string(j + 1) +
                                                 "] too (give one a `label`)");
      }
    }
  }
  if (!d.empty() && !scenario.vessel) check.Fail("detectors", "needs a vessel section");
  // The detectors' line models lay each plain line from an anchor on the seabed.
  const std::vector<LineSpec>& lines = scenario.mooring.lines;
  for (std::size_t i = 0; i < lines.size() && !d.empty(); ++i) {
    if (lines[i].anchor_in_water) {
      check.Fail(LinePath(lines[i], i) + ".anchor_in_water",
                 "the detectors' line models have no line held in the water; run this "
                 "mooring without detectors");
    }
  }
}

void CheckSimulation(const Checker& check, const SimulationSpec& s) {
  if (!(s.statistics_from < s.duration)) {
    check.Fail("simulation.statistics_from", WithUnit(s.statistics_from, "s") +
                                                 " is not before the end of the run (" +
                                                 WithUnit(s.duration, "s") + ")");
  }
  const double rows = s.duration * s.output_rate;
  if (!(rows <= kMaxOutputRows)) {
    check.Fail("simulation.output_rate_hz",
               WithUnit(s.output_rate, "Hz") + " for simulation.duration " +
                   WithUnit(s.duration, "s") + " would write " + Significant(rows, 4) +
                   " rows (at most " + FormatNumber(kMaxOutputRows) + ")");
  }
}

}  // namespace

void FailAt(const Scenario& scenario, const std::string& path, const std::string& what) {
  Checker(scenario).Fail(path, what);
}

void PlaceAtKey(const Scenario& scenario, const InputError& error, std::string_view prefix) {
  const std::string message = error.what();
  const std::size_t colon = message.find(": ");
  if (colon == std::string::npos || message.compare(0, prefix.size(), prefix) != 0) throw error;
  FailAt(scenario, message.substr(0, colon), message.substr(colon + 2));
}

void Validate(const Scenario& scenario) {
  std::vector<std::string> errors;
  const Checker check(scenario);
  // Each group of checks reports its first problem; the groups are independent.
  const auto group = [&](auto&& checks) {
    try {
      checks();
    } catch (const InputError& error) {
      errors.push_back(error.what());
    }
  };
  const MooringSpec& mooring = scenario.mooring;
  group([&] { CheckCurrent(check, mooring.current); });
  // Without lines, or with line types in doubt, the checks of lines and of line numbers
  // would only repeat the problem.
  if (mooring.lines.empty()) check.Fail("mooring.lines", "[] must list at least one line");
  const std::size_t before_lines = errors.size();
  group([&] { CheckLineTypes(check, mooring); });
  group([&] { CheckSeabed(check, mooring.seabed); });
  if (errors.size() == before_lines) group([&] { CheckLines(check, mooring); });
  if (errors.size() == before_lines) group([&] { CheckPoints(check, mooring); });
  const bool lines_hold = errors.size() == before_lines;
  if (scenario.vessel) group([&] { CheckVessel(check, *scenario.vessel); });
  group([&] { CheckTurret(check, scenario); });
  // The same rules at the start pose: only news if they hold at the origin.
  if (lines_hold) group([&] { CheckLinesAtInitialPose(check, scenario); });
  group([&] { CheckEnvironment(check, scenario); });
  group([&] { CheckSensorFaults(check, scenario); });
  group([&] { CheckSimulation(check, scenario.simulation); });
  group([&] { CheckFailure(check, scenario); });
  group([&] { CheckDetectors(check, scenario); });
  group([&] {
    const bool vessel_needed = scenario.marks.contains("controller") ||
                               scenario.marks.contains("sensors") ||
                               scenario.marks.contains("failure");
    if (vessel_needed && !scenario.vessel) {
      const char* what = scenario.marks.contains("controller") ? "controller"
                         : scenario.marks.contains("sensors")  ? "sensors"
                                                               : "failure";
      check.Fail(what, "needs a vessel section");
    }
  });
  ThrowCollected(std::move(errors));
}

namespace {

// Sets `key.path=value` in the document: maps by key (created if missing), lists by [i]
// (1-based, existing entries only); the value is parsed as YAML. Returns the key path.
std::string ApplyOverride(YAML::Node& root, const std::string& assignment) {
  const std::size_t equals = assignment.find('=');
  const std::string given = " " + assignment;  // after the option's name, "set"
  if (equals == std::string::npos || equals == 0) {
    throw OptionError("set", given + ": expected key.path=value (e.g. controller.type=pi)");
  }
  const std::string path = assignment.substr(0, equals);
  const std::string value = assignment.substr(equals + 1);
  std::vector<KeyStep> steps;
  try {
    steps = SplitKeyPath(path);
  } catch (const InputError& error) {
    throw OptionError("set", given + ": " + error.what());
  }
  if (steps.front().key == "base") {
    throw OptionError(
        "set",
        given + ": base is read before the overrides apply; write base: in the scenario file");
  }
  YAML::Node parsed;
  try {
    const std::vector<YAML::Node> documents = YAML::LoadAll(value);
    if (documents.size() > 1)
      throw OptionError("set", given + ": the value holds more than one YAML document");
    parsed = documents.empty() ? YAML::Node() : documents[0];
  } catch (const YAML::Exception& error) {
    throw OptionError("set", given + ": the value is not YAML: " + error.msg);
  }
  try {
    CheckOverrideUntagged(parsed, value, "");
  } catch (const InputError& e) {
    throw OptionError("set", given + e.what());
  }
  // Walk with node references (yaml-cpp nodes are handles).
  std::vector<YAML::Node> chain{root};
  for (std::size_t s = 0; s < steps.size(); ++s) {
    YAML::Node current = chain.back();
    const bool last = s + 1 == steps.size();
    const std::string& key = steps[s].key;
    if (!key.empty()) {
      if (!current.IsMap() && !current.IsNull()) {
        throw OptionError("set", given + ": '" + key + "' is under something that is not a map");
      }
      if (last) {
        current[key] = parsed;
      } else {
        YAML::Node next = current[key];
        if (!next.IsDefined() || next.IsNull()) {
          current[key] = YAML::Node(YAML::NodeType::Map);
          next = current[key];
        }
        chain.push_back(next);
      }
    } else {
      const int index = steps[s].index;
      if (!current.IsSequence() || index > static_cast<int>(current.size())) {
        throw OptionError("set",
                          given + ": there is no list entry [" + std::to_string(index) + "]");
      }
      if (last) {
        current[index - 1] = parsed;
      } else {
        chain.push_back(current[index - 1]);
      }
    }
  }
  return path;  // SplitKeyPath takes one spelling only: the canonical one
}

// ---------------------------------------------------------------------------------------
// Includes: `base: other.yaml` at the top of a scenario. The base (itself possibly with a
// base) is read first; this file's keys override its keys, maps merged key by key, lists
// and scalars replaced whole, a key set to null (`failure: ~`) removing the base's. Every
// value keeps the position in the file it was written in, for messages.

// A scenario file and the texts its values were written in.
struct Included {
  std::string file;
  const std::string* text = nullptr;
  // Subtrees written in a base file (the deepest entry wins), as ParseContext::origins.
  std::vector<ParseContext::Origin> origins;

  // The file (and text) the value at `path` was written in.
  ParseContext::Origin OriginOf(const std::string& path) const {
    const ParseContext::Origin* found = DeepestUnder(
        origins, path, [](const ParseContext::Origin& o) -> const std::string& { return o.path; });
    return found ? *found : ParseContext::Origin{path, file, text};
  }
};

// The value under `key` of map `node`, or an invalid node (without creating the key).
YAML::Node Lookup(const YAML::Node& node, const std::string& key) {
  for (const auto& entry : node) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) return entry.second;
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

// Merges map `base` (of `from`) under map `top` at key path `path`: what `top` lacks is
// taken from `base` (with its origin), maps in both are merged, a null in `top` removes.
void MergeBase(YAML::Node top, const YAML::Node& base, const std::string& path,
               const Included& from, Included& into) {
  for (const auto& entry : base) {
    if (!entry.first.IsScalar()) continue;  // the loader reports it where it is read
    const std::string& name = entry.first.Scalar();
    // A scenario is named by its own file (or its own `name`), never by its base's.
    if (path.empty() && (name == "base" || name == "name")) continue;
    const std::string child = KeyPath(path, name);
    YAML::Node own = Lookup(top, name);
    if (!own.IsDefined()) {
      top.force_insert(entry.first, entry.second);  // the key and value keep their marks
      const ParseContext::Origin origin = from.OriginOf(child);
      into.origins.push_back({child, origin.file, origin.text});
      for (const ParseContext::Origin& deeper : from.origins) {
        if (deeper.path != child && UnderPath(deeper.path, child)) into.origins.push_back(deeper);
      }
    } else if (own.IsNull()) {
      top.remove(name);
    } else if (own.IsMap() && entry.second.IsMap()) {
      MergeBase(own, entry.second, child, from, into);
    }
  }
}

// Where a relative path written in `file` points, relative to `top_file`'s folder.
std::string Rebased(const std::string& value, const std::string& file,
                    const std::string& top_file) {
  namespace fs = std::filesystem;
  if (value.empty() || fs::path(value).is_absolute()) return value;
  const fs::path from = fs::path(file).parent_path(), to = fs::path(top_file).parent_path();
  if (from == to) return value;
  const fs::path target = (from / value).lexically_normal();
  const fs::path relative = target.lexically_relative(to.empty() ? fs::path(".") : to);
  return relative.empty() ? target.string() : relative.string();
}

// Reads the base chain of `document` (the text of `self.file`) into it. `chain` holds the
// files being read, outermost first (a file met twice is a cycle); `texts` keeps the bases'
// texts alive for the marks. Throws a located InputError at the `base:` value.
void ResolveBase(YAML::Node document, Included& self, std::vector<std::string>& chain,
                 std::deque<std::string>& texts) {
  namespace fs = std::filesystem;
  if (!document.IsMap()) return;
  const YAML::Node base = Lookup(document, "base");
  if (!base.IsDefined()) return;
  const SourceMark at = ToSourceMark(base.Mark());
  if (!base.IsScalar() || base.Scalar().empty()) {
    ThrowAt(self.file, at, "base", Describe(base) + " must be a file name (a scenario)");
  }
  if (const std::optional<std::string> tag = ExplicitTag(base, self.text)) {
    ThrowAt(self.file, at, "base",
            "tagged value '" + *tag + "' (tags are not accepted; write the plain text)");
  }
  const std::string name = base.Scalar();
  const fs::path path = (fs::path(self.file).parent_path() / name).lexically_normal();
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(path, error);
  const std::string key = error ? path.string() : canonical.string();
  if (std::find(chain.begin(), chain.end(), key) != chain.end()) {
    std::string cycle;
    bool in = false;
    for (const std::string& file : chain) {
      in = in || file == key;
      if (in) cycle += fs::path(file).filename().string() + " -> ";
    }
    ThrowAt(self.file, at, "base",
            "'" + name + "' includes itself: " + cycle + fs::path(key).filename().string());
  }
  if (!fs::exists(path, error)) {
    ThrowAt(self.file, at, "base", "'" + name + "': no such file (" + path.string() + ")");
  }
  // A chain of bases is a few files deep; a longer one is a generated loop, not a scenario.
  constexpr std::size_t kMaxBaseDepth = 32;
  if (chain.size() >= kMaxBaseDepth) {
    ThrowAt(self.file, at, "base",
            "'" + name + "': more than " + std::to_string(kMaxBaseDepth) +
                " files in the chain of bases (" + fs::path(chain.front()).filename().string() +
                " -> ... -> " + fs::path(self.file).filename().string() + ")");
  }
  constexpr std::size_t kMaxScenarioBytes = 4 << 20;
  try {
    texts.push_back(ReadInputFile(path.string(), kMaxScenarioBytes, "scenario"));
  } catch (const InputError& failure) {
    ThrowAt(self.file, at, "base", "'" + name + "': " + failure.what());
  }
  Included parent{path.string(), &texts.back(), {}};
  YAML::Node parent_document = LoadDocument(texts.back(), parent.file, "scenario", "mooring");
  if (!parent_document.IsMap()) {
    ThrowAt(parent.file, ToSourceMark(parent_document.Mark()), "",
            Describe(parent_document) + " must be a map");
  }
  chain.push_back(key);
  ResolveBase(parent_document, parent, chain, texts);
  chain.pop_back();
  document.remove("base");
  MergeBase(document, parent_document, "", parent, self);
}

// Relative paths in values written in a base in another folder, made relative to the top
// file's folder (where the loader resolves them, and where the resolved text is read).
void RebasePaths(YAML::Node document, const Included& top) {
  const auto rebase = [&](YAML::Node value, const std::string& path) {
    if (!value.IsDefined() || !value.IsScalar()) return;
    const std::string written_in = top.OriginOf(path).file;
    if (written_in != top.file) value = Rebased(value.Scalar(), written_in, top.file);
  };
  const YAML::Node vessel = Lookup(document, "vessel");
  if (vessel.IsDefined() && vessel.IsMap()) {
    rebase(Lookup(vessel, "hydrodynamics"), "vessel.hydrodynamics");
  }
  const YAML::Node detectors = Lookup(document, "detectors");
  if (detectors.IsDefined() && detectors.IsSequence()) {
    for (std::size_t i = 0; i < detectors.size(); ++i) {
      if (detectors[i].IsMap()) {
        rebase(Lookup(detectors[i], "plugin"), ItemPath("detectors", i) + ".plugin");
      }
    }
  }
}

}  // namespace

Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name) {
  return ParseScenario(yaml_text, source_name, {});
}

Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name,
                       const std::vector<std::string>& overrides) {
  Scenario scenario;
  scenario.source_path = source_name;
  scenario.text = yaml_text;
  scenario.overrides = overrides;
  scenario.name = std::filesystem::path(source_name).stem().string();
  for (const std::string& assignment : overrides) {
    if (const std::optional<std::size_t> bad = FirstInvalidUtf8(assignment)) {
      throw OptionError("set", " " + EscapeInvalidUtf8(assignment) + ": not valid UTF-8 (byte " +
                                   HexByte(static_cast<unsigned char>(assignment[*bad])) +
                                   " at character " + std::to_string(*bad + 1) + ")");
    }
  }
  std::vector<std::string> errors;
  ParseContext context;
  context.file = source_name;
  context.marks = &scenario.marks;
  context.text = &yaml_text;
  context.errors = &errors;
  std::deque<std::string> base_texts;
  try {
    YAML::Node document = LoadDocument(yaml_text, source_name, "scenario", "mooring");
    Included top{source_name, &yaml_text, {}};
    std::error_code ignored;
    std::vector<std::string> chain = {
        std::filesystem::weakly_canonical(source_name, ignored).string()};
    ResolveBase(document, top, chain, base_texts);
    if (!top.origins.empty()) {
      RebasePaths(document, top);
      context.origins = top.origins;
      for (const ParseContext::Origin& origin : top.origins) {
        scenario.origins[origin.path] = origin.file;
      }
      // Outputs record the whole scenario, so that a run repeats without its bases.
      YAML::Emitter emitter;
      emitter << document;
      scenario.text = "# " + source_name +
                      " with its bases merged (moorsim validate --resolved)\n" + emitter.c_str() +
                      "\n";
    }
    for (const std::string& assignment : overrides) {
      context.overridden.push_back(ApplyOverride(document, assignment));
    }
    const Reader root(context, document, "", ToSourceMark(document.Mark()), &schema::Scenario());
    ParseDocument(root, scenario);
    // A relative plugin path, like a relative WAMIT stem, is relative to the scenario
    // file's directory.
    for (DetectorEntry& entry : scenario.detectors) {
      if (!entry.plugin.empty() && std::filesystem::path(entry.plugin).is_relative()) {
        entry.plugin = (std::filesystem::path(source_name).parent_path() / entry.plugin)
                           .lexically_normal()
                           .string();
      }
    }
    // A relative WAMIT stem is relative to the scenario file's directory.
    if (scenario.vessel && std::filesystem::path(scenario.vessel->hydrodynamics).is_relative()) {
      scenario.vessel->hydrodynamics =
          (std::filesystem::path(source_name).parent_path() / scenario.vessel->hydrodynamics)
              .lexically_normal()
              .string();
    }
  } catch (const YAML::ParserException& error) {
    ThrowAt(source_name, ToSourceMark(error.mark), "", "YAML syntax error: " + error.msg);
  } catch (const YAML::Exception& error) {
    // The Reader checks kinds before converting, so this is a safety net: still one line
    // with a position, never a yaml-cpp exception escaping to the CLI.
    ThrowAt(source_name, ToSourceMark(error.mark), "", error.msg);
  }
  // Checks between values run on a document whose every value could be read.
  ThrowCollected(std::move(errors));
  Validate(scenario);
  // Lines are numbered 1..N in any order in the file; consumers index lines[k - 1].
  std::stable_sort(scenario.mooring.lines.begin(), scenario.mooring.lines.end(),
                   [](const LineSpec& a, const LineSpec& b) { return a.id < b.id; });
  return scenario;
}

Scenario LoadScenario(const std::string& path) { return LoadScenario(path, {}); }

Scenario LoadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  // A scenario is a few kilobytes; reading stops at 4 MiB.
  constexpr std::size_t kMaxScenarioBytes = 4 << 20;
  return ParseScenario(ReadInputFile(path, kMaxScenarioBytes, "scenario"), path, overrides);
}

}  // namespace moorsim::scenarios
