#include "simulation/output_layout.h"

#include <array>
#include <vector>

#include "core/error.h"

namespace moorsim::simulation::layout {
namespace {

constexpr std::array kTables = {kTime,
                                kPoseTrue,
                                kPoseLowFrequency,
                                kVelocityTrue,
                                kPoseMeasured,
                                kTurret,
                                kFairleadTension,
                                kTensionMeasured,
                                kAnchors,
                                kThrustCommanded,
                                kThrustDelivered,
                                kLoadMooring,
                                kLoadWavesDrift,
                                kLoadCurrent,
                                kLoadWind,
                                kLoadThrust,
                                kInputTime,
                                kInputPose,
                                kInputThrust,
                                kInputTension,
                                kObserverBias,
                                kObserverWaveMotion,
                                kDetectorScore,
                                kDetectorDecision,
                                kDetectorAlarm};

std::vector<std::string> Split(std::string_view text) {
  std::vector<std::string> items;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    items.emplace_back(text.substr(0, comma));
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
  }
  return items;
}

}  // namespace

std::span<const Table> Tables() { return kTables; }

int Columns(const Table& table, int lines, int hypotheses) {
  switch (table.width) {
    case kPerLine:
      return lines;
    case kPerHypothesis:
      return hypotheses;
    default:
      return table.width;
  }
}

output::TableId Create(output::Hdf5File& file, const Table& table, int lines, int hypotheses,
                       const std::string& group, output::TableType type) {
  std::vector<std::string> names = Split(table.columns);
  if (table.width == kPerLine) {
    for (int i = 1; i <= lines; ++i) names.push_back("line " + std::to_string(i));
  }
  const std::string path =
      group.empty() ? std::string(table.path) : group + "/" + std::string(table.path);
  return file.CreateTable(path, Columns(table, lines, hypotheses), std::string(table.units), names,
                          type);
}

output::TableData Read(const output::Hdf5Reader& file, const std::string& file_name,
                       const Table& table, int lines) {
  const std::string path(table.path);
  output::TableData data = file.ReadTable(path);
  const int expected = Columns(table, lines);
  // A series reads as one column.
  const std::size_t columns = expected == kSeries ? 1 : static_cast<std::size_t>(expected);
  if (data.columns != columns) {
    const std::string found = file_name + ": " + path + ": " + std::to_string(data.columns);
    // The tables per line hold tensions.
    throw InputError(table.width == kPerLine
                         ? found + " columns, the scenario has " + std::to_string(lines) +
                               " mooring lines (one tension per line)"
                         : found + " columns, expected " + std::to_string(columns));
  }
  return data;
}

}  // namespace moorsim::simulation::layout
