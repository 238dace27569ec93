#include "vessel/hydro_data.h"

#include <algorithm>
#include <array>
#include <bitset>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"

namespace moorsim::vessel {
namespace {

// WAMIT writes every period and heading with the same format in all files of a run, so
// equal values compare equal; the tolerances only forgive a file re-written with fewer
// digits. Tabulated periods and headings are at least percents apart.
constexpr double kPeriodTolerance = 1e-6;   // relative
constexpr double kHeadingTolerance = 1e-6;  // degrees

// Added mass or damping coupling a mode symmetric about y = 0 with an antisymmetric one, as
// a fraction of sqrt(|M_ii M_jj|), above which the hull is taken to be asymmetric. WAMIT
// writes no such entries for a symmetric body (it solves the two symmetry classes apart).
constexpr double kSymmetryTolerance = 1e-6;

bool IsRotation(int mode) { return mode >= 3; }           // 0-based: 3, 4, 5 are roll, pitch, yaw
bool IsAntisymmetric(int mode) { return mode % 2 == 1; }  // 0-based sway, roll, yaw

/// A whole text file, handed out one non-blank line at a time as whitespace-separated
/// fields. Knows its path and the current line for messages. The fields view the text, so
/// an object is moved only before its first NextRow() and never copied.
class WamitText {
 public:
  WamitText(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}
  WamitText(WamitText&&) = default;
  WamitText(const WamitText&) = delete;
  WamitText& operator=(const WamitText&) = delete;

  const std::string& path() const { return path_; }
  int line_number() const { return line_number_; }
  std::size_t size() const { return field_count_; }

  /// Advances to the next line with any fields; false at the end of the file.
  bool NextRow() {
    while (position_ < text_.size()) {
      const std::size_t end = std::min(text_.find('\n', position_), text_.size());
      line_ = std::string_view(text_).substr(position_, end - position_);
      position_ = end + 1;
      ++line_number_;
      Split();
      if (field_count_ > 0) return true;
    }
    return false;
  }

  double Number(std::size_t field, const char* name) const {
    std::string_view text = fields_[field];
    if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);  // from_chars takes no '+'
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      Fail(std::string(name) + " = '" + std::string(fields_[field]) + "' is not a finite number");
    }
    return value;
  }

  int Integer(std::size_t field, const char* name) const {
    const std::string_view text = fields_[field];
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
      Fail(std::string(name) + " = '" + std::string(text) + "' is not an integer");
    }
    return value;
  }

  /// Throws "path:line: what: 'the line'".
  [[noreturn]] void Fail(const std::string& what) const {
    std::string_view shown = line_;
    while (!shown.empty() && (shown.back() == '\r' || shown.back() == ' ')) shown.remove_suffix(1);
    throw InputError(path_ + ":" + std::to_string(line_number_) + ": " + what + ": '" +
                     std::string(shown) + "'");
  }

  void RequireFields(std::size_t low, std::size_t high, const char* layout) const {
    if (field_count_ < low || field_count_ > high) {
      std::string count = std::to_string(low);
      if (high != low) {
        count += '-';
        count += std::to_string(high);
      }
      Fail("expected " + count + " numbers (" + layout + "), found " +
           std::to_string(field_count_));
    }
  }

 private:
  static constexpr std::size_t kMaxFields = 9;  // one more than the widest row (.9: 8)

  void Split() {
    field_count_ = 0;
    std::size_t i = 0;
    while (i < line_.size()) {
      while (i < line_.size() && std::isspace(static_cast<unsigned char>(line_[i]))) ++i;
      if (i == line_.size()) break;
      std::size_t j = i;
      while (j < line_.size() && !std::isspace(static_cast<unsigned char>(line_[j]))) ++j;
      if (field_count_ < kMaxFields) fields_[field_count_] = line_.substr(i, j - i);
      ++field_count_;  // keeps counting past kMaxFields so RequireFields reports the truth
      i = j;
    }
  }

  std::string path_;
  std::string text_;
  std::size_t position_ = 0;
  int line_number_ = 0;
  std::string_view line_;
  std::array<std::string_view, kMaxFields> fields_;
  std::size_t field_count_ = 0;
};

