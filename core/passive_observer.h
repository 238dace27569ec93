// The passive nonlinear observer with wave filtering of Fossen & Strand (1999) (Fossen 2011
// section 11.4.1; TAPM thesis section 3.4, eq. 3.18-3.19, gains section 4.5) in the horizontal
// plane: its state, gains, option checks, equations and integration, once for the two
// observers built on it, each with its own mooring model and sampling: the detection observers
// (detectors/passive_observer.h, one per mooring hypothesis, quasi-static mooring load, held
// samples) and the observer-based controller (vessel/controller.h, linearised mooring,
// interpolated samples).
//
// Observer (state x = [xi (6), eta (3), b (3), nu (3)], core/observer_state.h):
//   xi'  = A_w xi + K1(w0) e                 A_w per DOF: xi1' = xi2,
//                                            xi2' = -w0^2 xi1 - 2 lambda w0 xi2
//   eta' = R(psi) nu + K2 e
//   b'   = -T^-1 b + M_e(psi) K3 e           (b: Earth-frame force [N, N, N m])
//   nu'  = M^-1 (-D nu + R(psi)^T (g(eta) + b) + tau) + R(psi)^T K4 e
//   e    = y - (eta + C_w xi), heading wrapped to (-pi, pi]; 0 on channels not delivered
// with M_e(psi) = R(psi) M R(psi)^T the mass matrix in Earth axes, g(eta) the mooring load
// the caller models (Earth [Fx, Fy, Mz]: a hypothesis's quasi-static load, or a linearised
// -G eta) and R(psi) rotating the force part of [Fx, Fy, Mz] and leaving Mz. C_w xi = xi2 is
// the wave-frequency motion; without the wave model (wave_filter = false) xi stays 0 and
// eta follows y through K2 alone, wave motion included (a comparison case).
//
// Gains (TAPM thesis eq. 4.4-4.8, from Fossen 2011 and MSS's ExPassiveObs.m), per DOF i:
//   K1_i = -2 (zeta_n - lambda) w_c / w0,  K1_{i+3} = 2 w0 (zeta_n - lambda),  K2_i = w_c,
//   zeta_n = 1, lambda = 0.1, w_c = 1.2255 w0 (1.10 rad/s), K4 = diag(0.1, 0.1, 0.01),
//   K3 = 0.1 K4.
// The w0, lambda, K1 and K2 make the wave/position loop a notch at w0 with its poles at
// the roots of s^2 + 2 zeta_n w0 s + w0^2 (a double pole at -w0 for zeta_n = 1) and -w_c:
// from y to eta a notch of depth lambda / zeta_n = 0.1 in series with a first-order
// low-pass at w_c, 7.7 % of the wave motion left at w0 (Fossen 2011 section 11.4.1).
//
// How K3 and K4 are read (the TAPM thesis is silent on units): eq. 3.19d puts K4 e into
// M nu' = ... + R^T K4 e. Read literally, in SI with M ~ 1.1e8 kg, K4 = 0.1 N/m and
// K3 = 0.01 N/(m s): a 1 m error moves the bias estimate by 0.01 N per second, so the bias
// (about 1 MN on the seed FPSO) is never estimated and the velocity correction is ~1e-9
// m/s^2 per m; the observer is then an open-loop model whose position is only pulled by K2.
// Fossen's numbers (ExPassiveObs.m: K4 = diag(0.1, 0.1, 0.01) with w0 = 0.8976, w_c = 1.1
// rad/s and T = 1000 s) are for a mass-normalised model: his loop transfer h0(s) h_B(s),
// h_B(s) = K4 (s + 1/T + K3/K4) / (s + 1/T), must be SPR with the tuning rule
// 1/T << K3/K4 < w0 < w_c, which fixes the ratio K3/K4 [1/s] and leaves K4 as a rate.
// So here K4 is an acceleration per metre [1/s^2] and K3 a jerk per metre [1/s^3]: the
// force-level gains of eq. 3.19 are M_e K4 and M_e K3, i.e. K4_phys = R M R^T K4 so that
// M nu' = ... + R^T K4_phys e = ... + M R^T K4 e, and b' = ... + R M R^T K3 e. With the
// TAPM thesis's numbers the slowest error modes of the seed FPSO decay with time constants
// of about 20 s (surge, sway) and 30-36 s (yaw), and the loop keeps Fossen's notch and SPR
// shape. `mass_scaled_gains = false` gives the literal SI reading (K4 [N/m, N/m, N m/rad],
// K3 [N/(m s), ...]) for comparison; it does not estimate the bias.
// The bias leaks (-T^-1 b), so a constant Earth-frame load d that the model lacks is read
// at rest as b = d / (1 + (D_ii K2_i / M_ii + K4_i) / (T_i K3_i)) per DOF (mass-scaled
// gains, heading 0, M and D diagonal): 1.2 %, 1.1 % and 6.1 % low in surge, sway and yaw on
// the seed FPSO with the TAPM thesis's gains.
//
// Other choices: the wave model uses lambda in A_w as eq. 3.10-3.11 and Fossen do (the
// TAPM thesis's initPassiveObs.m (appendix A.4) builds A_w with zeta_n instead, and uses
// K4 = diag(0.3, 0.3, 0.01) where the text says 0.1). R is evaluated at the estimated
// heading, not at the measured one as Fossen's R(y3): the thesis's gyro noise (0.005 rad^2,
// 4 deg) rotated into a 1 MN bias would be a 70 kN force noise, and the wave-frequency yaw
// in R(y3) multiplies the wave-frequency part of the injected force and rectifies into a
// bias error (in the controller's tests 5 % of the load at 1 deg of 7 s yaw, 0.4 % with
// R(psi_hat)).
// Passivity (Fossen & Strand 1999) holds for a constant heading; a moored vessel's yaw
// rate (~1e-3 rad/s) is far below every error mode, so R and M_e are constant on their
// time scale.
//
// Discretisation (observations come at 1 Hz on the seed case's sensors): between two
// samples the thrust tau is held and the measurement y is either held (Hold::kZeroOrder:
// the detection observers, whose evidence must be the output predicted before y_k is
// used) or the straight line from the previous sample to the new one (Hold::kFirstOrder:
// the controller, which has the new sample when it integrates; a zero-order hold would
// shift the 7 s wave by half a sample, 26 deg at 1 Hz). With e(t) = y(t) - y_hat(t)
// varying, the observer ODE is integrated by classic RK4 in equal substeps of at most
// max_substep. The linearised observer's fastest eigenvalues on the seed model are the
// notch/cut-off poles, -1.21 +- 0.47i rad/s (|lambda| = 1.3), so with 0.5 s |lambda h| <=
// 0.65 (RK4 is stable to 2.78 on the real axis) and the relative one-step error
// (lambda h)^5 / 120 is <= 1e-3 on those modes, which decay by 0.55 per substep anyway; on
// the slow modes (|lambda| ~ 0.1) it is ~3e-9. The observer is not stiff: no exact
// integration of the wave part is needed. Only y is sampled: y_hat feeds back
// continuously inside the interval, so the hold adds no delay to the loop and the
// continuous-time poles decide stability. The heading estimate is kept in (-pi, pi].
//
// Start: Start::kAllChannels (the detection observers, as HypothesisEkf) waits for the
// first sample with all three channels valid and takes eta = y (psi wrapped), xi = b = nu
// = 0. Start::kEachChannel (the controller) starts at the first sample from the guess
// given to Reset(), and sets eta_i = y_i and channel i's wave state to 0 at the first
// valid sample of channel i. A channel not delivered gets no injection (its e is 0): the
// model runs open-loop on it and its wave state decays.
#pragma once

