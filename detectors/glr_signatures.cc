#include "detectors/glr_signatures.h"

#include "core/error.h"
#include "detectors/glr.h"

namespace moorsim::detectors {

namespace {

// Samples the intact filter watches before the break: ~10 times its slowest settling time
// apart from the 1000 s bias, which starts at the right value anyway (b0 below).
constexpr int kSettleSamples = 300;

}  // namespace

std::vector<Vec3> GlrSignatures(const HypothesisBank& bank, const LowFrequencyModel& model,
                                const EkfOptions& options, const Vec3& pose, double dt,
                                int window) {
  if (!(dt > 0.0) || window < 1) {
    throw InputError("GLR signatures: need dt > 0 and a window >= 1 (dt " + std::to_string(dt) +
                     ", window " + std::to_string(window) + ")");
  }
  const Mat3 no_damping = Mat3::Zero();
  // The environment that holds the intact vessel at rest at `pose` (Earth frame).
  const Vec3 b0 = -bank.mooring(0).Load(pose);
  std::vector<Vec3> signatures;
  for (int k = 1; k < bank.size(); ++k) {
    HypothesisEkf intact(bank.mooring(0), model, no_damping, options);
    const HypothesisEkf truth(bank.mooring(k), model, no_damping, options);
    HypothesisEkf::LfState x = HypothesisEkf::LfState::Zero();
    x.segment<3>(0) = pose;
    x.segment<3>(3) = b0;
    Observation observation;
    double t = 0.0;
    for (int i = 0; i < kSettleSamples; ++i, t += dt) {
      observation.t = t;
      observation.pose = pose;
      intact.Update(observation);
    }
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (int i = 0; i < window; ++i) {
      x = truth.LowFrequencyStep(x, Vec3::Zero(), dt, nullptr);
      t += dt;
      observation.t = t;
      observation.pose = x.segment<3>(0);
      const HypothesisEvidence e = intact.Update(observation);
      if (const std::optional<Vec3> w = WhitenInnovation(e.covariance, e.innovation)) {
        sum += *w;
        ++count;
      }
    }
    signatures.push_back(count > 0 ? Vec3(sum / count) : Vec3::Zero());
  }
  return signatures;
}

}  // namespace moorsim::detectors