/// The file's text, or nullopt if an optional file does not exist.
std::optional<WamitText> ReadFile(const std::string& path, bool required, const char* role) {
  std::error_code error;
  const bool exists = std::filesystem::exists(path, error);
  if (!exists) {
    if (!required) return std::nullopt;
    throw InputError(path + ": cannot open the WAMIT " + role + " file (required)");
  }
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a directory, not the WAMIT " + role + " file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the WAMIT " + role + " file");
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  if (size < 0) throw InputError(path + ": cannot read the WAMIT " + role + " file");
  std::string text(static_cast<std::size_t>(size), '\0');
  file.seekg(0, std::ios::beg);
  file.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!file) throw InputError(path + ": cannot read the WAMIT " + role + " file");
  return WamitText(path, std::move(text));
}

int ReadMode(const WamitText& text, std::size_t field, const char* name) {
  const int mode = text.Integer(field, name);
  if (mode < 1 || mode > 6) {
    text.Fail(std::string(name) + " = " + std::to_string(mode) + " must be 1..6");
  }
  return mode - 1;
}

std::string PeriodText(double period) { return "period " + FormatNumber(period) + " s"; }

// ---------------------------------------------------------------------------------------
// .1: added mass and damping

struct RadiationBlock {
  double period = 0.0;
  Mat6 added_mass = Mat6::Zero();  // non-dimensional, WAMIT frame
  Mat6 damping = Mat6::Zero();
  std::bitset<36> seen;
  Eigen::Matrix<int, 6, 6> line = Eigen::Matrix<int, 6, 6>::Zero();
};

std::vector<RadiationBlock> ReadRadiationRows(WamitText& text) {
  std::vector<RadiationBlock> blocks;
  while (text.NextRow()) {
    text.RequireFields(4, 5, "PER I J A [B]");
    const double period = text.Number(0, "PER");
    if (period < 0.0 && period != -1.0) {
      text.Fail("PER = " + FormatNumber(period) +
                " must be -1 (zero frequency), 0 (infinite frequency) or a period > 0 s");
    }
    const int i = ReadMode(text, 1, "I");
    const int j = ReadMode(text, 2, "J");
    const double a = text.Number(3, "A");
    double b = 0.0;  // WAMIT writes no damping at the limits, where it vanishes
    if (period > 0.0) {
      text.RequireFields(5, 5, "PER I J A B");
      b = text.Number(4, "B");
    }
    auto block = std::find_if(blocks.rbegin(), blocks.rend(), [&](const RadiationBlock& x) {
      return x.period == period;  // within one file WAMIT prints a period identically
    });
    if (block == blocks.rend()) {
      blocks.emplace_back();
      blocks.back().period = period;
      block = blocks.rbegin();
    }
    const std::size_t bit = static_cast<std::size_t>(6 * i + j);
    if (block->seen[bit]) {
      text.Fail("second entry for PER = " + FormatNumber(period) +
                ", I = " + std::to_string(i + 1) + ", J = " + std::to_string(j + 1));
    }
    block->seen[bit] = true;
    block->added_mass(i, j) = a;
    block->damping(i, j) = b;
    block->line(i, j) = text.line_number();
  }
  return blocks;
}

