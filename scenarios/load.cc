#include "scenarios/load.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"

namespace moorsim::scenarios {
namespace {

// ---------------------------------------------------------------------------------------
// Message building, shared by the parser and Validate().

// Shortest text that reads back as the same double ("-0.08", "1800", "2.5e-05").
std::string Number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string Fixed(double value, int decimals) {
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

std::string Significant(double value, int digits) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

std::string WithUnit(double value, std::string_view unit) {
  return unit.empty() ? Number(value) : Number(value) + " " + std::string(unit);
}

std::string JoinSorted(std::vector<std::string> words) {
  std::sort(words.begin(), words.end());
  std::string joined;
  for (const std::string& word : words) {
    joined += (joined.empty() ? "" : ", ") + word;
  }
  return joined.empty() ? "none" : joined;
}

[[noreturn]] void ThrowAt(const std::string& file, SourceMark mark, const std::string& path,
                          const std::string& what) {
  std::string message = file;
  if (mark.line > 0) {
    message += ":" + std::to_string(mark.line) + ":" + std::to_string(mark.column);
  }
  message += ": ";
  if (!path.empty()) message += path + ": ";
  throw InputError(message + what);
}

SourceMark ToSourceMark(const YAML::Mark& mark) {
  if (mark.is_null()) return {};
  return {mark.line + 1, mark.column + 1};  // yaml-cpp counts from 0, editors from 1
}

// List indices in key paths are 1-based (mooring.lines[3] is the third entry): the project
// numbers lines from 1 in everything a user reads, and the path should match the id.
std::string ItemPath(const std::string& list_path, std::size_t index) {
  return list_path + "[" + std::to_string(index + 1) + "]";
}

std::string KeyPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

double Radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// ---------------------------------------------------------------------------------------
// Strict reading of one YAML node at a key path.

struct ParseContext {
  std::string file;
  std::map<std::string, SourceMark>* marks;  // filled with the position of every node read
};

std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      // Tag "!" is yaml-cpp's mark of a quoted scalar; show the quotes so "must be a
      // number" makes sense for "0.08".
      return node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();
    case YAML::NodeType::Sequence: {
      // A short list of scalars reads best as written: "[0, 20] must be a list of 3 ...".
      std::string shown = "[";
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar() || i == 6) return "a list";
        shown += (i > 0 ? ", " : "") + Describe(node[i]);
      }
      return shown + "]";
    }
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "an empty value";
  }
}

class Reader {
 public:
  Reader(const ParseContext& context, YAML::Node node, std::string path, SourceMark mark)
      : context_(&context), node_(std::move(node)), path_(std::move(path)), mark_(mark) {
    (*context_->marks)[path_] = mark_;
  }

