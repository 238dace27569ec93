// Hand-made evidence for the detector tests.
#pragma once

#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors::testing {

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