/// Refuses added mass or damping that couples the two symmetry classes of a hull symmetric
/// about y = 0: the heading mirror would then be wrong.
void CheckPortStarboardSymmetry(const std::string& path, const std::vector<RadiationBlock>& all) {
  for (const RadiationBlock& block : all) {
    for (const auto& [matrix, name] :
         {std::pair{&block.added_mass, "A"}, std::pair{&block.damping, "B"}}) {
      for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
          if (IsAntisymmetric(i) == IsAntisymmetric(j)) continue;
          const double scale = std::sqrt(std::abs((*matrix)(i, i) * (*matrix)(j, j)));
          if (std::abs((*matrix)(i, j)) > kSymmetryTolerance * scale) {
            throw InputError(path + ":" + std::to_string(block.line(i, j)) + ": " + name + "(" +
                             std::to_string(i + 1) + "," + std::to_string(j + 1) +
                             ") = " + FormatNumber((*matrix)(i, j)) +
                             " couples modes of opposite symmetry about y = 0, so the hull is "
                             "not port/starboard symmetric; moorsim mirrors WAMIT's 0..180 deg "
                             "headings and needs a symmetric hull");
          }
        }
      }
    }
  }
}

/// Fills the radiation part of `data`; returns the finite periods in the order of the
/// stored frequencies (descending period = ascending ω) for the wave files to match.
std::vector<double> ReadRadiation(const std::string& stem, const WamitOptions& options,
                                  HydroData& data, std::vector<RadiationBlock>& blocks) {
  std::optional<WamitText> text = ReadFile(stem + ".1", true, "added-mass and damping (.1)");
  blocks = ReadRadiationRows(*text);
  const std::string& path = text->path();

  std::bitset<36> all_pairs;
  for (const RadiationBlock& block : blocks) all_pairs |= block.seen;
  for (const RadiationBlock& block : blocks) {
    if (block.seen == all_pairs) continue;
    for (std::size_t bit = 0; bit < 36; ++bit) {
      if (all_pairs[bit] && !block.seen[bit]) {
        throw InputError(path + ": " + PeriodText(block.period) + " has no entry for I = " +
                         std::to_string(bit / 6 + 1) + ", J = " + std::to_string(bit % 6 + 1) +
                         ", which other periods have (truncated file?)");
      }
    }
  }

  const auto find_limit = [&](double period, const char* what) -> const RadiationBlock& {
    const auto it = std::find_if(blocks.begin(), blocks.end(),
                                 [&](const RadiationBlock& b) { return b.period == period; });
    if (it == blocks.end()) {
      throw InputError(path + ": no rows with PER = " + FormatNumber(period) + " (" + what +
                       "); run WAMIT with the periods -1 and 0 in the list");
    }
    return *it;
  };

  // A_ij = ρ L^k Ā_ij, B_ij = ρ L^k ω B̄_ij, k = 3 + [i rotation] + [j rotation] (WAMIT
  // manual, "Added-mass and damping coefficients"); then T M T into the project frame.
  const double rho = options.water_density;
  const double length = options.length_scale;
  const auto to_project = [&](const Mat6& m, double factor) {
    Mat6 out;
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        const int k = 3 + IsRotation(i) + IsRotation(j);
        out(i, j) =
            kWamitToProject[i] * kWamitToProject[j] * factor * rho * std::pow(length, k) * m(i, j);
      }
    }
    return out;
  };
  data.added_mass_zero_frequency =
      to_project(find_limit(-1.0, "zero-frequency added mass").added_mass, 1.0);
  data.added_mass_infinite_frequency =
      to_project(find_limit(0.0, "infinite-frequency added mass").added_mass, 1.0);

  std::vector<const RadiationBlock*> finite;
  for (const RadiationBlock& block : blocks) {
    if (block.period > 0.0) finite.push_back(&block);
  }
  if (finite.empty()) throw InputError(path + ": no rows with a finite period");
  std::sort(finite.begin(), finite.end(), [](const RadiationBlock* a, const RadiationBlock* b) {
    return a->period > b->period;  // descending period = ascending frequency
  });
  std::vector<double> periods;
  for (const RadiationBlock* block : finite) {
    const double omega = 2.0 * kPi / block->period;
    periods.push_back(block->period);
    data.frequencies.push_back(omega);
    data.added_mass.push_back(to_project(block->added_mass, 1.0));
    data.damping.push_back(to_project(block->damping, omega));
  }
  return periods;
}

// ---------------------------------------------------------------------------------------
// .hst: hydrostatic restoring

