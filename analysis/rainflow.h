// Rainflow counting of a load history (ASTM E1049-85, section 5.4.4): the history reduced
// to its turning points, then each range that closes a loop counted as a cycle and the
// ranges left over (the residue) as half cycles. Each cycle keeps its range (peak to
// valley) and its mean, which mean-load corrections of T-N curves need.
#pragma once

#include <span>
#include <vector>

namespace moorsim::analysis {

/// One counted range: `count` is 1 for a full cycle, 0.5 for a half cycle.
struct RainflowCycle {
  double range = 0.0;  ///< peak minus valley (same unit as the history)
  double mean = 0.0;   ///< (peak + valley) / 2
  double count = 1.0;
};

/// The turning points of `history`: its first and last values and every local extremum
/// between them (a plateau counts once; non-finite values are refused with
/// std::invalid_argument, since a gap in a record cannot be counted through).
std::vector<double> TurningPoints(std::span<const double> history);

/// The rainflow cycles of `history` (any series; its turning points are taken first), in
/// the order the standard's procedure counts them: full cycles as they close, then the
/// residue's half cycles from its start.
std::vector<RainflowCycle> Rainflow(std::span<const double> history);

}  // namespace moorsim::analysis