#include <array>
#include <functional>
#include <string_view>

#include "core/observer_state.h"
#include "core/types.h"

namespace moorsim {

/// The observer's tuning: wave model, gains and bias model, per DOF (defaults: the TAPM
/// thesis's).
struct PassiveObserverTuning {
  /// Wave model: peak frequency w0 = 2 pi / 7 s (TAPM thesis table 4.3) [rad/s].
  Vec3 wave_frequency = Vec3::Constant(0.8975979010256552);
  Vec3 wave_damping = Vec3::Constant(0.1);   ///< lambda [-], >= 0 (TAPM thesis section 4.5)
  Vec3 notch_damping = Vec3::Constant(1.0);  ///< zeta_n [-], > lambda (TAPM thesis section 4.5)
  /// Cut-off w_c as a multiple of w0 [-], > 1: 1.2255 (TAPM thesis section 4.5; w_c = 1.10
  /// rad/s).
  Vec3 cutoff_ratio = Vec3::Constant(1.2255);
  Vec3 bias_time_constant = Vec3::Constant(1000.0);  ///< T [s] (TAPM thesis appendix A.4)
  /// K4 (TAPM thesis eq. 4.8): with mass_scaled_gains an acceleration per metre (per rad) of
  /// innovation [1/s^2], else [N/m, N/m, N m/rad].
  Vec3 velocity_gain = Vec3(0.1, 0.1, 0.01);
  /// K3 = 0.1 K4 (TAPM thesis eq. 4.7): with mass_scaled_gains [1/s^3], else [N/(m s), ...].
  /// Fossen's rule 1/T << K3/K4 < w0 must hold (checked: 1/T < K3/K4 < w0).
  Vec3 bias_gain = Vec3(0.01, 0.01, 0.001);
  /// true: the force-level gains are M_e K4 and M_e K3; false: K4 and K3 as they are (the
  /// literal SI reading, a comparison case that does not estimate the bias).
  bool mass_scaled_gains = true;
};

/// The tuning, and how the observer takes its samples (file comment).
struct PassiveNonlinearObserverOptions : PassiveObserverTuning {
  /// The measurement between two samples: the older held, or the line between them.
  enum class Hold { kZeroOrder, kFirstOrder };
  /// The start: at the first complete sample, or channel by channel.
  enum class Start { kAllChannels, kEachChannel };

