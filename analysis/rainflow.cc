#include "analysis/rainflow.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace moorsim::analysis {

std::vector<double> TurningPoints(std::span<const double> history) {
  std::vector<double> points;
  for (std::size_t i = 0; i < history.size(); ++i) {
    const double x = history[i];
    if (!std::isfinite(x)) {
      throw std::invalid_argument("rainflow: value " + std::to_string(i) +
                                  " is not a finite number");
    }
    if (points.empty()) {
      points.push_back(x);
      continue;
    }
    if (x == points.back()) continue;  // a plateau: one point
    if (points.size() >= 2) {
      const double previous = points[points.size() - 2];
      const double last = points.back();
      // Still rising or still falling: the last point was not a turning point.
      if ((last > previous && x > last) || (last < previous && x < last)) {
        points.back() = x;
        continue;
      }
    }
    points.push_back(x);
  }
  return points;
}

std::vector<RainflowCycle> Rainflow(std::span<const double> history) {
  std::vector<RainflowCycle> cycles;
  // The standard's stack of points not yet counted; `start` is the index of its first
  // point, which a half cycle discards.
  std::vector<double> stack;
  const auto range = [](double a, double b) { return std::abs(a - b); };
  for (double point : TurningPoints(history)) {
    stack.push_back(point);
    while (stack.size() >= 3) {
      const std::size_t n = stack.size();
      const double x = range(stack[n - 1], stack[n - 2]);  // the newest range
      const double y = range(stack[n - 2], stack[n - 3]);  // the range before it
      if (x < y) break;
      const double mean = (stack[n - 2] + stack[n - 3]) / 2.0;
      if (n == 3) {
        // Y holds the stack's first point: a half cycle, and the first point goes.
        cycles.push_back({y, mean, 0.5});
        stack.erase(stack.begin());
      } else {
        // A closed loop: one cycle; both of Y's points go.
        cycles.push_back({y, mean, 1.0});
        stack.erase(stack.end() - 3, stack.end() - 1);
      }
    }
  }
  // The residue: each of its ranges a half cycle.
  for (std::size_t i = 1; i < stack.size(); ++i) {
    cycles.push_back({range(stack[i], stack[i - 1]), (stack[i] + stack[i - 1]) / 2.0, 0.5});
  }
  return cycles;
}

}  // namespace moorsim::analysis
