// The nonlinear passive observer of the TAPM thesis (section 3.4, eq. 3.18-3.19; gains section 4.5;
// Fossen 2011 section 11.4.1, Fossen & Strand 1999) per hypothesis, with a fixed, offline
// innovation covariance for the evidence (TAPM thesis section 4.4), and the bank that runs one
// per hypothesis of a HypothesisBank. An alternative to HypothesisEkf / ObserverBank
// (detectors/ekf_observer.h): same state layout, same evidence.
//
// The observer is PassiveNonlinearObserver (core/passive_observer.h: equations, gains and
// how K3, K4 are read, discretisation) with the hypothesis's quasi-static mooring load g_h(eta)
// (QuasiStaticMooring::Load), D + D_mo as its damping, the mass-scaled gains, the measurement
// and the thrust command held between observations (zero-order hold) and RK4 substeps of at
// most max_substep (0.5 s). It starts at the first observation with all three channels valid:
// eta = y (psi wrapped) and xi = b = nu = 0, as HypothesisEkf. Until then, and at that
// sample, the evidence has dimension 0.
//
// Evidence: at each observation the innovation e_k = y_k - y_hat(t_k^-) is formed from the
// output predicted over the interval (before y_k is used), and its log-likelihood over the
// valid channels is log N(e_v; 0, Sigma_v), Sigma_v the valid block of the fixed covariance
// Sigma_h (TAPM thesis eq. 3.28 with Sigma_H from section 4.4). The innovation is 0 on invalid
// channels, the dimension is the number of valid ones, the covariance is Sigma_h. Sigma_h
// must be the covariance of these same predicted-output innovations (see
// detectors/innovation_covariance.h for how to train it).
// What that evidence separates: a wrong hypothesis's observer must take up the load
// difference (a parted line: ~3.5 MN on the seed FPSO) in its bias, which its K3/K4 loop
// does in 20-40 s with innovations of decimetres; that transient is where the evidence
// is. Once the bias has settled, the 1.1 rad/s position loop makes the observers'
// innovations nearly equal whatever their mooring model (on own-model data the
// steady-state log-likelihoods of the intact and line-6 observers differ by ~0.003 nats
// per sample, not always in favour of the true model), unlike the EKF's, whose gain is
// set by the noise levels.
//
// On bad state: a non-finite estimate or likelihood throws moorsim::SolverError naming
// the time; a non-finite valid measurement or command, or a time that does not advance
// (or jumps by more than max_interval), throws moorsim::InputError.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/observer_state.h"
#include "core/passive_observer.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/hypothesis_bank.h"

namespace moorsim::detectors {

/// The tuning of PassiveNonlinearObserver (TAPM thesis defaults) and the detection
/// observers' own options.
struct PassiveObserverOptions : PassiveObserverTuning {
  /// Linear mooring damping as a fraction of critical per DOF (MooringDampingMatrix);
  /// 0 = none, as EkfOptions. (TAPM thesis appendix A.4 adds 0.1 D.)
  Vec3 mooring_damping_ratio = Vec3::Zero();
  /// Whether Observation::tau_command drives the model (as EkfOptions).
  bool use_thrust_command = true;
  double max_substep = 0.5;    ///< RK4 substep bound [s]
  double max_interval = 60.0;  ///< longest gap between observations bridged [s]
};

/// Throws moorsim::InputError naming the field ("passive.velocity_gain[3]") and the value.
void Validate(const PassiveObserverOptions& options);

using ::moorsim::PassiveObserverGains;

/// Validates `options` and evaluates the gains.
PassiveObserverGains ComputePassiveObserverGains(const PassiveObserverOptions& options);

class HypothesisPassiveObserver : public ObserverStateLayout {
 public:
  /// `mooring_damping` is D_mo [N s/m, ...] in body axes, added to the model's D;
  /// `innovation_covariance` is Sigma_h [m^2, m^2, rad^2 ...], symmetric positive
  /// definite. Throws moorsim::InputError on bad options, a mass that is not positive
  /// definite or a covariance that is not finite, symmetric and positive definite.
  HypothesisPassiveObserver(QuasiStaticMooring mooring, const LowFrequencyModel& model,
                            const Mat3& mooring_damping, const Mat3& innovation_covariance,
                            const PassiveObserverOptions& options = {});

  /// Forgets the estimate; the next complete observation initialises it.
  void Reset();
  /// Integrates the observer to observation.t with the previous sample held, forms the
  /// evidence of observation against the predicted output, then holds observation for
  /// the next interval. Allocates nothing.
  HypothesisEvidence Update(const Observation& observation);

  bool initialised() const { return observer_.started(); }
  double time() const { return t_; }
  const State& state() const { return observer_.state(); }
  Vec3 pose() const { return state().segment<3>(kPose); }
  Vec3 bias() const { return state().segment<3>(kBias); }
  Vec3 velocity() const { return state().segment<3>(kVelocity); }
  Vec3 wave_motion() const { return state().segment<3>(kWave + 3); }
  const Mat3& innovation_covariance() const { return covariance_; }
  const PassiveObserverGains& gains() const { return observer_.gains(); }
  /// e^T Sigma^-1 e over the last sample's valid channels (0 if none).
  double normalised_innovation_squared() const { return nis_; }

  /// dx/dt of the observer with the measurement y held (used on channels where
  /// `valid`), the body thrust tau.
  State Derivative(const State& x, const Vec3& y, const std::array<bool, 3>& valid,
                   const Vec3& tau) const {
    return observer_.Derivative(x, y, valid, tau);
  }

 private:
  PassiveObserverOptions options_;
  PassiveNonlinearObserver observer_;
  Mat3 covariance_ = Mat3::Identity();
  // Per mask of valid channels (bit i = channel i): the inverse of Sigma's valid block,
  // scattered back to 3x3 (zero elsewhere), and log det of that block.
  std::array<Mat3, 8> information_{};
  std::array<double, 8> log_determinant_{};

  double t_ = 0.0;
  Vec3 tau_ = Vec3::Zero();  // held thrust, body
  double nis_ = 0.0;
};

/// One HypothesisPassiveObserver per hypothesis of a HypothesisBank, all fed the same
/// observations; the same public API as ObserverBank. With options.mooring_damping_ratio
/// > 0, hypothesis h gets D_mo = bank.MooringDamping(h, model.mass, ratio).
class PassiveObserverBank {
 public:
  /// `covariances[h]` is Sigma_h (e.g. from TrainPassiveCovariances); one per hypothesis,
  /// else moorsim::InputError.
  PassiveObserverBank(const HypothesisBank& bank, const LowFrequencyModel& model,
                      const PassiveObserverOptions& options, const std::vector<Mat3>& covariances);

  int size() const { return static_cast<int>(observers_.size()); }
  void Reset();
  /// Runs every observer on `observation`; the result stays valid until the next call.
  /// Allocates nothing.
  const Evidence& Update(const Observation& observation);
  const Evidence& evidence() const { return evidence_; }
  const HypothesisPassiveObserver& observer(int h) const { return observers_.at(h); }

 private:
  std::vector<HypothesisPassiveObserver> observers_;
  Evidence evidence_;
};

}  // namespace moorsim::detectors