  SourceMark mark() const { return mark_; }

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowAt(context_->file, mark_, path_, what);
  }

  /// Requires a map whose keys are all in `known`, each at most once.
  void CheckKeys(std::vector<std::string_view> known) const {
    if (!node_.IsMap()) Fail(Describe(node_) + " must be a map");
    std::vector<std::string> seen;
    for (const auto& entry : node_) {
      const YAML::Node& key = entry.first;
      const SourceMark key_mark = ToSourceMark(key.Mark());
      if (!key.IsScalar()) ThrowAt(context_->file, key_mark, path_, "keys must be plain names");
      const std::string& name = key.Scalar();
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        ThrowAt(context_->file, key_mark, path_,
                "unknown key '" + name + "' (known: " +
                    JoinSorted(std::vector<std::string>(known.begin(), known.end())) + ")");
      }
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
        ThrowAt(context_->file, key_mark, path_, "duplicate key '" + name + "'");
      }
      seen.push_back(name);
    }
  }

  /// The value under `key` of this map (CheckKeys first), or nothing if the key is absent.
  std::optional<Reader> Find(std::string_view key) const {
    for (const auto& entry : node_) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) {
        // yaml-cpp puts an empty value's mark on the next token, possibly lines later;
        // the key is where the user looks.
        const YAML::Mark& mark = entry.second.IsNull() ? entry.first.Mark() : entry.second.Mark();
        return Reader(*context_, entry.second, KeyPath(path_, key), ToSourceMark(mark));
      }
    }
    return std::nullopt;
  }

  Reader Child(std::string_view key) const {
    std::optional<Reader> child = Find(key);
    if (!child) Fail("required key '" + std::string(key) + "' is missing");
    return *child;
  }

  std::vector<Reader> Items() const {
    if (!node_.IsSequence()) Fail(Describe(node_) + " must be a list");
    std::vector<Reader> items;
    for (std::size_t i = 0; i < node_.size(); ++i) {
      items.emplace_back(*context_, node_[i], ItemPath(path_, i), ToSourceMark(node_[i].Mark()));
    }
    return items;
  }

  template <class T>
  T As() const;

  template <class T>
  T Required(std::string_view key) const {
    return Child(key).As<T>();
  }

  template <class T>
  std::optional<T> Maybe(std::string_view key) const {
    if (std::optional<Reader> child = Find(key)) return child->As<T>();
    return std::nullopt;
  }

  /// Overwrites `field` (which holds the default) if the key is present.
  template <class T>
  void Optional(std::string_view key, T& field) const {
    if (std::optional<T> value = Maybe<T>(key)) field = *value;
  }

 private:
  // A plain scalar (not quoted) that yaml-cpp's own conversion accepts.
  template <class T>
  T Decode(const char* expected) const {
    T value{};
    if (!node_.IsScalar() || node_.Tag() == "!" || !YAML::convert<T>::decode(node_, value)) {
      Fail(Describe(node_) + " must be " + expected);
    }
    return value;
  }

  const ParseContext* context_;
  YAML::Node node_;
  std::string path_;
  SourceMark mark_;
};

template <>
double Reader::As<double>() const {
  const double value = Decode<double>("a number");
  if (!std::isfinite(value)) Fail(Describe(node_) + " must be a finite number");
  return value;
}

template <>
int Reader::As<int>() const {
  return Decode<int>("an integer");
}

template <>
bool Reader::As<bool>() const {
  return Decode<bool>("true or false");
}

template <>
std::string Reader::As<std::string>() const {
  if (!node_.IsScalar()) Fail(Describe(node_) + " must be a string");
  return node_.Scalar();
}

template <>
Vec3 Reader::As<Vec3>() const {
  if (!node_.IsSequence() || node_.size() != 3) {
    Fail(Describe(node_) + " must be a list of 3 numbers [x, y, z]");
  }
  const std::vector<Reader> items = Items();
  return Vec3(items[0].As<double>(), items[1].As<double>(), items[2].As<double>());
}

// ---------------------------------------------------------------------------------------
// The schema, one function per block (documented in load.h and README.md).

// Neither axial_damping nor axial_damping_ratio given: half of a segment's critical
// damping stops the stiff axial modes from ringing and is invisible at wave periods.
constexpr double kDefaultAxialDampingRatio = 0.5;

void ParseWater(const Reader& r, Water& water) {
  r.CheckKeys({"density", "depth", "gravity"});
  r.Optional("density", water.density);
  r.Optional("gravity", water.gravity);
  water.depth = r.Required<double>("depth");
}

void ParseSeabed(const Reader& r, Seabed& seabed) {
  r.CheckKeys({"contact_smoothing", "damping", "friction_velocity", "stiffness"});
  r.Optional("stiffness", seabed.stiffness);
  r.Optional("damping", seabed.damping);
  r.Optional("contact_smoothing", seabed.contact_smoothing);
  r.Optional("friction_velocity", seabed.friction_velocity);
}

