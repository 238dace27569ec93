#include "scenarios/moordyn.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "core/version.h"
#include "mooring_fem/wave_kinematics.h"
#include "scenarios/load.h"
#include "scenarios/schema.h"
#include "scenarios/strict_yaml.h"

namespace moorsim::scenarios {
namespace {

constexpr std::size_t kMaxFileBytes = 4 << 20;

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::vector<std::string> Fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string field; in >> field;) fields.push_back(field);
  return fields;
}

std::optional<double> ToNumber(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A YAML double-quoted scalar when the text is not a plain word.
std::string Text(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (plain && !ToNumber(text)) return text;
  return strict_yaml::DoubleQuoted(text);
}

struct Row {
  int line = 0;  // 1-based line in the file
  std::vector<std::string> fields;
};

// A section of the file: its title (upper case, dashes removed) and its rows; a table's
// first two rows are its column names and units.
struct Section {
  std::string title;
  int line = 0;
  std::vector<Row> rows;
};

enum class Kind {
  kTitle,
  kLineTypes,
  kRodTypes,
  kBodies,
  kRods,
  kPoints,
  kLines,
  kOptions,
  kOutputs,
  kEnd,
  kOther
};

Kind KindOf(const std::string& title) {
  const auto has = [&](const char* word) { return title.find(word) != std::string::npos; };
  if (has("MOORDYN")) return Kind::kTitle;
  if (has("NEED THIS LINE")) return Kind::kEnd;
  if (has("LINE TYPE") || has("LINE DICTIONARY")) return Kind::kLineTypes;
  if (has("ROD TYPE") || has("ROD DICTIONARY")) return Kind::kRodTypes;
  if (has("BOD")) return Kind::kBodies;
  if (has("ROD")) return Kind::kRods;
  if (has("POINT") || has("CONNECTION") || has("NODE")) return Kind::kPoints;
  if (has("LINE")) return Kind::kLines;
  if (has("OPTION")) return Kind::kOptions;
  if (has("OUTPUT")) return Kind::kOutputs;
  return Kind::kOther;
}

std::vector<Section> ReadSections(const std::string& text) {
  std::vector<Section> sections;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find("---") != std::string::npos) {
      std::string title;
      for (const char c : line) {
        if (c != '-') title += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      }
      const auto first = title.find_first_not_of(" \t");
      const auto last = title.find_last_not_of(" \t");
      title = first == std::string::npos ? "" : title.substr(first, last - first + 1);
      sections.push_back({title, number, {}});
      continue;
    }
    if (sections.empty()) continue;
    std::vector<std::string> fields = Fields(line);
    if (!fields.empty()) sections.back().rows.push_back({number, std::move(fields)});
  }
  return sections;
}

// The columns of a table by meaning, from its header row's names.
class Columns {
 public:
  Columns(const std::string& file, const Row& header,
          const std::map<std::string, std::vector<std::string>>& names)
      : file_(file), line_(header.line) {
    for (std::size_t k = 0; k < header.fields.size(); ++k) {
      const std::string name = Lower(header.fields[k]);
      bool known = false;
      for (const auto& [meaning, spellings] : names) {
        if (std::find(spellings.begin(), spellings.end(), name) != spellings.end()) {
          index_[meaning] = k;
          known = true;
        }
      }
      if (!known) unknown_.push_back({header.fields[k], k});
    }
  }
  bool Has(const std::string& meaning) const { return index_.count(meaning) > 0; }
  const std::vector<std::pair<std::string, std::size_t>>& unknown() const { return unknown_; }
  // The field of `row` in the column `meaning`; an error line if the table has no such
  // column or the row no such field.
  std::string Field(const Row& row, const std::string& meaning) const {
    const auto it = index_.find(meaning);
    if (it == index_.end()) {
      throw InputError(file_ + ":" + std::to_string(line_) + ": the table has no " + meaning +
                       " column");
    }
    if (it->second >= row.fields.size()) {
      throw InputError(file_ + ":" + std::to_string(row.line) + ": no " + meaning + " value");
    }
    return row.fields[it->second];
  }
  double Value(const Row& row, const std::string& meaning) const {
    const std::string text = Field(row, meaning);
    const std::optional<double> value = ToNumber(text);
    if (!value) {
      throw InputError(file_ + ":" + std::to_string(row.line) + ": " + meaning + " '" + text +
                       "' is not a number");
    }
    return *value;
  }

 private:
  std::string file_;
  int line_;
  std::map<std::string, std::size_t> index_;
  std::vector<std::pair<std::string, std::size_t>> unknown_;
};

struct MdLineType {
  std::string name;
  int line = 0;
  double diameter = 0, mass = 0, ea = 0, ba = 0, cd = 0, ca = 0, cdax = 0, caax = 0;
  // A visco-elastic rope (EA_s|EA_D, BA_s or BA_s|BA_D): MoorDyn's segment is its dynamic
  // spring EA_D (damped by BA_D, held in `ba`) in series with the static spring that makes
  // the series EA_s, damped by BA_s: moorsim's dynamic spring, and its creep spring and
  // dashpot. 0: none.
  double dynamic_ea = 0, static_damping = 0;
  // EA_s|EA_Dc|EA_D_Lm: EA_D = EA_Dc + EA_D_Lm x the mean load (EA_Dc in dynamic_ea).
  double dynamic_ea_slope = 0;
  // EA from a file (MoorDyn's nonlinear stiffness): its name and (strain, tension) points.
  std::string ea_table;
  std::vector<std::pair<double, double>> ea_curve;
};

// "a|b|..." as its numbers (one or more), or nothing where one is not a number.
std::optional<std::vector<double>> BarSeparated(const std::string& text) {
  std::vector<double> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t bar = text.find('|', from);
    const std::optional<double> v = ToNumber(text.substr(from, bar - from));
    if (!v) return {};
    out.push_back(*v);
    if (bar == std::string::npos) return out;
    from = bar + 1;
  }
}

enum class PointKind { kFixed, kVessel, kFree };

struct Point {
  std::string id;
  int line = 0;
  PointKind kind = PointKind::kFree;
  std::string kind_text;
  double x = 0, y = 0, z = 0, mass = 0, volume = 0, cda = 0, ca = 0;
  std::vector<std::size_t> lines;  // indices of the lines attached
};

struct MdLine {
  std::string id;
  int line = 0;
  std::string type, a, b;
  double length = 0;
  int segments = 0;
};

// Collects one located line per problem, then throws them all.
class Problems {
 public:
  explicit Problems(std::string file) : file_(std::move(file)) {}
  void Add(int line, const std::string& what) {
    lines_.push_back(file_ + ":" + std::to_string(line) + ": " + what);
  }
  template <class Body>
  void Attempt(Body&& body) {
    try {
      body();
    } catch (const InputError& e) {
      lines_.push_back(e.what());
    }
  }
  void ThrowIfAny() const {
    if (lines_.empty()) return;
    std::string all;
    for (const std::string& line : lines_) all += (all.empty() ? "" : "\n") + line;
    throw InputError(all);
  }

 private:
  std::string file_;
  std::vector<std::string> lines_;
};

// A free point's name in the scenario.
std::string PointName(const Point& p) { return Text("point_" + p.id); }

std::string Vector(double x, double y, double z) {
  // MoorDyn (z up, y to port) to moorsim (z down, y to starboard).
  std::string text = "[";
  text.append(FormatNumber(x)).append(", ").append(FormatNumber(y == 0.0 ? 0.0 : -y));
  return text.append(", ").append(FormatNumber(z == 0.0 ? 0.0 : -z)).append("]");
}

// MoorDyn's bathymetry file (SeafloorFile): the counts nx and ny, the nx x coordinates,
// the ny y coordinates, then nx ny rows "x y z" (z up, the seabed's height), x major. It is
// looked for beside the input file and then in each folder above it (MoorDyn reads it from
// its working directory). Returns moorsim's grid file (scenarios/README.md): x north, y
// east (MoorDyn's -y, so the y axis is reversed), depths down, moved by the shift.
// A file an input names (`name`), looked for beside the input file `path` and then in each
// folder above it; throws InputError "<where>: not found ..." if it is in none.
std::filesystem::path FindBesideInput(const std::string& path, const std::string& name,
                                      const std::string& where) {
  for (std::filesystem::path dir = std::filesystem::absolute(path).parent_path();;
       dir = dir.parent_path()) {
    if (std::filesystem::is_regular_file(dir / name)) return dir / name;
    if (dir == dir.parent_path()) break;
  }
  throw InputError(where + ": not found beside the input file or in a folder above it");
}

// The lines of a file MoorDyn reads beside the input file (`name`), as MoorDyn reads them:
// every line kept, blank ones too, its fields split at white space.
std::vector<std::vector<std::string>> BesideFileRows(const std::string& path,
                                                     const std::string& name,
                                                     const std::string& where) {
  const std::filesystem::path found = FindBesideInput(path, name, where);
  const std::string text = strict_yaml::ReadInputFile(found.string(), kMaxFileBytes, "MoorDyn");
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string row; std::getline(in, row);) rows.push_back(Fields(row));
  return rows;
}

// A field as a number, or InputError naming the file's line.
double NumberAt(const std::vector<std::string>& fields, std::size_t k, const std::string& where,
                std::size_t row) {
  if (k >= fields.size()) {
    throw InputError(where + ", line " + std::to_string(row + 1) + ": " +
                     std::to_string(fields.size()) + " fields where " + std::to_string(k + 1) +
                     " or more are needed");
  }
  const std::optional<double> value = ToNumber(fields[k]);
  if (!value) {
    throw InputError(where + ", line " + std::to_string(row + 1) + ": '" + fields[k] +
                     "' is not a number");
  }
  return *value;
}

// An angle in degrees, in (-180, 180].
double Degrees(double radians) { return WrapAngle(radians) * 180.0 / std::numbers::pi + 0.0; }

// One regular wave in MoorDyn's frame (z up, y to port): elevation
// amplitude cos(omega t - k (x cos(beta) + y sin(beta)) + phase).
struct MdWave {
  double omega = 0.0, amplitude = 0.0, phase = 0.0, beta = 0.0;
};