Mat6 ReadRestoring(const std::string& stem, const WamitOptions& options) {
  std::optional<WamitText> text = ReadFile(stem + ".hst", true, "hydrostatics (.hst)");
  Mat6 c = Mat6::Zero();
  std::bitset<36> seen;
  while (text->NextRow()) {
    text->RequireFields(3, 3, "I J C");
    const int i = ReadMode(*text, 0, "I");
    const int j = ReadMode(*text, 1, "J");
    const double value = text->Number(2, "C");
    const std::size_t bit = static_cast<std::size_t>(6 * i + j);
    if (seen[bit]) {
      text->Fail("second entry for I = " + std::to_string(i + 1) +
                 ", J = " + std::to_string(j + 1));
    }
    seen[bit] = true;
    // C_ij = ρ g L^k C̄_ij with k = 2 (3,3), 3 (3,4), (3,5), 4 (4,4), (4,5), (5,5), ...:
    // k = 2 + [i rotation] + [j rotation]. WAMIT defines no restoring in surge and sway.
    const int k = 2 + IsRotation(i) + IsRotation(j);
    c(i, j) = kWamitToProject[i] * kWamitToProject[j] * options.water_density * options.gravity *
              std::pow(options.length_scale, k) * value;
  }
  if (seen.none()) throw InputError(text->path() + ": no rows (expected 'I J C')");
  return c;
}

// ---------------------------------------------------------------------------------------
// .3, .4, .9: tables over (period, heading, mode)

enum class WaveKind { kExciting, kRao, kDrift };

struct WaveTable {
  std::string path;
  std::vector<double> headings_wamit;  // degrees, in the order first seen
  // cells[heading][frequency]: value (dimensional, project frame) and the modes seen.
  std::vector<std::vector<ComplexVec6>> values;
  std::vector<std::vector<std::uint8_t>> seen;
};

std::size_t FindPeriod(const WamitText& text, const std::vector<double>& periods, double period) {
  // `periods` is descending.
  const auto it = std::lower_bound(periods.begin(), periods.end(), period,
                                   [](double a, double b) { return a > b; });
  for (auto candidate : {it, it == periods.begin() ? it : it - 1}) {
    if (candidate != periods.end() && std::abs(*candidate - period) <= kPeriodTolerance * period) {
      return static_cast<std::size_t>(candidate - periods.begin());
    }
  }
  text.Fail(PeriodText(period) + " is not one of the finite periods of the .1 file");
}