void ParseCurrent(const Reader& r, CurrentProfile& current) {
  r.CheckKeys({"direction_deg", "profile"});
  current.direction = Radians(r.Required<double>("direction_deg"));
  const Reader profile = r.Child("profile");
  const std::vector<Reader> points = profile.Items();
  if (points.empty()) profile.Fail("[] must hold at least one {depth, speed} point");
  for (const Reader& point : points) {
    point.CheckKeys({"depth", "speed"});
    current.depth.push_back(point.Required<double>("depth"));
    current.speed.push_back(point.Required<double>("speed"));
  }
}

LineType ParseLineType(const Reader& r) {
  r.CheckKeys({"added_mass_normal", "axial_damping", "axial_damping_ratio", "axial_stiffness",
               "diameter", "drag_normal", "drag_tangential", "friction_axial", "friction_lateral",
               "mass_per_length", "name"});
  LineType type;
  type.name = r.Required<std::string>("name");
  type.diameter = r.Required<double>("diameter");
  type.mass_per_length = r.Required<double>("mass_per_length");
  type.axial_stiffness = r.Required<double>("axial_stiffness");
  type.axial_damping = r.Maybe<double>("axial_damping");
  type.axial_damping_ratio = r.Maybe<double>("axial_damping_ratio");
  if (!type.axial_damping && !type.axial_damping_ratio) {
    type.axial_damping_ratio = kDefaultAxialDampingRatio;
  }
  type.drag_normal = r.Required<double>("drag_normal");
  type.drag_tangential = r.Required<double>("drag_tangential");
  type.added_mass_normal = r.Required<double>("added_mass_normal");
  r.Optional("friction_axial", type.friction_axial);
  r.Optional("friction_lateral", type.friction_lateral);
  type.mark = r.mark();
  return type;
}

LineSpec ParseLine(const Reader& r, int entry, int default_segments) {
  r.CheckKeys({"anchor", "fairlead", "id", "length", "segments", "type"});
  LineSpec line;
  line.entry = entry;
  line.id = entry;
  r.Optional("id", line.id);
  line.type = r.Required<std::string>("type");
  line.anchor = r.Required<Vec3>("anchor");
  line.fairlead_body = r.Required<Vec3>("fairlead");
  const Reader length = r.Child("length");
  line.length = length.As<double>();
  line.length_mark = length.mark();
  line.segments = default_segments;
  r.Optional("segments", line.segments);
  line.mark = r.mark();
  return line;
}

void ParseMooring(const Reader& r, Scenario& scenario) {
  r.CheckKeys({"current", "defaults", "line_types", "lines", "seabed", "water"});
  MooringSpec& mooring = scenario.mooring;
  ParseWater(r.Child("water"), mooring.water);
  if (std::optional<Reader> seabed = r.Find("seabed")) ParseSeabed(*seabed, mooring.seabed);
  if (std::optional<Reader> current = r.Find("current")) ParseCurrent(*current, mooring.current);
  for (const Reader& type : r.Child("line_types").Items()) {
    mooring.line_types.push_back(ParseLineType(type));
  }
  if (std::optional<Reader> defaults = r.Find("defaults")) {
    defaults->CheckKeys({"segments"});
    defaults->Optional("segments", mooring.defaults.segments);
  }
  const std::vector<Reader> lines = r.Child("lines").Items();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    mooring.lines.push_back(
        ParseLine(lines[i], static_cast<int>(i) + 1, mooring.defaults.segments));
  }
}

void ParseName(const Reader& r, Scenario& scenario) { scenario.name = r.As<std::string>(); }

void ParseSolver(const Reader& r, Scenario& scenario) {
  r.CheckKeys({"atol_position", "atol_velocity", "max_order", "max_step", "rtol",
               "stability_limit_detection"});
  SolverSpec& solver = scenario.solver;
  r.Optional("rtol", solver.rtol);
  r.Optional("atol_position", solver.atol_position);
  r.Optional("atol_velocity", solver.atol_velocity);
  r.Optional("max_order", solver.max_order);
  r.Optional("stability_limit_detection", solver.stability_limit_detection);
  r.Optional("max_step", solver.max_step);
}