  bool wave_filter = true;  ///< false: no wave model (K1 = 0, so xi stays 0)
  Hold hold = Hold::kZeroOrder;
  Start start = Start::kAllChannels;
  /// RK4 substep bound [s]: an interval dt takes ceil(dt / max_substep - 1e-9) (at least
  /// one) equal substeps.
  double max_substep = 0.5;
};

/// The gain matrices of eq. 3.19, diagonal blocks per DOF (TAPM thesis eq. 4.4-4.8).
struct PassiveObserverGains {
  Vec3 k1_integral = Vec3::Zero();  ///< K1_i, rows of xi1 [-]: -2 (zeta_n - lambda) w_c / w0
  Vec3 k1_wave = Vec3::Zero();      ///< K1_{i+3}, rows of xi2 [1/s]: 2 w0 (zeta_n - lambda)
  Vec3 k2 = Vec3::Zero();           ///< K2 = w_c [1/s]
  Vec3 k3 = Vec3::Zero();           ///< K3 (units: PassiveObserverTuning::bias_gain)
  Vec3 k4 = Vec3::Zero();           ///< K4 (units: PassiveObserverTuning::velocity_gain)
};

/// A caller's name for an option in the messages of ValidatePassiveObserver.
struct PassiveObserverKey {
  std::string_view name;
  /// true: the caller sets it per DOF and the key of element i is "name[i + first_index]";
  /// false: one value for all DOFs, named without an index.
  bool per_dof = true;
};

/// How a caller's messages name the options: "<prefix><name>[i]" (ValidatePassiveObserver
/// throws "<key> = <value>: <rule>"). The defaults are the option names, per DOF, from 1.
struct PassiveObserverKeys {
  std::string_view prefix;
  int first_index = 1;
  PassiveObserverKey wave_frequency{"wave_frequency"};
  PassiveObserverKey wave_damping{"wave_damping"};
  PassiveObserverKey notch_damping{"notch_damping"};
  PassiveObserverKey cutoff_ratio{"cutoff_ratio"};
  PassiveObserverKey bias_time_constant{"bias_time_constant"};
  PassiveObserverKey velocity_gain{"velocity_gain"};
  PassiveObserverKey bias_gain{"bias_gain"};
  PassiveObserverKey max_substep{"max_substep", false};
  /// true: the caller sets K3 as the ratio K3/K4, which bias_gain then names and whose
  /// value the messages quote.
  bool bias_gain_is_ratio = false;
};

/// Every option finite and > 0 (wave_damping >= 0), zeta_n > lambda, and the passivity
/// conditions of Fossen & Strand (1999) per DOF: w_c / w0 > 1 and 1/T < K3/K4 < w0. Throws
/// moorsim::InputError "<key> = <value>: <rule>" with the caller's keys.
void ValidatePassiveObserver(const PassiveNonlinearObserverOptions& options,
                             const PassiveObserverKeys& keys = {});

/// Validates `options` and evaluates the gains.
PassiveObserverGains ComputePassiveObserverGains(const PassiveNonlinearObserverOptions& options,
                                                 const PassiveObserverKeys& keys = {});

/// The observer of the file comment on samples of the pose, with the caller's mooring load.
class PassiveNonlinearObserver : public ObserverStateLayout {
 public:
  using Options = PassiveNonlinearObserverOptions;
  /// g(eta): the mooring load [N, N, N m], Earth frame, at the pose eta (NED [m, m, rad]).
  using MooringLoad = std::function<Vec3(const Vec3& eta)>;