// MoorDyn's wave_frequencies.txt: rows "omega re im [beta]", the first at 0 rad/s. WaveKin 7
// sums them as they are, as |A| sin(omega t - k x + arg A); WaveKin 2 first puts them on an
// even grid of the smallest spacing (complex amplitude and direction joined by straight
// lines) and inverse-transforms them, |A| cos(omega t - k x + arg A), its top bin (the
// transform's Nyquist bin) taking half its real part. The 0 rad/s row is a constant level,
// not a wave: left out (with a warning if it is not zero).
std::vector<MdWave> SpectrumWaves(const std::string& path, int line, int wavekin,
                                  const std::function<void(const std::string&)>& warn) {
  const std::string where = path + ":" + std::to_string(line) + ": WaveKin " +
                            std::to_string(wavekin) + ": wave_frequencies.txt";
  struct Row {
    double omega;
    std::complex<double> a;
    double beta;
  };
  std::vector<Row> rows;
  const auto lines = BesideFileRows(path, "wave_frequencies.txt", where);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    if (lines[i].size() < 3 || lines[i].size() > 4) {
      throw InputError(where + ", line " + std::to_string(i + 1) +
                       ": a row is omega [rad/s], the amplitude's real and imaginary parts "
                       "[m] and optionally the direction [rad]");
    }
    Row r{NumberAt(lines[i], 0, where, i),
          {NumberAt(lines[i], 1, where, i), NumberAt(lines[i], 2, where, i)},
          lines[i].size() == 4 ? NumberAt(lines[i], 3, where, i) : 0.0};
    if (std::abs(r.beta) > 2.0 * std::numbers::pi) {
      throw InputError(where + ", line " + std::to_string(i + 1) +
                       ": the direction must be within +-2 pi rad");
    }
    if (!rows.empty() && !(r.omega > rows.back().omega)) {
      throw InputError(where + ", line " + std::to_string(i + 1) +
                       ": the frequencies must increase");
    }
    rows.push_back(r);
  }
  if (rows.size() < 2 || rows.front().omega != 0.0) {
    throw InputError(where + ": at least two rows, the first at 0 rad/s");
  }
  if (std::abs(rows.front().a) > 0.0) {
    warn("WaveKin " + std::to_string(wavekin) +
         ": wave_frequencies.txt's 0 rad/s row is a constant water level, not a wave: left out");
  }
  std::vector<MdWave> waves;
  if (wavekin == 7) {
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const Row& r = rows[i];
      if (std::abs(r.a) == 0.0) continue;
      waves.push_back({r.omega, std::abs(r.a), std::arg(r.a) - std::numbers::pi / 2.0, r.beta});
    }
    return waves;
  }
  double dw = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < rows.size(); ++i)
    dw = std::min(dw, rows[i].omega - rows[i - 1].omega);
  // The count as a double first: a spacing of 1e-300 is no size.
  const double grid = std::floor(rows.back().omega / dw) + 1.0;
  if (!(grid <= 1e6)) throw InputError(where + ": more than 1e6 frequencies on its even grid");
  const std::size_t nw = static_cast<std::size_t>(grid);
  std::size_t j = 1;
  for (std::size_t i = 1; i < nw; ++i) {
    const double omega = static_cast<double>(i) * dw;
    while (j + 1 < rows.size() && rows[j].omega < omega) ++j;
    const double f =
        std::clamp((omega - rows[j - 1].omega) / (rows[j].omega - rows[j - 1].omega), 0.0, 1.0);
    std::complex<double> a = rows[j - 1].a + f * (rows[j].a - rows[j - 1].a);
    const double beta = rows[j - 1].beta + f * (rows[j].beta - rows[j - 1].beta);
    if (i == nw - 1) a = 0.5 * a.real();  // the inverse transform's Nyquist bin
    if (std::abs(a) == 0.0) continue;
    waves.push_back({omega, std::abs(a), std::arg(a), beta});
  }
  return waves;
}

// MoorDyn's wave_elevation.txt (WaveKin 3): rows "t zeta" at the origin, waves travelling
// along x. MoorDyn resamples it every dtWave from 0 (straight lines between the rows, held
// beyond the last), drops a last sample to make the count even, Fourier-transforms it and
// keeps the frequencies up to 0.5 Hz: those are the regular waves, of period N dtWave / n.
std::vector<MdWave> ElevationWaves(const std::string& path, int line, double dt_wave,
                                   const std::function<void(const std::string&)>& warn) {
  const std::string where = path + ":" + std::to_string(line) + ": WaveKin 3: wave_elevation.txt";
  if (!(dt_wave > 0.0)) throw InputError(where + ": dtWave must be > 0");
  std::vector<double> times, elevations;
  const auto lines = BesideFileRows(path, "wave_elevation.txt", where);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const double t = NumberAt(lines[i], 0, where, i);
    if (!times.empty() && !(t > times.back())) {
      throw InputError(where + ", line " + std::to_string(i + 1) + ": the times must increase");
    }
    times.push_back(t);
    elevations.push_back(NumberAt(lines[i], 1, where, i));
  }
  if (times.size() < 2) throw InputError(where + ": at least two rows \"t zeta\"");
  const double samples_wanted = std::floor(times.back() / dt_wave) + 1.0;
  if (!(samples_wanted >= 2.0) || samples_wanted > 1e6) {
    throw InputError(where + ": " + FormatNumber(samples_wanted) +
                     " samples at dtWave; 2 to 1e6 are needed");
  }
  std::size_t n = static_cast<std::size_t>(samples_wanted);
  if (n % 2 != 0) --n;
  std::vector<double> zeta(n);
  std::size_t j = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt_wave;
    while (j + 1 < times.size() && times[j] < t) ++j;
    const double f = std::clamp((t - times[j - 1]) / (times[j] - times[j - 1]), 0.0, 1.0);
    zeta[i] = elevations[j - 1] + f * (elevations[j] - elevations[j - 1]);
  }
  const double dw = std::numbers::pi / (dt_wave * static_cast<double>(n / 2));
  // The transform below costs N per frequency kept: a record of N samples keeps about
  // N dtWave / 2 of them (0.5 Hz at most). Beyond 1e8 the import would take minutes.
  const double kept = std::min(static_cast<double>(n / 2), std::floor(std::numbers::pi / dw));
  if (static_cast<double>(n) * kept > 1e8) {
    throw InputError(where + ": " + std::to_string(n) + " samples at dtWave " +
                     FormatNumber(dt_wave) + " s keep " +
                     std::to_string(static_cast<std::size_t>(kept)) +
                     " frequencies: more than moorsim transforms (samples x frequencies <= "
                     "1e8); give a shorter record");
  }
  std::vector<MdWave> waves;
  double mean = 0.0;
  for (double z : zeta) mean += z;
  if (std::abs(mean / static_cast<double>(n)) > 1e-9) {
    warn("WaveKin 3: wave_elevation.txt's mean level " +
         FormatNumber(mean / static_cast<double>(n)) + " m is not a wave: left out");
  }
  for (std::size_t k = 1; k <= n / 2; ++k) {
    if (static_cast<double>(k) * dw > 0.5 * 2.0 * std::numbers::pi) break;  // as MoorDyn cuts
    std::complex<double> x = 0.0;
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(n);
    const std::complex<double> step = std::polar(1.0, angle * static_cast<double>(k));
    std::complex<double> turn = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      // exp(-2 pi i k i / N), advanced by a rotation and re-anchored every 1024 samples so
      // that rounding cannot accumulate.
      if (i % 1024 == 0) turn = std::polar(1.0, angle * static_cast<double>(k * i % n));
      x += zeta[i] * turn;
      turn *= step;
    }
    // Amplitude 2 |X| / N, but the Nyquist bin's real part once.
    const std::complex<double> a = k == n / 2
                                       ? std::complex<double>(x.real() / static_cast<double>(n))
                                       : 2.0 * x / static_cast<double>(n);
    if (std::abs(a) < 1e-12) continue;
    waves.push_back({static_cast<double>(k) * dw, std::abs(a), std::arg(a), 0.0});
  }
  return waves;
}

// MoorDyn's current files (Currents 1, 2, 5) as a table in MoorDyn's frame: axes x, y, z
// (up) and t, velocities (ux, uy, uz) at ((ix ny + iy) nz + iz) nt + it.
struct MdCurrent {
  std::vector<double> x{0.0}, y{0.0}, z, t{0.0};
  std::vector<Vec3> velocity;
  double period = 0.0;  // MoorDyn repeats a table sampled in time (Currents 2 and 5)
  std::string file;
};

// A strictly increasing axis read from fields [first, first + count).
std::vector<double> AxisOf(const std::vector<std::string>& fields, std::size_t first,
                           std::size_t count, const std::string& where, std::size_t row,
                           const std::string& name) {
  std::vector<double> axis;
  for (std::size_t k = first; k < first + count; ++k) {
    axis.push_back(NumberAt(fields, k, where, row));
    if (axis.size() > 1 && !(axis.back() > axis[axis.size() - 2])) {
      throw InputError(where + ", line " + std::to_string(row + 1) + ": the " + name +
                       " values must increase");
    }
  }
  if (axis.empty()) {
    throw InputError(where + ", line " + std::to_string(row + 1) + ": no " + name + " values");
  }
  return axis;
}

// MoorDyn samples a table given in time every smallest step from 0 and repeats it after
// as many steps as reach the last time, plus one.
double RepeatPeriod(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < t.size(); ++i) dt = std::min(dt, t[i] - t[i - 1]);
  return (std::floor(t.back() / dt) + 1.0) * dt;
}