// The top level, sorted by key. Later sections (vessel, environment, controller, sensors,
// failure, simulation, detectors) each add one row; the table also gives the "known:" list.
struct Section {
  std::string_view key;
  bool required;
  void (*parse)(const Reader&, Scenario&);
};

constexpr Section kSections[] = {
    {"mooring", true, ParseMooring},
    {"name", false, ParseName},
    {"solver", false, ParseSolver},
};

void ParseDocument(const Reader& root, Scenario& scenario) {
  std::vector<std::string_view> known;
  for (const Section& section : kSections) known.push_back(section.key);
  root.CheckKeys(known);
  for (const Section& section : kSections) {
    if (std::optional<Reader> value = root.Find(section.key)) {
      section.parse(*value, scenario);
    } else if (section.required) {
      root.Child(section.key);  // throws "required key ... is missing"
    }
  }
}

// ---------------------------------------------------------------------------------------
// Semantic checks.

class Checker {
 public:
  explicit Checker(const Scenario& scenario)
      : file_(scenario.source_path.empty() ? "scenario" : scenario.source_path),
        marks_(scenario.marks) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& what) const {
    ThrowAt(file_, Locate(path), path, what);
  }

  void Positive(const std::string& path, double value, std::string_view unit) const {
    if (!(value > 0.0)) Fail(path, WithUnit(value, unit) + " must be > 0");
  }

  void NonNegative(const std::string& path, double value, std::string_view unit) const {
    if (!(value >= 0.0)) Fail(path, WithUnit(value, unit) + " must be >= 0");
  }

  void InRange(const std::string& path, int value, int low, int high) const {
    if (value < low || value > high) {
      Fail(path, std::to_string(value) + " must be in " + std::to_string(low) + ".." +
                     std::to_string(high));
    }
  }

 private:
  // A value that was not written (a default) is reported at the nearest enclosing block
  // that was: "mooring.lines[2].id" falls back to the entry "mooring.lines[2]".
  SourceMark Locate(std::string path) const {
    while (!path.empty()) {
      if (const auto found = marks_.find(path); found != marks_.end()) return found->second;
      const std::size_t cut = path.find_last_of(".[");
      path.resize(cut == std::string::npos ? 0 : cut);
    }
    return {};
  }

  std::string file_;
  const std::map<std::string, SourceMark>& marks_;
};

void CheckWater(const Checker& check, const Water& water) {
  check.Positive("mooring.water.density", water.density, "kg/m^3");
  check.Positive("mooring.water.gravity", water.gravity, "m/s^2");
  check.Positive("mooring.water.depth", water.depth, "m");
}

void CheckSeabed(const Checker& check, const Seabed& seabed) {
  check.Positive("mooring.seabed.stiffness", seabed.stiffness, "N/m^3");
  check.NonNegative("mooring.seabed.damping", seabed.damping, "N s/m^3");
  check.Positive("mooring.seabed.contact_smoothing", seabed.contact_smoothing, "m");
  check.Positive("mooring.seabed.friction_velocity", seabed.friction_velocity, "m/s");
}

void CheckCurrent(const Checker& check, const CurrentProfile& current) {
  const std::string profile = "mooring.current.profile";
  if (current.depth.size() != current.speed.size()) {
    check.Fail(profile, std::to_string(current.depth.size()) + " depths and " +
                            std::to_string(current.speed.size()) +
                            " speeds differ in number; every point needs both");
  }
  for (std::size_t i = 0; i < current.depth.size(); ++i) {
    const std::string point = ItemPath(profile, i);
    check.NonNegative(point + ".depth", current.depth[i], "m");
    if (i > 0 && !(current.depth[i] > current.depth[i - 1])) {
      check.Fail(point + ".depth", WithUnit(current.depth[i], "m") +
                                       " must be greater than the previous point's depth " +
                                       WithUnit(current.depth[i - 1], "m"));
    }
    check.NonNegative(point + ".speed", current.speed[i], "m/s");
  }
}