std::optional<WaveTable> ReadWaveTable(const std::string& path, WaveKind kind,
                                       const std::vector<double>& periods,
                                       const WamitOptions& options) {
  const char* role = kind == WaveKind::kExciting ? "exciting-force (.3)"
                     : kind == WaveKind::kRao    ? "motion RAO (.4)"
                                                 : "mean drift (.9)";
  std::optional<WamitText> text = ReadFile(path, false, role);
  if (!text) return std::nullopt;

  WaveTable table;
  table.path = path;
  const bool drift = kind == WaveKind::kDrift;
  const std::size_t mode_field = drift ? 3 : 2;
  const double rho_g = options.water_density * options.gravity;
  const double length = options.length_scale;
  while (text->NextRow()) {
    if (drift) {
      text->RequireFields(8, 8, "PER BETA1 BETA2 I |F| phase Re Im");
    } else {
      text->RequireFields(7, 7, "PER BETA I |X| phase Re Im");
    }
    const double period = text->Number(0, "PER");
    if (period == -1.0 || period == 0.0) continue;  // the limits carry no wave data we use
    if (period < 0.0) text->Fail("PER = " + FormatNumber(period) + " must be -1, 0 or > 0 s");
    const double beta = text->Number(1, "BETA");
    if (drift && std::abs(text->Number(2, "BETA2") - beta) > kHeadingTolerance) {
      continue;  // bidirectional drift (β1 ≠ β2) is for QTFs; we take the mean drift only
    }
    const int signed_mode = text->Integer(mode_field, "I");
    if (drift && signed_mode >= -6 && signed_mode <= -4) {
      continue;  // moments in the displaced body's axes; modes 4..6 are about fixed axes
    }
    if (drift && (signed_mode < 1 || signed_mode > 6)) {
      text->Fail("I = " + std::to_string(signed_mode) +
                 " must be 1..6 (or -4..-6, moments in the body's axes)");
    }
    const int mode = ReadMode(*text, mode_field, "I");
    const double re = text->Number(mode_field + 3, "Re");
    const double im = text->Number(mode_field + 4, "Im");
    text->Number(mode_field + 1, "modulus");  // checked for form only
    text->Number(mode_field + 2, "phase");

    const std::size_t f = FindPeriod(*text, periods, period);
    if (beta < -kHeadingTolerance || beta > 180.0 + kHeadingTolerance) {
      text->Fail("heading " + FormatNumber(beta) +
                 " deg is outside 0..180 deg; moorsim takes the other half from the hull's "
                 "port/starboard symmetry");
    }
    std::size_t h = 0;
    while (h < table.headings_wamit.size() &&
           std::abs(table.headings_wamit[h] - beta) > kHeadingTolerance) {
      ++h;
    }
    if (h == table.headings_wamit.size()) {
      table.headings_wamit.push_back(beta);
      table.values.emplace_back(periods.size(), ComplexVec6::Zero());
      table.seen.emplace_back(periods.size(), std::uint8_t{0});
    }
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << mode);
    if (table.seen[h][f] & bit) {
      text->Fail("second entry for PER = " + FormatNumber(period) + ", heading " +
                 FormatNumber(beta) + " deg, I = " + std::to_string(mode + 1));
    }
    table.seen[h][f] |= bit;

    // Dimensional values (WAMIT manual, chapter 4): X = ρ g A L^m X̄ with m = 2 (forces),
    // 3 (moments); ξ = A ξ̄ / L^n with n = 0, 1; F̄ drift = ρ g A² L^m F̄ with m = 1, 2.
    double scale = 1.0;
    switch (kind) {
      case WaveKind::kExciting:
        scale = rho_g * std::pow(length, 2 + IsRotation(mode));
        break;
      case WaveKind::kRao:
        scale = std::pow(length, -static_cast<int>(IsRotation(mode)));
        break;
      case WaveKind::kDrift:
        scale = rho_g * std::pow(length, 1 + IsRotation(mode));
        break;
    }
    scale *= kWamitToProject[mode];
    table.values[h][f][mode] = drift ? std::complex<double>(scale * re, 0.0)
                                     : std::complex<double>(scale * re, scale * im);
  }

  if (table.headings_wamit.empty()) throw InputError(path + ": no rows with a finite period");
  std::uint8_t all_modes = 0;
  for (const auto& row : table.seen) {
    for (std::uint8_t modes : row) all_modes |= modes;
  }
  for (std::size_t h = 0; h < table.seen.size(); ++h) {
    for (std::size_t f = 0; f < periods.size(); ++f) {
      const std::uint8_t missing = all_modes & static_cast<std::uint8_t>(~table.seen[h][f]);
      if (missing == 0) continue;
      int mode = 0;
      while (!(missing & (1u << mode))) ++mode;
      throw InputError(path + ": no entry for " + PeriodText(periods[f]) + ", heading " +
                       FormatNumber(table.headings_wamit[h]) + " deg, I = " +
                       std::to_string(mode + 1) + ", which other rows have (truncated file?)");
    }
  }
  return table;
}

