// The GLR's known failure signatures (Lajic et al. 2009, eq. 22), computed from the hypothesis
// models themselves: s_k is the mean whitened innovation of the INTACT observer over the first M
// samples after line k parts, with the vessel at rest at `pose` before the break.
//
// Construction, per failure hypothesis k: before the break the truth is the intact model at
// rest at `pose`, held there by a constant environmental force b0 = -(intact mooring load);
// the intact EKF watches noise-free measurements of it until its estimate has settled. At
// t = 0 line k parts: the truth follows hypothesis k's model under the same b0 (so it drifts
// away from line k's anchor), and the intact EKF keeps watching. Its innovations over the
// next M samples, whitened with its own S, averaged, are s_k. Noise-free data give the
// expected innovation directly (the filter is linear in the measurement noise to first order).
#pragma once

#include <vector>

#include "core/types.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"

namespace moorsim::detectors {

/// Signatures s_1 .. s_{N-1} for every failure hypothesis of `bank` (index k - 1), for a GLR
/// window of `window` samples at sample interval `dt` [s]. `pose` is (x, y, psi) before the
/// break. Costs about 2 ms per hypothesis.
std::vector<Vec3> GlrSignatures(const HypothesisBank& bank, const LowFrequencyModel& model,
                                const EkfOptions& options, const Vec3& pose, double dt, int window);

}  // namespace moorsim::detectors