void CheckLineType(const Checker& check, const LineType& type, const std::string& path,
                   const Water& water) {
  check.Positive(path + ".diameter", type.diameter, "m");
  // A line no heavier than the water it displaces has no submerged weight: no catenary,
  // nothing holds it on the seabed.
  const double displaced = water.density * std::numbers::pi * type.diameter * type.diameter / 4.0;
  if (!(type.mass_per_length > displaced)) {
    check.Fail(path + ".mass_per_length",
               WithUnit(type.mass_per_length, "kg/m") + " must exceed the displaced water mass " +
                   Significant(displaced, 4) + " kg/m (the line would float)");
  }
  check.Positive(path + ".axial_stiffness", type.axial_stiffness, "N");
  if (type.axial_damping && type.axial_damping_ratio) {
    check.Fail(path + ".axial_damping_ratio",
               Number(*type.axial_damping_ratio) + " cannot be combined with axial_damping " +
                   WithUnit(*type.axial_damping, "N s") + "; give one of them");
  }
  if (type.axial_damping) check.NonNegative(path + ".axial_damping", *type.axial_damping, "N s");
  if (type.axial_damping_ratio) {
    const double ratio = *type.axial_damping_ratio;
    if (!(ratio >= 0.0 && ratio <= 10.0)) {
      check.Fail(path + ".axial_damping_ratio", Number(ratio) + " must be in [0, 10]");
    }
  }
  check.NonNegative(path + ".drag_normal", type.drag_normal, "");
  check.NonNegative(path + ".drag_tangential", type.drag_tangential, "");
  check.NonNegative(path + ".added_mass_normal", type.added_mass_normal, "");
  check.NonNegative(path + ".friction_axial", type.friction_axial, "");
  check.NonNegative(path + ".friction_lateral", type.friction_lateral, "");
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
    CheckLineType(check, mooring.line_types[i], path, mooring.water);
  }
}

// Segment counts: 2 is the least that has an internal node; beyond 10000 a line is a
// typo, not a model (the state would hold 60000 numbers per line).
constexpr int kMinSegments = 2;
constexpr int kMaxSegments = 10000;

void CheckLines(const Checker& check, const MooringSpec& mooring) {
  const std::vector<LineSpec>& lines = mooring.lines;
  if (lines.empty()) check.Fail("mooring.lines", "[] must list at least one line");
  const int count = static_cast<int>(lines.size());
  // Messages name the entry as written; lines may already be sorted by id.
  const auto path_of = [](const LineSpec& line, std::size_t index) {
    return ItemPath("mooring.lines", line.entry > 0 ? line.entry - 1 : index);
  };
  std::vector<std::string> type_names;
  for (const LineType& type : mooring.line_types) type_names.push_back(type.name);

  for (std::size_t i = 0; i < lines.size(); ++i) {
    const LineSpec& line = lines[i];
    const std::string path = path_of(line, i);
    for (std::size_t j = 0; j < i; ++j) {
      if (lines[j].id == line.id) {
        check.Fail(path + ".id",
                   std::to_string(line.id) + " is already the id of " + path_of(lines[j], j));
      }
    }
    if (line.id < 1 || line.id > count) {
      check.Fail(path + ".id", std::to_string(line.id) + " must be in 1.." + std::to_string(count) +
                                   " (ids number the " + std::to_string(count) + " lines from 1)");
    }
    if (std::find(type_names.begin(), type_names.end(), line.type) == type_names.end()) {
      check.Fail(path + ".type",
                 "unknown line type '" + line.type + "' (known: " + JoinSorted(type_names) + ")");
    }
    check.InRange(path + ".segments", line.segments, kMinSegments, kMaxSegments);
    check.Positive(path + ".length", line.length, "m");

    const double depth = mooring.water.depth;
    if (line.anchor.z() > depth + 1e-6) {
      check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") +
                                       " is below the seabed at depth " + WithUnit(depth, "m"));
    }
    // With the vessel at the origin and heading 0 the fairlead's Earth position is its
    // body position.
    const Vec3& fairlead = line.fairlead_body;
    if (line.anchor.z() < fairlead.z()) {
      check.Fail(path + ".anchor", "z = " + WithUnit(line.anchor.z(), "m") +
                                       " is above the fairlead at z = " +
                                       WithUnit(fairlead.z(), "m") + " (z points down)");
    }
    const double distance = (line.anchor - fairlead).norm();
    if (line.length < distance) {
      check.Fail(path + ".length", WithUnit(line.length, "m") +
                                       " is shorter than the anchor-fairlead distance " +
                                       Fixed(distance, 1) + " m");
    }
  }
}