MdCurrent CurrentFile(const std::string& path, int line, int mode) {
  MdCurrent c;
  c.file = mode == 1 ? "current_profile.txt"
                     : (mode == 2 ? "current_profile_dynamic.txt" : "current_profile_4d.txt");
  const std::string where =
      path + ":" + std::to_string(line) + ": Currents " + std::to_string(mode) + ": " + c.file;
  const auto lines = BesideFileRows(path, c.file, where);
  const auto velocity_at = [&](std::size_t ix, std::size_t iy, std::size_t iz,
                               std::size_t it) -> Vec3& {
    return c.velocity[((ix * c.y.size() + iy) * c.z.size() + iz) * c.t.size() + it];
  };
  if (mode == 1) {
    // Three header lines, then rows "z ux [uy [uz]]".
    std::vector<Vec3> rows;
    for (std::size_t i = 3; i < lines.size(); ++i) {
      if (lines[i].empty()) continue;
      const std::vector<std::string>& f = lines[i];
      c.z.push_back(NumberAt(f, 0, where, i));
      if (c.z.size() > 1 && !(c.z.back() > c.z[c.z.size() - 2])) {
        throw InputError(where + ", line " + std::to_string(i + 1) + ": z must increase");
      }
      rows.emplace_back(NumberAt(f, 1, where, i), f.size() > 2 ? NumberAt(f, 2, where, i) : 0.0,
                        f.size() > 3 ? NumberAt(f, 3, where, i) : 0.0);
    }
    if (rows.empty()) throw InputError(where + ": no rows \"z ux uy uz\" after its three headers");
    c.velocity = rows;
    return c;
  }
  if (mode == 2) {
    // Line 5: the z values; from line 7: "t ux(z1..zn) [uy(z1..zn) [uz(z1..zn)]]".
    if (lines.size() < 7) throw InputError(where + ": the z values on line 5, rows from line 7");
    c.z = AxisOf(lines[4], 0, lines[4].size(), where, 4, "z");
    const std::size_t nz = c.z.size();
    std::vector<std::vector<Vec3>> rows;
    c.t.clear();
    for (std::size_t i = 6; i < lines.size(); ++i) {
      if (lines[i].empty()) continue;
      const std::vector<std::string>& f = lines[i];
      if (f.size() != nz + 1 && f.size() != 2 * nz + 1 && f.size() != 3 * nz + 1) {
        throw InputError(where + ", line " + std::to_string(i + 1) + ": " +
                         std::to_string(f.size()) + " fields; a row is t and " +
                         std::to_string(nz) + " values of ux (then of uy, then of uz)");
      }
      c.t.push_back(NumberAt(f, 0, where, i));
      if (c.t.size() > 1 && !(c.t.back() > c.t[c.t.size() - 2])) {
        throw InputError(where + ", line " + std::to_string(i + 1) + ": t must increase");
      }
      std::vector<Vec3> profile(nz, Vec3::Zero());
      for (std::size_t k = 0; k < nz; ++k) {
        for (std::size_t m = 0; m < 3 && (m + 1) * nz + 1 <= f.size(); ++m) {
          profile[k](static_cast<Eigen::Index>(m)) = NumberAt(f, 1 + m * nz + k, where, i);
        }
      }
      rows.push_back(profile);
    }
    if (rows.empty()) throw InputError(where + ": no rows from line 7");
    c.velocity.assign(nz * c.t.size(), Vec3::Zero());
    for (std::size_t it = 0; it < c.t.size(); ++it) {
      for (std::size_t iz = 0; iz < nz; ++iz) velocity_at(0, 0, iz, it) = rows[it][iz];
    }
    c.period = RepeatPeriod(c.t);
    return c;
  }
  // Currents 5: line 1 the counts nx ny nz nt, lines 2-5 the axes, then one row per point
  // "x y z t ux uy uz".
  if (lines.size() < 6) throw InputError(where + ": the counts, four axes, then the rows");
  std::size_t counts[4];
  for (std::size_t a = 0; a < 4; ++a) {
    const double n = NumberAt(lines[0], a, where, 0);
    if (!(n >= 1.0 && n <= 1e6 && n == std::floor(n))) {
      throw InputError(where + ", line 1: the counts nx ny nz nt must be whole numbers >= 1");
    }
    counts[a] = static_cast<std::size_t>(n);
  }
  c.x = AxisOf(lines[1], 0, counts[0], where, 1, "x");
  c.y = AxisOf(lines[2], 0, counts[1], where, 2, "y");
  c.z = AxisOf(lines[3], 0, counts[2], where, 3, "z");
  c.t = AxisOf(lines[4], 0, counts[3], where, 4, "t");
  const double points = static_cast<double>(counts[0]) * static_cast<double>(counts[1]) *
                        static_cast<double>(counts[2]) * static_cast<double>(counts[3]);
  if (points > 1e7) throw InputError(where + ": more than 1e7 grid points");
  c.velocity.assign(static_cast<std::size_t>(points), Vec3::Zero());
  std::vector<char> seen(c.velocity.size(), 0);
  std::size_t given = 0;
  const auto index_on = [&](const std::vector<double>& axis, double v, std::size_t i,
                            const char* name) {
    const auto it = std::find(axis.begin(), axis.end(), v);
    if (it == axis.end()) {
      throw InputError(where + ", line " + std::to_string(i + 1) + ": " + name + " " +
                       FormatNumber(v) + " is not on its axis");
    }
    return static_cast<std::size_t>(it - axis.begin());
  };
  for (std::size_t i = 5; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const std::vector<std::string>& f = lines[i];
    if (f.size() != 7) {
      throw InputError(where + ", line " + std::to_string(i + 1) + ": a row is x y z t ux uy uz");
    }
    const std::size_t ix = index_on(c.x, NumberAt(f, 0, where, i), i, "x");
    const std::size_t iy = index_on(c.y, NumberAt(f, 1, where, i), i, "y");
    const std::size_t iz = index_on(c.z, NumberAt(f, 2, where, i), i, "z");
    const std::size_t it = index_on(c.t, NumberAt(f, 3, where, i), i, "t");
    const std::size_t k = ((ix * c.y.size() + iy) * c.z.size() + iz) * c.t.size() + it;
    if (seen[k]) {
      throw InputError(where + ", line " + std::to_string(i + 1) + ": the point is given twice");
    }
    seen[k] = 1;
    ++given;
    c.velocity[k] =
        Vec3(NumberAt(f, 4, where, i), NumberAt(f, 5, where, i), NumberAt(f, 6, where, i));
  }
  if (given != c.velocity.size()) {
    throw InputError(where + ": " + std::to_string(given) + " rows for " +
                     std::to_string(c.velocity.size()) + " grid points");
  }
  c.period = RepeatPeriod(c.t);
  return c;
}

std::string SeafloorGrid(const std::string& path, int line, const std::string& name, double shift_x,
                         double shift_y) {
  const std::string where = path + ":" + std::to_string(line) + ": SeafloorFile " + name;
  const std::filesystem::path found = FindBesideInput(path, name, where);
  const std::string text =
      strict_yaml::ReadInputFile(found.string(), kMaxFileBytes, "MoorDyn seafloor");
  std::istringstream in(text);
  std::vector<double> numbers;
  for (std::string token; in >> token;) {
    const std::optional<double> value = ToNumber(token);
    if (!value) throw InputError(where + ": '" + token + "' is not a number");
    numbers.push_back(*value);
  }
  const auto bad = [&](const std::string& what) { return InputError(where + ": " + what); };
  if (numbers.size() < 2 || numbers[0] < 2 || numbers[1] < 2 ||
      numbers[0] != std::floor(numbers[0]) || numbers[1] != std::floor(numbers[1])) {
    throw bad("it must start with the point counts nx and ny (2 or more each)");
  }
  // The counts as read (a double: 2^63 or 1e300 are no size), and the numbers they need,
  // also a double, so that no product wraps around.
  const double need = 2.0 + numbers[0] + numbers[1] + 3.0 * numbers[0] * numbers[1];
  if (static_cast<double>(numbers.size()) != need) {
    throw bad("holds " + std::to_string(numbers.size()) + " numbers where " +
              FormatNumber(numbers[0]) + " x " + FormatNumber(numbers[1]) + " points need " +
              FormatNumber(need));
  }
  // The file's numbers are few (its size is bounded), so the counts fit a size_t now.
  const std::size_t nx = static_cast<std::size_t>(numbers[0]);
  const std::size_t ny = static_cast<std::size_t>(numbers[1]);
  const double* xs = numbers.data() + 2;
  const double* ys = xs + nx;
  const double* rows = ys + ny;
  std::ostringstream grid;
  grid << "# depth [m, down] below (x north, y east) [m]: MoorDyn's SeafloorFile " << name
       << ", y reversed (MoorDyn's y points to port), heights made depths";
  if (shift_x != 0.0 || shift_y != 0.0) grid << ", moved with the model";
  grid << "\nx\\y";
  for (std::size_t j = ny; j-- > 0;) grid << ", " << FormatNumber(-(ys[j] - shift_y) + 0.0);
  grid << "\n";
  for (std::size_t i = 0; i < nx; ++i) {
    grid << FormatNumber(xs[i] - shift_x);
    for (std::size_t j = ny; j-- > 0;) {
      const double* p = rows + 3 * (i * ny + j);
      if (p[0] != xs[i] || p[1] != ys[j]) {
        throw bad("point " + std::to_string(i * ny + j + 1) + " is at (" + FormatNumber(p[0]) +
                  ", " + FormatNumber(p[1]) + ") where the axes put (" + FormatNumber(xs[i]) +
                  ", " + FormatNumber(ys[j]) + ")");
      }
      grid << ", " << FormatNumber(-p[2] + 0.0);
    }
    grid << "\n";
  }
  return grid.str();
}

// A line type's EA given as a file: MoorDyn's nonlinear stiffness, three header lines and
// then rows "strain tension" (tension in N), which MoorDyn interpolates linearly. Returns
// the points past (0, 0) (a first row at the origin is left out: moorsim's curve starts
// there); each must exceed the one before in both, or the row is one located line.
std::vector<std::pair<double, double>> StiffnessTable(const std::string& path, int line,
                                                      const std::string& name) {
  const std::string where = path + ":" + std::to_string(line) + ": EA table " + name;
  const std::filesystem::path found = FindBesideInput(path, name, where);
  const std::string text =
      strict_yaml::ReadInputFile(found.string(), kMaxFileBytes, "MoorDyn EA table");
  std::istringstream in(text);
  std::vector<std::pair<double, double>> points;
  int number = 0;
  for (std::string row; std::getline(in, row);) {
    if (++number <= 3) continue;  // the headers
    std::istringstream fields(row);
    std::string a, b;
    if (!(fields >> a)) continue;  // a blank row
    const std::string at = found.string() + ":" + std::to_string(number) + ": ";
    const std::optional<double> strain = ToNumber(a);
    const std::optional<double> tension = (fields >> b) ? ToNumber(b) : std::nullopt;
    if (!strain || !tension) {
      throw InputError(at + "'" + row + "' must be a strain and a tension [N]");
    }
    if (points.empty() && *strain == 0.0 && *tension == 0.0) continue;
    const std::pair<double, double> before = points.empty() ? std::pair(0.0, 0.0) : points.back();
    if (!(*strain > before.first && *tension > before.second)) {
      throw InputError(at + "strain " + FormatNumber(*strain) + " and tension " +
                       FormatNumber(*tension) + " N must both exceed the row before's (" +
                       FormatNumber(before.first) + " and " + FormatNumber(before.second) + " N)");
    }
    points.emplace_back(*strain, *tension);
  }
  if (points.empty()) throw InputError(where + ": holds no strain-tension rows");
  return points;
}