/// Stores `table` in the project's heading order. The first table read sets the headings;
/// the others must have the same ones.
template <typename Value>
std::vector<Value> ToHeadingGrid(const WaveTable& table, HydroData& data,
                                 std::string& heading_source) {
  std::vector<double> wamit = table.headings_wamit;
  std::sort(wamit.begin(), wamit.end(), std::greater<>());  // 180..0 deg = project −π..0
  std::vector<double> project;
  for (double beta : wamit) project.push_back(ProjectHeadingFromWamit(beta * kDegree));

  const auto describe = [](const std::vector<double>& degrees) {
    std::string out;
    for (auto it = degrees.rbegin(); it != degrees.rend(); ++it) {
      out += (out.empty() ? "" : " ") + FormatNumber(*it);
    }
    return out + " deg";
  };
  if (heading_source.empty()) {
    if (std::abs(wamit.front() - 180.0) > kHeadingTolerance ||
        std::abs(wamit.back()) > kHeadingTolerance) {
      throw InputError(table.path + ": headings " + describe(wamit) +
                       " must include 0 and 180 deg for the port/starboard mirror to cover "
                       "every direction");
    }
    data.headings = project;
    heading_source = table.path;
  } else {
    bool same = project.size() == data.headings.size();
    for (std::size_t h = 0; same && h < project.size(); ++h) {
      same = std::abs(project[h] - data.headings[h]) <= kHeadingTolerance * kDegree;
    }
    if (!same) {
      std::vector<double> expected;
      for (double beta : data.headings) {
        expected.push_back(WamitHeadingFromProject(beta) / kDegree);
      }
      throw InputError(table.path + ": headings " + describe(wamit) + " differ from those of " +
                       heading_source + " (" + describe(expected) + ")");
    }
  }

  std::vector<Value> grid(data.frequencies.size() * data.headings.size());
  for (std::size_t h_file = 0; h_file < table.headings_wamit.size(); ++h_file) {
    const double beta = table.headings_wamit[h_file];
    const std::size_t h = static_cast<std::size_t>(
        std::find_if(wamit.begin(), wamit.end(),
                     [&](double b) { return std::abs(b - beta) <= kHeadingTolerance; }) -
        wamit.begin());
    for (std::size_t f = 0; f < data.frequencies.size(); ++f) {
      if constexpr (std::is_same_v<Value, Vec6>) {
        grid[data.WaveIndex(f, h)] = table.values[h_file][f].real();
      } else {
        grid[data.WaveIndex(f, h)] = table.values[h_file][f];
      }
    }
  }
  return grid;
}

void CheckOptions(const WamitOptions& options) {
  for (const auto& [value, name] :
       {std::pair{options.water_density, "water_density"}, std::pair{options.gravity, "gravity"},
        std::pair{options.length_scale, "length_scale"}}) {
    if (!std::isfinite(value) || value <= 0.0) {
      throw InputError(std::string("WamitOptions.") + name + " = " + FormatNumber(value) +
                       ": must be a finite number > 0");
    }
  }
}

// ---------------------------------------------------------------------------------------
// Interpolation

/// value = (1 − t) v[low] + t v[high]; clamped to the grid's ends.
struct Bracket {
  std::size_t low = 0;
  std::size_t high = 0;
  double t = 0.0;
};

Bracket BracketOf(const std::vector<double>& grid, double x) {
  if (x <= grid.front()) return {0, 0, 0.0};
  if (x >= grid.back()) return {grid.size() - 1, grid.size() - 1, 0.0};
  const std::size_t high =
      static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), x) - grid.begin());
  const std::size_t low = high - 1;
  return {low, high, (x - grid[low]) / (grid[high] - grid[low])};
}

/// β wrapped to [−π, π] and folded into the table's [−π, 0]; `mirrored` when the result is
/// the mirror image of the wave asked for. ±π (head seas) are the same tabulated heading.
struct FoldedHeading {
  double beta = 0.0;
  bool mirrored = false;
};

FoldedHeading FoldHeading(double beta) {
  const double wrapped = std::remainder(beta, 2.0 * kPi);
  if (wrapped >= kPi) return {-kPi, false};
  if (wrapped > 0.0) return {-wrapped, true};
  return {wrapped, false};
}

