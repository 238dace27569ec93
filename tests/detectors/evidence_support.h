// Hand-made evidence for the detector tests.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors::testing {

/// The load tests' four lines: line k's horizontal load on the vessel, 4.5 MN pointing to
/// its anchor at (k - 1) x 90 deg.
inline Vec3 QuarterLineLoad(int line) {
  const double angle = (line - 1) * std::numbers::pi / 2;
  return Vec3(4.5e6 * std::cos(angle), 4.5e6 * std::sin(angle), 0.0);
}

/// Evidence at time t whose hypotheses carry only the given log-likelihoods.
inline Evidence WithLogLikelihoods(double t, const std::vector<double>& log_likelihood) {
  Evidence evidence;
  evidence.t = t;
  evidence.hypotheses.resize(log_likelihood.size());
  for (std::size_t k = 0; k < log_likelihood.size(); ++k) {
    evidence.hypotheses[k].log_likelihood = log_likelihood[k];
  }
  return evidence;
}

}  // namespace moorsim::detectors::testing