void CheckSolver(const Checker& check, const SolverSpec& solver) {
  if (!(solver.rtol > 0.0 && solver.rtol < 1.0)) {
    check.Fail("solver.rtol", Number(solver.rtol) + " must be in (0, 1)");
  }
  check.Positive("solver.atol_position", solver.atol_position, "m");
  check.Positive("solver.atol_velocity", solver.atol_velocity, "m/s");
  check.InRange("solver.max_order", solver.max_order, 1, 5);  // CVODE's BDF orders
  if (!(solver.max_step >= 0.0)) {
    check.Fail("solver.max_step", WithUnit(solver.max_step, "s") + " must be >= 0 (0 = no limit)");
  }
}

}  // namespace

void Validate(const Scenario& scenario) {
  const Checker check(scenario);
  const MooringSpec& mooring = scenario.mooring;
  CheckWater(check, mooring.water);
  CheckSeabed(check, mooring.seabed);
  CheckCurrent(check, mooring.current);
  CheckLineTypes(check, mooring);
  check.InRange("mooring.defaults.segments", mooring.defaults.segments, kMinSegments, kMaxSegments);
  CheckLines(check, mooring);
  CheckSolver(check, scenario.solver);
}

Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name) {
  Scenario scenario;
  scenario.source_path = source_name;
  scenario.text = yaml_text;
  scenario.name = std::filesystem::path(source_name).stem().string();
  const ParseContext context{source_name, &scenario.marks};
  try {
    const std::vector<YAML::Node> documents = YAML::LoadAll(yaml_text);
    if (documents.empty() || documents[0].IsNull()) {
      ThrowAt(source_name, {}, "", "the scenario is empty (expected a map with 'mooring')");
    }
    if (documents.size() > 1) {
      ThrowAt(source_name, ToSourceMark(documents[1].Mark()), "",
              "a scenario file holds one YAML document; this is a second one");
    }
    const Reader root(context, documents[0], "", ToSourceMark(documents[0].Mark()));
    ParseDocument(root, scenario);
  } catch (const YAML::ParserException& error) {
    ThrowAt(source_name, ToSourceMark(error.mark), "", "YAML syntax error: " + error.msg);
  } catch (const YAML::Exception& error) {
    // The Reader checks kinds before converting, so this is a safety net: still one line
    // with a position, never a yaml-cpp exception escaping to the CLI.
    ThrowAt(source_name, ToSourceMark(error.mark), "", error.msg);
  }
  Validate(scenario);
  // Lines are numbered 1..N in any order in the file; consumers index lines[k - 1].
  std::stable_sort(scenario.mooring.lines.begin(), scenario.mooring.lines.end(),
                   [](const LineSpec& a, const LineSpec& b) { return a.id < b.id; });
  return scenario;
}

Scenario LoadScenario(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw InputError(path + ": is a directory, not a scenario file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    const std::error_code error(errno, std::generic_category());
    throw InputError(path + ": cannot open the scenario file: " + error.message());
  }
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw InputError(path + ": cannot read the scenario file");
  return ParseScenario(text.str(), path);
}

}  // namespace moorsim::scenarios