// Where the values of the written scenario come from in the MoorDyn file. Each is marked as
// it is written (its offset in the text), so that what the loader says of the scenario,
// which the user does not see, is said of the MoorDyn file's line and field instead.
class Origins {
 public:
  explicit Origins(std::ostringstream& text) : text_(text) {}

  // Records that what is written next comes from `field` of line `line` (0: of no line,
  // a default) of the MoorDyn file; returns "" to be written in its place.
  const char* operator()(int line, std::string field) {
    marks_.push_back({static_cast<std::size_t>(text_.tellp()), line, std::move(field)});
    return "";
  }

  // The loader's refusal of the scenario `yaml`, read as `name` ("<name>:L:C: key: what",
  // one per line), with each line located at its value's origin in the MoorDyn file `path`:
  // "<path>:<line>: <field>: what (the scenario's key)".
  std::string Relocate(const std::string& refused, const std::string& name, const std::string& path,
                       const std::string& yaml) const {
    // Each mark's line and column in the text.
    std::vector<std::pair<int, int>> at;
    int line = 1;
    std::size_t line_start = 0, scanned = 0;
    for (const Mark& m : marks_) {
      for (; scanned < m.offset && scanned < yaml.size(); ++scanned) {
        if (yaml[scanned] == '\n') {
          ++line;
          line_start = scanned + 1;
        }
      }
      at.emplace_back(line, static_cast<int>(m.offset - line_start) + 1);
    }
    // One message per line, each starting with `name` (which may hold a newline itself).
    std::vector<std::size_t> starts;
    for (std::size_t k = 0; k < refused.size(); k = refused.find('\n', k) + 1) {
      if (refused.compare(k, name.size() + 1, name + ":") == 0 || k == 0) starts.push_back(k);
      if (refused.find('\n', k) == std::string::npos) break;
    }
    std::string out;
    for (std::size_t i = 0; i < starts.size(); ++i) {
      const std::size_t end = i + 1 < starts.size() ? starts[i + 1] - 1 : refused.size();
      if (!out.empty()) out += "\n";
      out += RelocateOne(refused.substr(starts[i], end - starts[i]), name, path, at);
    }
    return out;
  }

 private:
  struct Mark {
    std::size_t offset;
    int line;
    std::string field;
  };

  std::string RelocateOne(const std::string& message, const std::string& name,
                          const std::string& path,
                          const std::vector<std::pair<int, int>>& at) const {
    const std::string refused = "the imported model is one moorsim refuses: ";
    if (message.rfind(name + ":", 0) != 0) return path + ": " + refused + message;
    // "L:C: key: what" (or ": what" with no position).
    std::string rest = message.substr(name.size() + 1);
    int line = 0, column = 0;
    const auto [after_line, line_error] =
        std::from_chars(rest.data(), rest.data() + rest.size(), line);
    if (line_error == std::errc() && *after_line == ':') {
      const char* from = after_line + 1;
      const auto [after_column, column_error] =
          std::from_chars(from, rest.data() + rest.size(), column);
      if (column_error == std::errc()) rest.erase(0, after_column - rest.data());
    }
    if (rest.rfind(": ", 0) == 0) rest.erase(0, 2);
    // The scenario's key path, kept after the message for whoever reads the scenario.
    std::string key;
    const std::size_t colon = rest.find(": ");
    if (colon != std::string::npos &&
        std::all_of(rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '[' ||
                 c == ']';
        })) {
      key = rest.substr(0, colon);
      rest.erase(0, colon + 2);
    }
    const std::string in_scenario = key.empty() ? "" : " (the scenario's " + key + ")";
    // The last mark at or before the message's position.
    const Mark* origin = nullptr;
    for (std::size_t k = 0; k < marks_.size(); ++k) {
      if (at[k] <= std::pair(line, std::max(column, 1))) origin = &marks_[k];
    }
    if (line == 0 || origin == nullptr || origin->line == 0) {
      return path + ": " + refused + rest + in_scenario;
    }
    return path + ":" + std::to_string(origin->line) + ": " + origin->field + ": " + rest +
           in_scenario;
  }

  std::ostringstream& text_;
  std::vector<Mark> marks_;
};

}  // namespace