void CheckFinite(double omega, double beta, const char* function) {
  if (!std::isfinite(omega) || !std::isfinite(beta)) {
    throw Error(std::string("HydroData::") + function + "(omega = " + FormatNumber(omega) +
                ", beta = " + FormatNumber(beta) + "): arguments must be finite");
  }
}

void CheckFinite(double omega, const char* function) {
  if (!std::isfinite(omega)) {
    throw Error(std::string("HydroData::") + function + "(omega = " + FormatNumber(omega) +
                "): the frequency must be finite");
  }
}

template <typename Value>
Value InterpolateWave(const HydroData& data, const std::vector<Value>& table, double omega,
                      double beta, const char* function, const char* extension) {
  CheckFinite(omega, beta, function);
  if (table.empty()) {
    throw Error(std::string("HydroData::") + function + ": no table: '" + data.source + extension +
                "' was not read");
  }
  const Bracket f = BracketOf(data.frequencies, omega);
  const FoldedHeading folded = FoldHeading(beta);
  const Bracket h = BracketOf(data.headings, folded.beta);
  // Weights are exactly 1 and 0 on a tabulated point, so tabulated values come back exact.
  Value value = ((1.0 - f.t) * (1.0 - h.t)) * table[data.WaveIndex(f.low, h.low)] +
                ((1.0 - f.t) * h.t) * table[data.WaveIndex(f.low, h.high)] +
                (f.t * (1.0 - h.t)) * table[data.WaveIndex(f.high, h.low)] +
                (f.t * h.t) * table[data.WaveIndex(f.high, h.high)];
  if (folded.mirrored) {
    for (int i = 0; i < 6; ++i) value[i] *= kPortStarboardMirror[i];
  }
  return value;
}

Mat6 InterpolateMatrix(const HydroData& data, const std::vector<Mat6>& table, double omega,
                       const char* function) {
  CheckFinite(omega, function);
  const Bracket f = BracketOf(data.frequencies, omega);
  return (1.0 - f.t) * table[f.low] + f.t * table[f.high];
}

}  // namespace

Mat6 HydroData::AddedMass(double omega) const {
  return InterpolateMatrix(*this, added_mass, omega, "AddedMass");
}

Mat6 HydroData::Damping(double omega) const {
  return InterpolateMatrix(*this, damping, omega, "Damping");
}

ComplexVec6 HydroData::Exciting(double omega, double beta) const {
  return InterpolateWave(*this, exciting_force, omega, beta, "Exciting", ".3");
}

ComplexVec6 HydroData::Rao(double omega, double beta) const {
  return InterpolateWave(*this, motion_rao, omega, beta, "Rao", ".4");
}

Vec6 HydroData::Drift(double omega, double beta) const {
  return InterpolateWave(*this, mean_drift, omega, beta, "Drift", ".9");
}

HydroData ReadWamit(const std::string& stem, const WamitOptions& options) {
  CheckOptions(options);
  HydroData data;
  data.source = stem;
  data.water_density = options.water_density;
  data.gravity = options.gravity;

  std::vector<RadiationBlock> radiation;
  const std::vector<double> periods = ReadRadiation(stem, options, data, radiation);
  data.restoring = ReadRestoring(stem, options);

  std::string heading_source;
  if (auto table = ReadWaveTable(stem + ".3", WaveKind::kExciting, periods, options)) {
    data.exciting_force = ToHeadingGrid<ComplexVec6>(*table, data, heading_source);
  }
  if (auto table = ReadWaveTable(stem + ".4", WaveKind::kRao, periods, options)) {
    data.motion_rao = ToHeadingGrid<ComplexVec6>(*table, data, heading_source);
  }
  if (auto table = ReadWaveTable(stem + ".9", WaveKind::kDrift, periods, options)) {
    data.mean_drift = ToHeadingGrid<Vec6>(*table, data, heading_source);
  }
  // The mirror is only used for wave data; radiation data alone need no symmetry.
  if (!heading_source.empty()) CheckPortStarboardSymmetry(stem + ".1", radiation);
  return data;
}

}  // namespace moorsim::vessel