  /// `mass` is M = M_RB + A(0) and `damping` D, body axes (M symmetrised as (M + M^T) / 2).
  /// Throws moorsim::InputError on bad options (named by `keys`), non-finite matrices or a
  /// mass that is not positive definite.
  PassiveNonlinearObserver(const Options& options, const Mat3& mass, const Mat3& damping,
                           MooringLoad load, const PassiveObserverKeys& keys = {});

  /// Forgets everything: not started, x = 0 but eta = `eta_initial` (psi wrapped), the
  /// guess that Start::kEachChannel keeps on a channel until its first valid sample.
  void Reset(const Vec3& eta_initial = Vec3::Zero());
  /// Takes the sample y [m, m, rad] (NED; used on the channels where `valid`) that ends an
  /// interval of dt [s] during which the body thrust tau [N, N, N m] acted: integrates the
  /// observer over the interval (once started; dt is not used before), starts the
  /// observer or a channel on the sample by options.start, and holds the sample for the
  /// next interval. Allocates nothing.
  void Update(double dt, const Vec3& tau, const Vec3& y, const std::array<bool, 3>& valid);

  /// e = y - (eta + C_w xi) at the current estimate on the `valid` channels (heading
  /// wrapped), 0 elsewhere: the innovation of a sample against the predicted output.
  Vec3 OutputError(const Vec3& y, const std::array<bool, 3>& valid) const;
  /// dx/dt at x with the measurement y (used on channels where `valid`) and the body
  /// thrust tau.
  State Derivative(const State& x, const Vec3& y, const std::array<bool, 3>& valid,
                   const Vec3& tau) const;

  bool started() const { return started_; }
  const State& state() const { return x_; }
  /// Which channels of the sample held last were valid (injected over its interval with a
  /// first-order hold, over the next one with a zero-order hold).
  const std::array<bool, 3>& valid() const { return valid_; }
  const Options& options() const { return options_; }
  const PassiveObserverGains& gains() const { return gains_; }

 private:
  void Propagate(double dt, const Vec3& tau, const Vec3& y, const std::array<bool, 3>& valid);

  Options options_;
  PassiveObserverGains gains_;
  MooringLoad load_;
  Mat3 mass_ = Mat3::Zero();
  Mat3 mass_inverse_ = Mat3::Zero();
  Mat3 damping_ = Mat3::Zero();
  Vec3 bias_rate_ = Vec3::Zero();        // 1 / T
  Vec3 wave_stiffness_ = Vec3::Zero();   // w0^2
  Vec3 wave_resistance_ = Vec3::Zero();  // 2 lambda w0

  bool started_ = false;
  std::array<bool, 3> seen_ = {false, false, false};  // Start::kEachChannel: channel started
  Vec3 y_ = Vec3::Zero();                             // held sample, 0 where not valid
  std::array<bool, 3> valid_ = {false, false, false};
  State x_ = State::Zero();
};

}  // namespace moorsim