MoorDynImport ImportMoorDyn(const std::string& path, const std::string& command,
                            const std::string& files_stem) {
  const std::string text = strict_yaml::ReadInputFile(path, kMaxFileBytes, "MoorDyn input");
  // Names and fields go into the scenario as they are: the file is UTF-8 (or ASCII), said at
  // its line, not where the scenario would be refused for it.
  if (const std::optional<std::size_t> bad = strict_yaml::FirstInvalidUtf8(text)) {
    throw InputError(path + ":" + std::to_string(strict_yaml::MarkOfOffset(text, *bad).line) +
                     ": " + strict_yaml::InvalidUtf8(text, *bad));
  }
  const std::vector<Section> sections = ReadSections(text);
  Problems problems(path);
  MoorDynImport out;
  const auto warn = [&](int line, const std::string& what) {
    out.warnings.push_back(path + ":" + std::to_string(line) + ": " + what);
  };

  std::vector<MdLineType> types;
  std::vector<Point> points;
  std::vector<MdLine> lines;
  std::map<std::string, std::pair<double, int>> options;  // name (lower case) -> value, line
  std::vector<std::string> settings;                      // options that are not the model
  std::optional<std::pair<std::string, int>> seafloor;    // SeafloorFile: its path, line
  std::string title;
  bool any_table = false;
  std::map<Kind, int> section_line;  // the first of each kind
  for (const Section& section : sections) {
    const Kind kind = KindOf(section.title);
    section_line.emplace(kind, section.line);
    if (kind == Kind::kTitle) {
      if (!section.rows.empty()) {
        std::string first;
        for (const std::string& f : section.rows.front().fields)
          first += (first.empty() ? "" : " ") + f;
        title = first;
      }
      continue;
    }
    if (kind == Kind::kEnd || kind == Kind::kOutputs) continue;
    const bool table = kind == Kind::kLineTypes || kind == Kind::kPoints || kind == Kind::kLines ||
                       kind == Kind::kRodTypes || kind == Kind::kBodies || kind == Kind::kRods;
    if (table && section.rows.size() <= 2) continue;  // column names and units only
    if (kind == Kind::kRodTypes || kind == Kind::kRods || kind == Kind::kBodies) {
      problems.Add(section.rows[2].line,
                   (kind == Kind::kBodies ? "bodies" : "rods") +
                       std::string(" are not supported (moorsim models lines, points and the "
                                   "vessel)"));
      continue;
    }
    if (kind == Kind::kOther) {
      if (!section.rows.empty()) {
        problems.Add(section.line, "section '" + section.title + "' is not supported");
      }
      continue;
    }
    if (kind == Kind::kOptions) {
      for (const Row& row : section.rows) {
        if (row.fields.size() < 2) continue;
        const std::string name = Lower(row.fields[1]);
        const std::optional<double> value = ToNumber(row.fields[0]);
        options[name] = {value.value_or(std::nan("")), row.line};
        static const std::set<std::string> kModel = {
            "wtrdpth", "wtrdnsty", "g", "gravity", "kbot", "cbot", "frictioncoefficient"};
        static const std::set<std::string> kUnsupported = {"watrkin", "seafloor", "bathymetry"};
        if (name == "seafloorfile") {
          seafloor = {row.fields[0], row.line};
        } else if ((name == "wavekin" && value != 1.0) || name == "currents") {
          // Read after the tables (the files MoorDyn reads for them sit beside the input).
          static const std::set<double> kWaveKin = {0.0, 2.0, 3.0, 7.0};
          static const std::set<double> kCurrents = {0.0, 1.0, 2.0, 5.0};
          const std::set<double>& known = name == "wavekin" ? kWaveKin : kCurrents;
          if (!value || known.count(*value) == 0) {
            problems.Add(row.line,
                         "option " + row.fields[1] + " " + row.fields[0] +
                             " is not supported (WaveKin 0, 1, 2, 3 or 7 and Currents 0, 1, 2 "
                             "or 5 are: MoorDyn v2.7.1 does not implement its node approaches "
                             "either)");
          }
        } else if (name == "wavekin" && value == 1.0) {
          // Waves driven through the API: the file holds none, the coupling program gives
          // them step by step; without it MoorDyn's water is still too.
          warn(row.line,
               "option WaveKin 1: the wave kinematics come from the coupling program through "
               "MoorDyn's API; the imported model sees still water (or moorsim's own waves, "
               "environment.waves with on_lines)");
        } else if (kUnsupported.count(name) > 0 && row.fields[0] != "0") {
          problems.Add(row.line, "option " + row.fields[1] + " " + row.fields[0] +
                                     " is not supported (a flat seabed and still water, or "
                                     "moorsim's own current and waves)");
        } else if (kModel.count(name) > 0 && !value) {
          problems.Add(row.line,
                       "option " + row.fields[1] + " '" + row.fields[0] + "' is not a number");
        } else if (kModel.count(name) == 0) {
          settings.push_back(row.fields[1] + " " + row.fields[0]);
        }
      }
      continue;
    }
    any_table = true;
    const Row& header = section.rows[0];
    std::vector<Row> rows(section.rows.begin() + 2, section.rows.end());
    if (kind == Kind::kLineTypes) {
      const Columns c(path, header,
                      {{"name", {"typename", "linetype", "name", "type"}},
                       {"diameter", {"diam", "d"}},
                       {"mass", {"mass/m", "massden", "massdeninair", "mass", "m"}},
                       {"unused", {"tbd"}},
                       {"EA", {"ea"}},
                       {"BA", {"ba/-zeta", "ba", "ba/zeta", "c", "cintdamp"}},
                       {"EI", {"ei"}},
                       {"Cd", {"cd", "cdn"}},
                       {"Ca", {"ca", "can"}},
                       {"CdAx", {"cdax", "cdt"}},
                       {"CaAx", {"caax", "cat"}},
                       {"Cl", {"cl"}},
                       {"dF", {"df"}},
                       {"cF", {"cf"}}});
      for (const auto& [name, k] : c.unknown()) {
        problems.Add(header.line, "line-type column '" + name + "' is not supported");
      }
      for (const Row& row : rows) {
        problems.Attempt([&] {
          MdLineType t;
          t.line = row.line;
          t.name = c.Field(row, "name");
          t.diameter = c.Value(row, "diameter");
          t.mass = c.Value(row, "mass");
          const std::string ea = c.Field(row, "EA");
          const std::string ba = c.Has("BA") ? c.Field(row, "BA") : "0";
          const std::string where =
              path + ":" + std::to_string(row.line) + ": line type " + t.name + ": ";
          const std::optional<std::vector<double>> eas = BarSeparated(ea);
          if (eas && (eas->size() == 2 || eas->size() == 3)) {
            // EA_s|EA_D, or EA_s|EA_Dc|EA_D_Lm: EA_D = EA_Dc + EA_D_Lm x the mean load.
            // BA_s|BA_D, or BA_s alone (no damping on the dynamic spring).
            const std::optional<std::vector<double>> bas = BarSeparated(ba);
            if (!bas || bas->size() > 2) {
              throw InputError(where + "BA '" + ba + "' must be BA_s or BA_s|BA_D [N s]");
            }
            const double ba_s = bas->front(), ba_d = bas->size() == 2 ? (*bas)[1] : 0.0;
            const std::vector<double>& v = *eas;
            if (!(v[1] > v[0] && v[0] > 0.0)) {
              throw InputError(where + "EA '" + ea + "': the dynamic stiffness " +
                               (v.size() == 3 ? "EA_Dc" : "EA_D") + " must exceed the static EA_s");
            }
            if (v.size() == 3 && !(v[2] >= 0.0)) {
              throw InputError(where + "EA '" + ea +
                               "': the dynamic stiffness's slope with the mean load EA_D_Lm "
                               "must be >= 0");
            }
            if (!(ba_s > 0.0) || ba_d < 0.0) {
              throw InputError(where + "BA '" + ba +
                               "': a visco-elastic rope's static damping BA_s (moorsim's creep "
                               "dashpot) must be > 0 and its BA_D >= 0, both in N s");
            }
            t.ea = v[0];
            t.dynamic_ea = v[1];
            if (v.size() == 3) t.dynamic_ea_slope = v[2];
            t.static_damping = ba_s;
            t.ba = ba_d;
            if (ba_d > 0.0) {
              warn(row.line, "line type " + t.name + ": BA_D " + FormatNumber(ba_d) +
                                 " damps the whole segment's stretch (moorsim's axial "
                                 "damping), not MoorDyn's dynamic spring alone");
            }
          } else if (!ToNumber(ea) &&
                     (ea.find('|') != std::string::npos || ea.rfind("SYROPE:", 0) == 0)) {
            throw InputError(path + ":" + std::to_string(row.line) + ": EA '" + ea +
                             "': a SYROPE rope or a visco-elastic rope on a tension table is not "
                             "supported yet (give a constant EA or a table, EA_s|EA_D or "
                             "EA_s|EA_Dc|EA_D_Lm with BA_s|BA_D)");
          } else if (!ToNumber(ea)) {
            t.ea_table = ea;
            t.ea_curve = StiffnessTable(path, row.line, ea);
            t.ba = c.Has("BA") ? c.Value(row, "BA") : 0.0;
          } else {
            t.ea = *ToNumber(ea);
            t.ba = c.Has("BA") ? c.Value(row, "BA") : 0.0;
          }
          t.cd = c.Value(row, "Cd");
          t.ca = c.Value(row, "Ca");
          t.cdax = c.Value(row, "CdAx");
          if (c.Has("EI") && c.Value(row, "EI") != 0.0) {
            warn(row.line, "line type " + t.name + ": bending stiffness EI " + c.Field(row, "EI") +
                               " left out (moorsim's lines have none)");
          }
          t.caax = c.Has("CaAx") ? c.Value(row, "CaAx") : 0.0;
          if (c.Has("unused") && c.Value(row, "unused") != 0.0) {
            warn(row.line, "line type " + t.name + ": column tbd " + c.Field(row, "unused") +
                               " left out (a placeholder column)");
          }
          for (const char* viv : {"Cl", "dF", "cF"}) {
            if (c.Has(viv) && c.Value(row, viv) != 0.0) {
              warn(row.line, "line type " + t.name + ": vortex-induced vibration (" +
                                 std::string(viv) + ") left out");
            }
          }
          types.push_back(t);
        });
      }
    } else if (kind == Kind::kPoints) {
      const Columns c(path, header,
                      {{"id", {"id", "node", "point", "connection", "#"}},
                       {"type", {"type", "attachment", "attach"}},
                       {"x", {"x"}},
                       {"y", {"y"}},
                       {"z", {"z"}},
                       {"mass", {"mass", "m"}},
                       {"volume", {"volume", "v"}},
                       {"CdA", {"cda"}},
                       {"Ca", {"ca"}},
                       {"Fx", {"fx"}},
                       {"Fy", {"fy"}},
                       {"Fz", {"fz"}}});
      for (const auto& [name, k] : c.unknown()) {
        problems.Add(header.line, "point column '" + name + "' is not supported");
      }
      for (const Row& row : rows) {
        problems.Attempt([&] {
          Point p;
          p.line = row.line;
          p.id = c.Field(row, "id");
          p.kind_text = c.Field(row, "type");
          const std::string kind_name = Lower(p.kind_text);
          if (kind_name == "fixed" || kind_name == "fix" || kind_name == "anchor") {
            p.kind = PointKind::kFixed;
          } else if (kind_name == "vessel" || kind_name == "coupled" || kind_name == "cpld" ||
                     kind_name == "vessel1") {
            p.kind = PointKind::kVessel;
          } else if (kind_name == "free" || kind_name == "connect" || kind_name == "con") {
            p.kind = PointKind::kFree;
          } else {
            throw InputError(path + ":" + std::to_string(row.line) + ": point " + p.id +
                             " of type '" + p.kind_text +
                             "' is not supported (Fixed, Vessel or Coupled, Free)");
          }
          p.x = c.Value(row, "x");
          p.y = c.Value(row, "y");
          p.z = c.Value(row, "z");
          p.mass = c.Has("mass") ? c.Value(row, "mass") : 0.0;
          p.volume = c.Has("volume") ? c.Value(row, "volume") : 0.0;
          p.cda = c.Has("CdA") ? c.Value(row, "CdA") : 0.0;
          p.ca = c.Has("Ca") ? c.Value(row, "Ca") : 0.0;
          for (const char* force : {"Fx", "Fy", "Fz"}) {
            if (c.Has(force) && c.Value(row, force) != 0.0) {
              throw InputError(path + ":" + std::to_string(row.line) + ": point " + p.id +
                               ": an external force " + force + " " + c.Field(row, force) +
                               " is not supported");
            }
          }
          points.push_back(p);
        });
      }
    } else {
      const Columns c(path, header,
                      {{"id", {"id", "line", "#"}},
                       {"type", {"linetype", "type"}},
                       {"a", {"attacha", "nodea", "nodeanch", "anchor", "attach1", "pointa"}},
                       {"b", {"attachb", "nodeb", "nodefair", "fairlead", "attach2", "pointb"}},
                       {"length", {"unstrlen", "unstrlength", "length", "l"}},
                       {"segments", {"numsegs", "nsegs", "n"}},
                       {"outputs", {"lineoutputs", "outputs", "flags/outputs", "flags"}}});
      for (const auto& [name, k] : c.unknown()) {
        problems.Add(header.line, "line column '" + name + "' is not supported");
      }
      for (const Row& row : rows) {
        problems.Attempt([&] {
          MdLine l;
          l.line = row.line;
          l.id = c.Field(row, "id");
          l.type = c.Field(row, "type");
          l.a = c.Field(row, "a");
          l.b = c.Field(row, "b");
          l.length = c.Value(row, "length");
          const double segments = c.Value(row, "segments");
          if (segments != std::floor(segments) || segments < 1 || segments > 10000) {
            throw InputError(path + ":" + std::to_string(row.line) + ": NumSegs " +
                             c.Field(row, "segments") + " must be a whole number in 1..10000");
          }
          l.segments = static_cast<int>(segments);
          lines.push_back(l);
        });
      }
    }
  }
  if (!any_table) {
    problems.Add(1, "no LINE TYPES, POINTS or LINES tables (not a MoorDyn input file?)");
  }
  // A name given twice would leave one of its rows unused (MoorDyn too keys them by name).
  const auto once = [&](const auto& rows, const char* noun, const auto& name_of) {
    std::map<std::string, int> first;
    for (const auto& row : rows) {
      const auto [it, fresh] = first.emplace(name_of(row), row.line);
      if (!fresh) {
        problems.Add(row.line, std::string(noun) + " " + it->first +
                                   " is given twice (first on line " + std::to_string(it->second) +
                                   ")");
      }
    }
  };
  once(types, "line type", [](const MdLineType& t) { return t.name; });
  once(points, "point", [](const Point& p) { return p.id; });
  once(lines, "line", [](const MdLine& l) { return l.id; });
  problems.ThrowIfAny();

  // The topology: every line's points, then each chain from a fixed point to the vessel.
  const auto point_index = [&](const std::string& id) -> std::optional<std::size_t> {
    std::string name = id;
    // MoorDyn v1 wrote attachments as point numbers; v2 may prefix them ("R1", "Body1")
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (points[k].id == name) return k;
    }
    return std::nullopt;
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    for (const std::string* end : {&lines[i].a, &lines[i].b}) {
      if (const std::optional<std::size_t> k = point_index(*end)) {
        points[*k].lines.push_back(i);
      } else {
        problems.Add(lines[i].line, "line " + lines[i].id + " is attached to '" + *end +
                                        "', which is not a point of the file (rods and bodies "
                                        "are not supported)");
      }
    }
    if (std::none_of(types.begin(), types.end(),
                     [&](const MdLineType& t) { return t.name == lines[i].type; })) {
      problems.Add(lines[i].line,
                   "line " + lines[i].id + ": unknown line type '" + lines[i].type + "'");
    }
  }
  problems.ThrowIfAny();
  // The topology. A free point joining two lines is a joint of one moorsim line through
  // it; one joining one line or three and more (a free end, a bridle's apex, a shared buoy)
  // is a moorsim free point, and so is a joint on no path from a fixed point (between two
  // vessel points). Each moorsim line is a path of MoorDyn lines through joints between two
  // ends that are not joints, written from its lower end (a fixed point, else the deeper
  // free point) to its upper end (a vessel point, else a free point).
  std::vector<bool> junction(points.size(), false);
  for (std::size_t k = 0; k < points.size(); ++k) {
    junction[k] = points[k].kind == PointKind::kFree && points[k].lines.size() != 2;
  }
  struct Chain {
    std::vector<std::size_t> lines;   // from the lower end up
    std::vector<std::size_t> joints;  // the free points between them
    std::size_t lower = 0, upper = 0;
  };
  std::vector<Chain> chains;
  std::vector<bool> used(lines.size(), false);
  const auto is_end = [&](std::size_t k) {
    return points[k].kind != PointKind::kFree || junction[k];
  };
  // The path from end point `from` along line `first`, or nothing if it loops.
  const auto walk = [&](std::size_t from, std::size_t first) -> std::optional<Chain> {
    Chain chain;
    chain.lower = from;
    std::size_t at = from;
    std::size_t line = first;
    while (true) {
      chain.lines.push_back(line);
      used[line] = true;
      const std::size_t next =
          *point_index(lines[line].a == points[at].id ? lines[line].b : lines[line].a);
      if (is_end(next)) {
        chain.upper = next;
        return chain;
      }
      chain.joints.push_back(next);
      at = next;
      line = points[next].lines[0] == line ? points[next].lines[1] : points[next].lines[0];
      if (used[line]) return std::nullopt;
    }
  };
  // Which end is the lower: a fixed point, else a free point below the other; never a vessel
  // point.
  const auto rank = [&](std::size_t k) {
    return points[k].kind == PointKind::kFixed ? 0 : points[k].kind == PointKind::kFree ? 1 : 2;
  };
  const auto add = [&](Chain chain) {
    const Point& a = points[chain.lower];
    const Point& b = points[chain.upper];
    if (rank(chain.upper) < rank(chain.lower) ||
        (rank(chain.lower) == 1 && rank(chain.upper) == 1 && b.z < a.z)) {
      std::swap(chain.lower, chain.upper);
      std::reverse(chain.lines.begin(), chain.lines.end());
      std::reverse(chain.joints.begin(), chain.joints.end());
    }
    const MdLine& first = lines[chain.lines.front()];
    const Point& lower = points[chain.lower];
    const Point& upper = points[chain.upper];
    if (chain.lower == chain.upper) {
      problems.Add(first.line,
                   "line " + first.id + " runs in a loop from point " + lower.id + " back to it");
    } else if (lower.kind == PointKind::kFixed && upper.kind == PointKind::kFixed) {
      problems.Add(first.line, "line " + first.id + " leads from fixed point " + lower.id +
                                   " to fixed point " + upper.id + ", which moorsim does not hold");
    } else if (lower.kind == PointKind::kVessel) {
      problems.Add(first.line, "line " + first.id + " runs between vessel points " + lower.id +
                                   " and " + upper.id);
    } else {
      chains.push_back(chain);
    }
  };
  for (int pass = 0; pass < 2; ++pass) {
    // Fixed points first (so lines read from their anchors), then the free points.
    // A vessel point's lines last, after the joints between two vessel points have become
    // free points.
    for (const PointKind kind : {PointKind::kFixed, PointKind::kFree, PointKind::kVessel}) {
      if (kind == PointKind::kVessel && pass == 0) continue;
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (points[k].kind != kind || !is_end(k)) continue;
        for (const std::size_t line : points[k].lines) {
          if (used[line]) continue;
          if (const std::optional<Chain> chain = walk(k, line)) {
            add(*chain);
          } else {
            problems.Add(lines[line].line, "line " + lines[line].id +
                                               " leads into a loop of free points from point " +
                                               points[k].id);
          }
        }
      }
    }
    // Joints still on no path (between two vessel points): free points of their own.
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (points[k].kind != PointKind::kFree || junction[k]) continue;
      junction[k] = std::any_of(points[k].lines.begin(), points[k].lines.end(),
                                [&](std::size_t line) { return !used[line]; });
    }
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!used[i]) {
      problems.Add(lines[i].line,
                   "line " + lines[i].id + " is in a loop of free points that reaches no end");
    }
  }
  const auto option = [&](const std::string& name) -> std::optional<std::pair<double, int>> {
    const auto it = options.find(name);
    if (it == options.end()) return std::nullopt;
    return it->second;
  };
  // MoorDyn's water depth: WtrDpth (0 unless given), deepened to any point listed below it
  // (MoorDyn v2 warns and does the same, so a file may leave WtrDpth out).
  std::optional<std::pair<double, int>> depth = option("wtrdpth");
  bool depth_given = true;  // false: a point's
  for (const Point& p : points) {
    if (-p.z > (depth ? depth->first : 0.0)) {
      if (depth) {
        warn(p.line, "point " + p.id + " lies below the water depth WtrDpth (" +
                         FormatNumber(depth->first) + " m): the depth is taken to it (" +
                         FormatNumber(-p.z) + " m), as MoorDyn does");
      }
      depth = std::make_pair(-p.z, p.line);
      depth_given = false;
    }
  }
  if (!depth) problems.Add(1, "no WtrDpth option and no point below the water: no water depth");
  if (chains.empty()) problems.Add(1, "no line moorsim can hold");
  problems.ThrowIfAny();

  // Vessel points far from MoorDyn's origin (a Coupled point given where it starts, a line
  // driven at its end): the model moves horizontally so that their centre is moorsim's
  // origin, the vessel's reference point, and they are points of the vessel again.
  double shift_x = 0.0, shift_y = 0.0;
  {
    double sum_x = 0.0, sum_y = 0.0, far = 0.0;
    int count = 0;
    for (const Point& p : points) {
      if (p.kind != PointKind::kVessel) continue;
      sum_x += p.x;
      sum_y += p.y;
      far = std::max({far, std::abs(p.x), std::abs(p.y)});
      ++count;
    }
    if (count > 0 && far > schema::kMaxBodyCoordinate) {
      shift_x = sum_x / count;
      shift_y = sum_y / count;
      for (Point& p : points) {
        p.x -= shift_x;
        p.y -= shift_y;
      }
    }
  }

  // A bathymetry file: a depth grid beside the scenario.
  if (seafloor) {
    problems.Attempt([&] {
      const std::string stem =
          files_stem.empty() ? std::filesystem::path(path).stem().string() : files_stem;
      const std::string grid_name = stem + "_seabed.csv";
      out.files.push_back(
          {grid_name, SeafloorGrid(path, seafloor->second, seafloor->first, shift_x, shift_y)});
    });
    problems.ThrowIfAny();
  }

  const auto rho = option("wtrdnsty");
  auto gravity = option("g");
  if (!gravity) gravity = option("gravity");

  // MoorDyn's waves and current, read from the files beside the input.
  const auto wavekin = option("wavekin");
  const auto currents = option("currents");
  std::vector<vessel::WaveComponent> trains;
  std::optional<MdCurrent> current;
  const auto warn_at = [&](int line) {
    return std::function<void(const std::string&)>(
        [&, line](const std::string& what) { warn(line, what); });
  };
  if (wavekin && (wavekin->first == 2.0 || wavekin->first == 3.0 || wavekin->first == 7.0)) {
    problems.Attempt([&] {
      const int mode = static_cast<int>(wavekin->first);
      const auto dt_wave = option("dtwave");
      const std::vector<MdWave> waves =
          mode == 3 ? ElevationWaves(path, wavekin->second, dt_wave ? dt_wave->first : 0.25,
                                     warn_at(wavekin->second))
                    : SpectrumWaves(path, wavekin->second, mode, warn_at(wavekin->second));
      const double depth_m = depth->first;
      for (const MdWave& w : waves) {
        // Moved with the model: the phase at the new origin. Then y and the direction
        // mirrored (MoorDyn's y points to port).
        const double k = mooring_fem::WaveKinematics::WaveNumber(w.omega, depth_m,
                                                                 gravity ? gravity->first : 9.81);
        const double phase =
            w.phase - k * (shift_x * std::cos(w.beta) + shift_y * std::sin(w.beta));
        trains.push_back({w.omega, w.amplitude, phase, -w.beta});
      }
      if (trains.empty()) warn(wavekin->second, "WaveKin: the waves' files hold no wave");
    });
  }
  if (currents && currents->first != 0.0) {
    problems.Attempt(
        [&] { current = CurrentFile(path, currents->second, static_cast<int>(currents->first)); });
  }
  problems.ThrowIfAny();
  std::string seabed_file;
  if (!out.files.empty()) seabed_file = out.files.front().first;
  // A current that is one direction at every depth and steady is moorsim's profile;
  // otherwise a table beside the scenario.
  std::optional<std::pair<double, std::vector<std::pair<double, double>>>> profile;
  std::string current_file;
  if (current) {
    const MdCurrent& c = *current;
    Vec3 along = Vec3::Zero();
    bool one_direction = c.x.size() == 1 && c.y.size() == 1 && c.t.size() == 1;
    for (const Vec3& v : c.velocity) {
      if (v.z() != 0.0) one_direction = false;
      if (along.isZero() && !v.isZero()) along = v.normalized();
      if (!v.isZero() && (v - v.norm() * along).norm() > 1e-12 * v.norm()) one_direction = false;
    }
    if (one_direction) {
      // moorsim: direction from north (x) toward east (-y); depths down, from the surface.
      const double direction = std::atan2(-along.y(), along.x());
      std::vector<std::pair<double, double>> points;  // depth, speed
      for (std::size_t k = c.z.size(); k-- > 0;) {
        if (c.z[k] <= 0.0) points.push_back({-c.z[k] + 0.0, c.velocity[k].norm()});
      }
      // Points above the mean surface are left out, and the surface's value added where
      // the points straddle it.
      const auto above = std::find_if(c.z.begin(), c.z.end(), [](double z) { return z > 0.0; });
      if (above != c.z.end() && above != c.z.begin() && *(above - 1) < 0.0) {
        const std::size_t k = static_cast<std::size_t>(above - c.z.begin());
        const double f = -c.z[k - 1] / (c.z[k] - c.z[k - 1]);
        const double speed =
            c.velocity[k - 1].norm() + f * (c.velocity[k].norm() - c.velocity[k - 1].norm());
        points.insert(points.begin(), {0.0, speed});
      }
      if (points.empty()) points.push_back({0.0, c.velocity.back().norm()});
      profile = {along.isZero() ? 0.0 : direction, points};
    } else {
      const std::string stem =
          files_stem.empty() ? std::filesystem::path(path).stem().string() : files_stem;
      current_file = stem + "_current.txt";
      std::ostringstream table;
      table << "# The water's velocity [m/s] over north x, east y, depth [m] and time [s]: "
               "MoorDyn's "
            << c.file << " (Currents " << currents->first
            << "), y and z reversed (MoorDyn's y points to port and its z up)";
      if (shift_x != 0.0 || shift_y != 0.0) table << ", moved with the model";
      table << "\nx:";
      for (double x : c.x) table << " " << FormatNumber(x - shift_x);
      table << "\ny:";
      for (std::size_t j = c.y.size(); j-- > 0;)
        table << " " << FormatNumber(-(c.y[j] - shift_y) + 0.0);
      table << "\ndepth:";
      for (std::size_t k = c.z.size(); k-- > 0;) table << " " << FormatNumber(-c.z[k] + 0.0);
      table << "\ntime:";
      for (double t : c.t) table << " " << FormatNumber(t);
      table << "\n# x, y, depth, time, velocity north, east, down\n";
      for (std::size_t i = 0; i < c.x.size(); ++i) {
        for (std::size_t j = c.y.size(); j-- > 0;) {
          for (std::size_t k = c.z.size(); k-- > 0;) {
            for (std::size_t l = 0; l < c.t.size(); ++l) {
              const Vec3& v = c.velocity[((i * c.y.size() + j) * c.z.size() + k) * c.t.size() + l];
              table << FormatNumber(c.x[i] - shift_x) << " "
                    << FormatNumber(-(c.y[j] - shift_y) + 0.0) << " " << FormatNumber(-c.z[k] + 0.0)
                    << " " << FormatNumber(c.t[l]) << " " << FormatNumber(v.x()) << " "
                    << FormatNumber(-v.y() + 0.0) << " " << FormatNumber(-v.z() + 0.0) << "\n";
            }
          }
        }
      }
      out.files.push_back({current_file, table.str()});
    }
  }

  // The scenario.
  std::ostringstream y;
  Origins from(y);
  y << "# yaml-language-server: $schema=moorsim.schema.json\n";
  y << "# Imported from the MoorDyn input file " << strict_yaml::OneLine(path) << " by `"
    << strict_yaml::OneLine(command) << "` (moorsim " << moorsim::kVersion << ").\n";
  if (!title.empty()) y << "# Its title: " << title << "\n";
  y << "# Frames: MoorDyn's z points up from the still water level and its y to port; here z\n"
       "# points down and y to starboard, so (x, y, z) there is (x, -y, -z) here. Fixed points\n"
       "# are anchors (Earth frame), vessel points fairleads (body frame), free points joining\n"
       "# two lines the joints of a line's sections, other free points (free ends, bridles,\n"
       "# shared buoys) moorsim's free points. Line numbers are moorsim's, from 1; each says\n"
       "# which MoorDyn lines and points it is made of.\n";
  if (shift_x != 0.0 || shift_y != 0.0) {
    y << "# The vessel points lie far from MoorDyn's origin: every point is moved by ("
      << FormatNumber(-shift_x + 0.0) << ", " << FormatNumber(-shift_y + 0.0)
      << ") m in MoorDyn's x and y, so that their centre is the vessel's reference point.\n";
  }
  if (!settings.empty()) {
    y << "# Integration and output settings of the file, not part of the model (moorsim's\n"
         "# integrator chooses its own steps):";
    for (const std::string& s : settings) y << " " << s << ";";
    y << "\n";
  }
  for (const std::string& w : out.warnings) y << "# Left out: " << strict_yaml::OneLine(w) << "\n";
  const std::string stem = std::filesystem::path(path).stem().string();
  y << "name: " << Text(stem) << "\n";
  y << "mooring:\n";
  y << "  water: {" << from(rho ? rho->second : 0, "option WtrDnsty")
    << "density: " << FormatNumber(rho ? rho->first : 1025.0) << ", "
    << from(gravity ? gravity->second : 0, "option g")
    << "gravity: " << FormatNumber(gravity ? gravity->first : 9.81) << ", "
    << from(depth->second, depth_given ? "option WtrDpth" : "the deepest point")
    << "depth: " << FormatNumber(depth->first) << "}  # "
    << (depth_given ? "WtrDpth (line " + std::to_string(depth->second) + ")"
                    : "the deepest point's depth (line " + std::to_string(depth->second) +
                          "), as MoorDyn takes it");
  y << (rho ? ", WtrDnsty (line " + std::to_string(rho->second) + ")"
            : ", MoorDyn's default density");
  y << (gravity ? ", g (line " + std::to_string(gravity->second) + ")"
                : ", MoorDyn's default gravity")
    << "\n";
  const auto kbot = option("kbot");
  const auto cbot = option("cbot");
  const double seabed_stiffness = kbot ? kbot->first : 3.0e6;
  // MoorDyn's contact is linear from the first touch; moorsim ramps its stiffness up over
  // contact_smoothing (0.5 m by default), which would let a line on a soft seabed sink
  // deeper than in MoorDyn. A tenth of the shallowest resting penetration of the sinking
  // line types, w / (kBot d), keeps them at MoorDyn's depth within a twentieth of it
  // (between 1 cm, below which landing nodes cost the integrator steps, and 0.5 m).
  std::optional<double> penetration;
  for (const MdLineType& t : types) {
    const double w =
        (t.mass - (rho ? rho->first : 1025.0) * std::numbers::pi * t.diameter * t.diameter / 4.0) *
        (gravity ? gravity->first : 9.81);
    if (w > 0.0 && t.diameter > 0.0 && seabed_stiffness > 0.0) {
      const double p = w / (seabed_stiffness * t.diameter);
      penetration = penetration ? std::min(*penetration, p) : p;
    }
  }
  y << "  seabed: {" << from(kbot ? kbot->second : 0, "option kBot")
    << "stiffness: " << FormatNumber(seabed_stiffness) << ", "
    << from(cbot ? cbot->second : 0, "option cBot")
    << "damping: " << FormatNumber(cbot ? cbot->first : 3.0e5);
  if (penetration) {
    y << ", contact_smoothing: "
      << FormatNumber(std::clamp(std::round(1e3 * 0.1 * *penetration) / 1e3, 0.01, 0.5));
  }
  if (!seabed_file.empty()) {
    y << ", " << from(seafloor->second, "option SeafloorFile " + seafloor->first)
      << "grid: " << Text(seabed_file);
  }
  y << "}  # kBot and cBot" << (kbot || cbot ? "" : " (MoorDyn's defaults)")
    << ", per unit of contact area";
  if (penetration) {
    y << "; contact_smoothing a tenth of the shallowest line's resting penetration ("
      << FormatNumber(std::round(1e4 * *penetration) / 1e4)
      << " m), as MoorDyn's contact is linear from the first touch";
  }
  if (seafloor) y << "; SeafloorFile (line " << seafloor->second << ") as a depth grid";
  y << "\n";
  const auto friction = option("frictioncoefficient");
  y << from(section_line[Kind::kLineTypes], "LINE TYPES") << "  line_types:\n";
  for (const MdLineType& t : types) {
    const std::string of = "line type " + t.name + ", ";
    y << from(t.line, "line type " + t.name) << "    - name: " << Text(t.name)
      << "  # LINE TYPES, line " << t.line << "\n";
    y << from(t.line, of + "Diam") << "      diameter: " << FormatNumber(t.diameter) << "\n";
    y << from(t.line, of + "Mass/m") << "      mass_per_length: " << FormatNumber(t.mass) << "\n";
    y << from(t.line, of + "EA");
    if (t.ea_curve.empty()) {
      y << "      axial_stiffness: " << FormatNumber(t.ea) << "\n";
    } else {
      y << "      tension_strain:  # EA table " << strict_yaml::OneLine(t.ea_table)
        << " (MoorDyn joins its points by straight lines, moorsim by a monotone cubic)\n";
      for (const auto& [strain, tension] : t.ea_curve) {
        y << "        - {strain: " << FormatNumber(strain) << ", tension: " << FormatNumber(tension)
          << "}\n";
      }
    }
    if (t.dynamic_ea > 0.0) {
      // MoorDyn's static spring, in series with EA_D: EA_D EA_s / (EA_D - EA_s).
      const double creep_spring = t.dynamic_ea * t.ea / (t.dynamic_ea - t.ea);
      if (t.dynamic_ea_slope > 0.0) {
        y << "      dynamic_axial_stiffness: " << FormatNumber(t.dynamic_ea)
          << "  # EA_s|EA_Dc|EA_D_Lm " << FormatNumber(t.ea) << "|" << FormatNumber(t.dynamic_ea)
          << "|" << FormatNumber(t.dynamic_ea_slope) << "\n";
        y << "      dynamic_axial_stiffness_slope: " << FormatNumber(t.dynamic_ea_slope)
          << "  # EA_D_Lm: EA_D = EA_Dc + EA_D_Lm x the mean load\n";
      } else {
        y << "      dynamic_axial_stiffness: " << FormatNumber(t.dynamic_ea) << "  # EA_s|EA_D "
          << FormatNumber(t.ea) << "|" << FormatNumber(t.dynamic_ea) << "\n";
      }
      y << from(t.line, of + "BA")
        << "      creep_time: " << FormatNumber(t.static_damping / creep_spring)
        << "  # BA_s / (EA_D EA_s / (EA_D - EA_s)): the static damping "
        << FormatNumber(t.static_damping) << " N s over the static spring "
        << FormatNumber(creep_spring) << " N\n";
      y << "      axial_damping: " << FormatNumber(t.ba) << "  # BA_D [N s]\n";
    } else if (t.ba < 0.0) {
      y << from(t.line, of + "BA/-zeta") << "      axial_damping_ratio: " << FormatNumber(-t.ba)
        << "  # BA/-zeta " << FormatNumber(t.ba) << "\n";
    } else {
      y << from(t.line, of + "BA") << "      axial_damping: " << FormatNumber(t.ba)
        << "  # BA [N s]\n";
    }
    y << from(t.line, of + "Cd") << "      drag_normal: " << FormatNumber(t.cd) << "\n";
    y << from(t.line, of + "CdAx")
      << "      drag_tangential: " << FormatNumber(t.cdax * std::numbers::pi) << "  # CdAx "
      << FormatNumber(t.cdax) << " x pi (MoorDyn applies it to pi d, moorsim to d)\n";
    y << from(t.line, of + "Ca") << "      added_mass_normal: " << FormatNumber(t.ca) << "\n";
    if (t.caax != 0.0) {
      y << from(t.line, of + "CaAx") << "      added_mass_tangential: " << FormatNumber(t.caax)
        << "  # CaAx\n";
    }
    if (friction) {
      y << from(friction->second, "option FrictionCoefficient")
        << "      friction_axial: " << FormatNumber(friction->first)
        << "  # FrictionCoefficient (line " << friction->second << ")\n";
      y << "      friction_lateral: " << FormatNumber(friction->first) << "\n";
    }
  }
  bool any_point = false;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point& p = points[k];
    if (p.kind != PointKind::kFree || !junction[k]) continue;
    if (!any_point) y << from(section_line[Kind::kPoints], "POINTS") << "  points:\n";
    any_point = true;
    const std::string of = "point " + p.id + ", ";
    y << "    - {" << from(p.line, "point " + p.id) << "name: " << PointName(p) << ", "
      << from(p.line, of + "X Y Z") << "position: " << Vector(p.x, p.y, p.z) << ", "
      << from(p.line, of + "Mass") << "mass: " << FormatNumber(p.mass) << ", "
      << from(p.line, of + "Volume") << "volume: " << FormatNumber(p.volume) << ", "
      << from(p.line, of + "Ca") << "added_mass: " << FormatNumber(p.ca) << ", "
      << from(p.line, of + "CdA") << "drag_area: " << FormatNumber(p.cda) << "}  # point " << p.id
      << " (line " << p.line << ")\n";
  }
  y << from(section_line[Kind::kLines], "LINES") << "  lines:\n";
  int id = 0;
  for (const Chain& chain : chains) {
    const Point& anchor = points[chain.lower];
    const Point& fairlead = points[chain.upper];
    const MdLine& first = lines[chain.lines.front()];
    std::string which = "line" + std::string(chain.lines.size() > 1 ? "s " : " ");
    for (std::size_t k = 0; k < chain.lines.size(); ++k) {
      which += (k ? ", " : "") + lines[chain.lines[k]].id;
    }
    which += " (point " + anchor.id + " to " + fairlead.id + ")";
    y << from(first.line, which) << "    - id: " << ++id << "  # MoorDyn line";
    y << (chain.lines.size() > 1 ? "s " : " ");
    for (std::size_t k = 0; k < chain.lines.size(); ++k) {
      y << (k ? ", " : "") << lines[chain.lines[k]].id;
    }
    y << ": point " << anchor.id;
    for (const std::size_t j : chain.joints) y << " -> " << points[j].id;
    y << " -> " << fairlead.id << "\n";
    if (anchor.kind == PointKind::kFixed) {
      y << from(anchor.line, "point " + anchor.id + ", X Y Z")
        << "      anchor: " << Vector(anchor.x, anchor.y, anchor.z);
    } else {
      y << from(anchor.line, "point " + anchor.id) << "      from: " << PointName(anchor);
    }
    y << "  # point " << anchor.id << " (line " << anchor.line << ")\n";
    // A fixed point above a flat seabed holds the line's end in the water (a jumper).
    if (anchor.kind == PointKind::kFixed && !seafloor && -anchor.z < depth->first - 1.0) {
      y << from(anchor.line, "point " + anchor.id + ", Z") << "      anchor_in_water: true  # "
        << FormatNumber(depth->first + anchor.z) << " m above the seabed\n";
    }
    if (fairlead.kind == PointKind::kVessel) {
      y << from(fairlead.line, "point " + fairlead.id + ", X Y Z")
        << "      fairlead: " << Vector(fairlead.x, fairlead.y, fairlead.z);
    } else {
      y << from(fairlead.line, "point " + fairlead.id) << "      to: " << PointName(fairlead);
    }
    y << "  # point " << fairlead.id << " (line " << fairlead.line << ")\n";
    // A chain written from the fairlead down is reversed: sections go from the anchor up.
    const MdLine& only = lines[chain.lines.front()];
    if (chain.lines.size() == 1 && only.segments >= 2) {
      const std::string of = "line " + only.id + ", ";
      y << from(only.line, of + "LineType") << "      type: " << Text(only.type) << "\n";
      y << from(only.line, of + "UnstrLen") << "      length: " << FormatNumber(only.length)
        << "\n";
      y << from(only.line, of + "NumSegs") << "      segments: " << only.segments << "\n";
      continue;
    }
    y << from(first.line, which) << "      sections:\n";
    for (const std::size_t k : chain.lines) {
      const std::string of = "line " + lines[k].id + ", ";
      y << "        - {" << from(lines[k].line, of + "LineType") << "type: " << Text(lines[k].type)
        << ", " << from(lines[k].line, of + "UnstrLen")
        << "length: " << FormatNumber(lines[k].length) << ", "
        << from(lines[k].line, of + "NumSegs") << "segments: " << lines[k].segments
        << "}  # MoorDyn line " << lines[k].id << "\n";
    }
    bool any_body = false;
    for (std::size_t k = 0; k < chain.joints.size(); ++k) {
      const Point& p = points[chain.joints[k]];
      if (p.mass == 0.0 && p.volume == 0.0 && p.cda == 0.0) continue;
      if (!any_body) y << from(first.line, which) << "      bodies:\n";
      any_body = true;
      const std::string of = "point " + p.id + ", ";
      y << "        - {" << from(p.line, "point " + p.id) << "joint: " << k + 1 << ", "
        << from(p.line, of + "Mass") << "mass: " << FormatNumber(p.mass) << ", "
        << from(p.line, of + "Volume") << "volume: " << FormatNumber(p.volume) << ", "
        << from(p.line, of + "Ca") << "added_mass: " << FormatNumber(p.ca) << ", "
        << from(p.line, of + "CdA") << "drag_area: " << FormatNumber(p.cda) << "}  # point " << p.id
        << " (line " << p.line << ")\n";
    }
  }
  if (!trains.empty() || current) {
    y << "environment:\n";
    if (!trains.empty()) {
      const int mode = static_cast<int>(wavekin->first);
      y << from(wavekin->second, "option WaveKin") << "  waves:  # WaveKin " << mode << " (line "
        << wavekin->second << "): "
        << (mode == 7   ? "wave_frequencies.txt's components, summed as they are"
            : mode == 2 ? "wave_frequencies.txt's components on MoorDyn's even grid"
                        : "wave_elevation.txt's Fourier components up to 0.5 Hz")
        << "; moorsim evaluates them at the nodes (MoorDyn "
        << (mode == 7 ? "too" : "interpolates them from its grid, water_grid.txt") << ")\n";
      y << "    on_lines: true\n    stretching: wheeler\n    trains:\n";
      for (const vessel::WaveComponent& c : trains) {
        y << "      - {period: " << FormatNumber(2.0 * std::numbers::pi / c.omega)
          << ", amplitude: " << FormatNumber(c.amplitude)
          << ", phase_deg: " << FormatNumber(Degrees(c.phase))
          << ", direction_toward_deg: " << FormatNumber(Degrees(c.direction)) << "}\n";
      }
    }
    if (profile) {
      y << from(currents->second, "option Currents") << "  current:  # Currents " << currents->first
        << " (line " << currents->second << "): " << current->file
        << ", one direction at every depth\n";
      y << "    direction_deg: " << FormatNumber(Degrees(profile->first)) << "\n";
      y << "    profile:\n";
      for (const auto& [d, v] : profile->second) {
        y << "      - {depth: " << FormatNumber(d) << ", speed: " << FormatNumber(v) << "}\n";
      }
    } else if (current) {
      y << from(currents->second, "option Currents") << "  current: {file: " << Text(current_file);
      if (current->period > 0.0) y << ", period: " << FormatNumber(current->period);
      y << "}  # Currents " << currents->first << " (line " << currents->second
        << "): " << current->file
        << (current->period > 0.0 ? ", repeated as MoorDyn repeats it" : "") << "\n";
    }
  }
  out.yaml = y.str();
  out.lines = id;
  // The loader checks the scenario; the files it names sit beside it in a scratch folder.
  std::string folder;
  if (!out.files.empty()) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "moorsim-import-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw Error("import: cannot make a scratch folder in " +
                  std::filesystem::temp_directory_path().string());
    }
    folder = pattern;
    for (const auto& [name, contents] : out.files) {
      std::ofstream(std::filesystem::path(folder) / name) << contents;
    }
  }
  std::string refused;
  const std::string scenario_name =
      (folder.empty() ? std::filesystem::path(stem) : std::filesystem::path(folder) / stem)
          .string() +
      ".yaml";
  try {
    ParseScenario(out.yaml, scenario_name);
  } catch (const InputError& e) {
    refused = e.what();
  }
  if (!folder.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
  if (refused.empty()) return out;
  // Said of the MoorDyn file: the scenario's lines are not the user's.
  std::string message = from.Relocate(refused, scenario_name, path, out.yaml);
  for (std::size_t at; !folder.empty() && (at = message.find(folder + "/")) != std::string::npos;) {
    message.erase(at, folder.size() + 1);
  }
  throw InputError(message);
}

}  // namespace moorsim::scenarios
