// Position-mooring controllers and the passive observer, on a small 3-DOF plant integrated
// here: eta' = R(psi) nu, M nu' + D nu + R^T G eta = tau + R^T d, with the seed FPSO's M and
// D, the seed mooring's 81.6 kN/m in surge and sway and no yaw stiffness (a turret that
// lets the hull weathervane), and a constant NED load d.
#include "vessel/controller.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <vector>

#include "core/error.h"
#include "core/random.h"

namespace moorsim::vessel {
namespace {

const double kWavePeriod = 7.0;  // [s], TAPM thesis table 4.3

Vec3 BodyToNed(const Vec3& v, double psi) {
  return Vec3(std::cos(psi) * v.x() - std::sin(psi) * v.y(),
              std::sin(psi) * v.x() + std::cos(psi) * v.y(), v.z());
}
Vec3 NedToBody(const Vec3& v, double psi) { return BodyToNed(v, -psi); }  // R(-psi) = R(psi)^T

ManoeuvringModel TestModel() {
  ManoeuvringModel model = SeedManoeuvringModel();
  model.mooring_stiffness(2, 2) = 0.0;
  return model;
}

// The 3-DOF low-frequency plant, RK4 at a fixed step.
struct Plant {
  ManoeuvringModel model = TestModel();
  Vec3 disturbance_ned = Vec3::Zero();  // [N, N, N m]
  Vec3 eta = Vec3::Zero();
  Vec3 nu = Vec3::Zero();
  Mat3 mass_inverse = model.mass.inverse();

  void Derivative(const Vec3& e, const Vec3& n, const Vec3& tau, Vec3* e_dot, Vec3* n_dot) const {
    *e_dot = BodyToNed(n, e.z());
    const Vec3 restoring = model.mooring_stiffness * e;
    *n_dot =
        mass_inverse * (tau + NedToBody(disturbance_ned - restoring, e.z()) - model.damping * n);
  }
  void Step(const Vec3& tau, double h) {
    Vec3 e1, n1, e2, n2, e3, n3, e4, n4;
    Derivative(eta, nu, tau, &e1, &n1);
    Derivative(eta + 0.5 * h * e1, nu + 0.5 * h * n1, tau, &e2, &n2);
    Derivative(eta + 0.5 * h * e2, nu + 0.5 * h * n2, tau, &e3, &n3);
    Derivative(eta + h * e3, nu + h * n3, tau, &e4, &n4);
    eta += h / 6.0 * (e1 + 2 * e2 + 2 * e3 + e4);
    nu += h / 6.0 * (n1 + 2 * n2 + 2 * n3 + n4);
  }
};

// Measured pose = low-frequency pose + a 7 s wave-frequency motion + white noise.
struct Sensor {
  double wave_amplitude = 0.0;      // [m] on x and y
  double wave_yaw_amplitude = 0.0;  // [rad]
  double noise_position = 0.0;      // standard deviation [m]
  double noise_heading = 0.0;       // [rad]
  RandomStream noise = RandomStream::Derive(7, "controller_test.sensor");

  Vec3 WaveMotion(double t) const {
    const double w = 2 * kPi / kWavePeriod;
    return Vec3(wave_amplitude * std::sin(w * t), wave_amplitude * std::sin(w * t + 1.0),
                wave_yaw_amplitude * std::sin(w * t + 2.0));
  }
  PoseMeasurementInput Measure(double t, const Vec3& eta) {
    PoseMeasurementInput m;
    m.time = t;
    m.pose = eta + WaveMotion(t) +
             Vec3(noise_position * noise.Normal(), noise_position * noise.Normal(),
                  noise_heading * noise.Normal());
    return m;
  }
};

// Amplitude of the component at `period` in a record sampled every dt (one DFT bin; the
// record spans a whole number of periods).
double Amplitude(const std::vector<double>& record, double dt, double period) {
  std::complex<double> sum = 0.0;
  for (std::size_t k = 0; k < record.size(); ++k) {
    sum += record[k] * std::exp(std::complex<double>(0.0, -2 * kPi * k * dt / period));
  }
  return 2.0 * std::abs(sum) / static_cast<double>(record.size());
}

struct ClosedLoopRecord {
  std::vector<Vec3> eta;      // true low-frequency pose at each controller sample
  std::vector<Vec3> tau;      // command
  std::vector<Vec3> eta_hat;  // controller's estimate
  std::vector<Vec3> bias;
};

// Closed loop at a 1 Hz controller, plant RK4 at 0.1 s, command held between samples.
ClosedLoopRecord RunClosedLoop(PositionController& controller, Plant& plant, Sensor& sensor,
                               double duration, double dropout_start = -1,
                               double dropout_end = -1) {
  const double dt = controller.sample_time();
  const int substeps = 10;
  ClosedLoopRecord r;
  const int samples = static_cast<int>(std::lround(duration / dt));
  for (int k = 0; k < samples; ++k) {
    const double t = k * dt;
    PoseMeasurementInput m = sensor.Measure(t, plant.eta);
    if (t >= dropout_start && t < dropout_end) {
      m.pose.x() = std::nan("");
      m.valid[0] = false;
    }
    const Vec3 tau = controller.Update(m);
    r.eta.push_back(plant.eta);
    r.tau.push_back(tau);
    r.eta_hat.push_back(controller.EstimatedPose());
    r.bias.push_back(controller.EstimatedBias());
    for (int s = 0; s < substeps; ++s) plant.Step(tau, dt / substeps);
  }
  return r;
}

std::vector<double> Channel(const std::vector<Vec3>& v, int i, std::size_t from) {
  std::vector<double> out;
  for (std::size_t k = from; k < v.size(); ++k) out.push_back(v[k][i]);
  return out;
}

// First sample time after which the horizontal offset from `eta_d` stays below `radius`.
double SettlingTime(const std::vector<Vec3>& eta, const Vec3& eta_d, double radius, double dt) {
  std::size_t k = eta.size();
  while (k > 0 && (eta[k - 1] - eta_d).head<2>().norm() < radius) --k;
  return k * dt;
}

// --- (1) PI: zero steady-state error under a constant NED load -------------------------

TEST(PiController, SettlesAtTheSetpointUnderAConstantNedLoad) {
  // Thesis gains, heading -135 deg (the TAPM thesis's initial heading), load 200 kN north and
  // 100 kN west. Closed form for P alone: (Kp + G) e = d, i.e. 1.10 m north, 0.092 m west.
  // The integral removes it; its slowest pole is Ki / (Kp + G) = 1e3 / 1.08e6 -> ~1080 s
  // in the east channel, so 10 000 s leaves e^-8 of the 0.09 m. Settling criterion: the
  // position stays within 1 cm of the setpoint over the last 1000 s.
  const Vec3 eta_d(0.0, 0.0, -135 * kDegree);
  Sensor ideal;
  for (const bool integral : {false, true}) {
    PiControllerOptions options;
    if (!integral) options.ki.setZero();
    PiController controller(options, eta_d, 1.0);
    Plant plant;
    plant.eta = eta_d;
    plant.disturbance_ned = Vec3(2e5, -1e5, 0.0);
    const ClosedLoopRecord r = RunClosedLoop(controller, plant, ideal, 10000.0);
    const Vec3 expected_p_offset((2e5) / (1e5 + 8.157e4), (-1e5) / (1e6 + 8.157e4), 0.0);
    if (!integral) {
      // P only: the static offset of the closed form, to 0.1 % (the loop has settled to
      // machine precision after 10 000 s; the margin covers nothing but rounding).
      EXPECT_NEAR(r.eta.back().x(), expected_p_offset.x(), 1e-3 * expected_p_offset.x());
      EXPECT_NEAR(r.eta.back().y(), expected_p_offset.y(), 1e-3 * -expected_p_offset.y());
      continue;
    }
    double worst = 0.0;
    for (std::size_t k = r.eta.size() - 1000; k < r.eta.size(); ++k) {
      worst = std::max(worst, (r.eta[k] - eta_d).head<2>().norm());
    }
    EXPECT_LT(worst, 0.01) << "largest offset over the last 1000 s [m]";
    std::printf("PI: within 1 cm from t = %.0f s on (P-only offset %.3f m)\n",
                SettlingTime(r.eta, eta_d, 0.01, 1.0), expected_p_offset.head<2>().norm());
    EXPECT_NEAR(r.eta.back().z(), eta_d.z(), 1e-9);  // no yaw load, no yaw motion
    // At rest the command balances the load: R(psi) tau = -d.
    const Vec3 force_ned = BodyToNed(r.tau.back(), r.eta.back().z());
    EXPECT_NEAR(force_ned.x(), -2e5, 2e3);
    EXPECT_NEAR(force_ned.y(), 1e5, 1e3);
    EXPECT_TRUE(std::isnan(controller.EstimatedPose().x()));
    EXPECT_TRUE(std::isnan(controller.EstimatedBias().z()));
  }
}

// --- (2) sign at any heading ------------------------------------------------------------

TEST(PositionControllers, DisplacedNorthGetsASouthwardForceAtAnyHeading) {
  for (const double psi_deg : {0.0, 45.0, 90.0, 179.0, -90.0, -135.0}) {
    const double psi = psi_deg * kDegree;
    for (const ControllerType t : {ControllerType::kPi, ControllerType::kObserverPid}) {
      const std::string_view type = ChoiceName(t);
      ControllerSpec spec;
      spec.type = t;
      spec.setpoint = Vec3(0.0, 0.0, psi);
      const auto controller = MakeController(spec, 1.0);
      PoseMeasurementInput m;
      m.pose = Vec3(1.0, 0.0, psi);  // 1 m north of the setpoint, on heading
      const Vec3 tau = controller->Update(m);
      const Vec3 force_ned = BodyToNed(tau, psi);
      EXPECT_LT(force_ned.x(), 0.0) << type << " psi " << psi_deg;
      // Only north is wrong: the east component is a rounding residue of the rotation.
      EXPECT_LT(std::abs(force_ned.y()), 1e-9 * std::abs(force_ned.x())) << type << psi_deg;
      // First sample: e = 1 m, z = dt e = 1 m s, nu_hat = 0, so |F| = Kp + Ki exactly.
      double expected = 1e5 + 1e3;  // thesis gains
      if (const auto* pid = dynamic_cast<const ObserverPidController*>(controller.get())) {
        expected = pid->kp().x() + pid->ki().x();
      }
      EXPECT_NEAR(force_ned.x(), -expected, 1e-9 * expected) << type << " psi " << psi_deg;
    }
  }
}

// --- (3) heading error wraps ------------------------------------------------------------

TEST(PositionControllers, HeadingErrorWrapsAcrossPlusMinus180Degrees) {
  // Setpoint 179 deg, measured -179 deg = 181 deg: the vessel is 2 deg past the setpoint
  // (clockwise), so the moment must be small and turn it back: negative N, |N| = the yaw
  // gains times 2 deg, not times 358 deg.
  for (const ControllerType t : {ControllerType::kPi, ControllerType::kObserverPid}) {
    const std::string_view type = ChoiceName(t);
    ControllerSpec spec;
    spec.type = t;
    spec.setpoint = Vec3(0.0, 0.0, 179 * kDegree);
    const auto controller = MakeController(spec, 1.0);
    PoseMeasurementInput m;
    m.pose = Vec3(0.0, 0.0, -179 * kDegree);
    const Vec3 tau = controller->Update(m);
    double gains = 1e3 + 1e2;  // thesis Kp + Ki dt
    if (const auto* pid = dynamic_cast<const ObserverPidController*>(controller.get())) {
      gains = pid->kp().z() + pid->ki().z();
    }
    EXPECT_LT(tau.z(), 0.0) << type;
    EXPECT_NEAR(tau.z(), -gains * 2 * kDegree, 1e-9 * gains) << type;
    EXPECT_NEAR(tau.x(), 0.0, 1e-9) << type;
    EXPECT_NEAR(tau.y(), 0.0, 1e-9) << type;
  }
}

// --- (4) missing channels ---------------------------------------------------------------

TEST(PiController, MissingChannelHoldsItsLastValueAndFreezesItsIntegral) {
  PiControllerOptions options;  // thesis gains, kd = 0
  PiController controller(options, Vec3::Zero(), 1.0);
  PoseMeasurementInput first;
  first.pose = Vec3(1.0, 2.0, 0.1);
  controller.Update(first);
  PoseMeasurementInput second;
  second.pose = Vec3(std::nan(""), 3.0, 0.2);
  second.valid = {false, true, true};
  const Vec3 tau = controller.Update(second);
  // x held at 1 m and integrated once; y fresh at 3 m, integral 2 + 3; psi 0.2, 0.1 + 0.2.
  const Vec3 error(1.0, 3.0, 0.2), integral(1.0, 5.0, 0.3);
  const Vec3 expected =
      NedToBody(-(options.kp.cwiseProduct(error) + options.ki.cwiseProduct(integral)), 0.2);
  EXPECT_LT((tau - expected).norm(), 1e-9 * expected.norm());
  EXPECT_LT((controller.integral() - integral).norm(), 1e-12);

  // valid = true with a NaN value counts as missing; a missing heading holds the rotation.
  PoseMeasurementInput third;
  third.pose = Vec3(1.0, 3.0, std::nan(""));
  const Vec3 tau3 = controller.Update(third);
  EXPECT_TRUE(tau3.allFinite());
  const Vec3 integral3(2.0, 8.0, 0.3);
  const Vec3 expected3 =
      NedToBody(-(options.kp.cwiseProduct(error) + options.ki.cwiseProduct(integral3)), 0.2);
  EXPECT_LT((tau3 - expected3).norm(), 1e-9 * expected3.norm());
}

TEST(PiController, ChannelMissingFromTheStartGivesNoActionOnIt) {
  PiController controller(PiControllerOptions{}, Vec3(5.0, 0.0, 0.0), 1.0);
  PoseMeasurementInput m;
  m.pose = Vec3(std::nan(""), 1.0, 0.0);
  m.valid = {false, true, true};
  const Vec3 tau = controller.Update(m);
  EXPECT_DOUBLE_EQ(tau.x(), 0.0);
  EXPECT_LT(tau.y(), 0.0);
}

TEST(PiController, DerivativeOfARampIsItsSlopeAfterTheFilterSettles) {
  // x = 0.1 t through a 10 s first-order lag: after 200 s the filtered slope is 0.1 m/s
  // to e^-20, so the derivative term is Kd 0.1 to rounding.
  PiControllerOptions options;
  options.kp.setZero();
  options.ki.setZero();
  options.kd = Vec3(1e6, 0.0, 0.0);
  PiController controller(options, Vec3::Zero(), 1.0);
  Vec3 tau;
  for (int k = 0; k <= 200; ++k) {
    PoseMeasurementInput m;
    m.pose = Vec3(0.1 * k, 0.0, 0.0);
    tau = controller.Update(m);
  }
  EXPECT_NEAR(tau.x(), -1e6 * 0.1, 1e-3);
}

TEST(PiController, FilteredErrorFollowsAHeadingStepThroughTheFirstOrderLag) {
  // A 0.1 rad heading step at sample 1: with filtered_error on yaw the P term follows the
  // 10 s lag, 1 - exp(-k dt / T) of the step after k samples; raw, it takes the whole step
  // at once.
  PiControllerOptions options;
  options.kp = Vec3(0.0, 0.0, 1e8);
  options.ki.setZero();
  options.filtered_error = {false, false, true};
  PiController filtered(options, Vec3::Zero(), 1.0);
  options.filtered_error = {false, false, false};
  PiController raw(options, Vec3::Zero(), 1.0);
  PoseMeasurementInput m;
  filtered.Update(m);
  raw.Update(m);
  m.pose = Vec3(0.0, 0.0, 0.1);
  for (int k = 1; k <= 5; ++k) {
    const double expected = -1e8 * 0.1 * (1.0 - std::exp(-k / 10.0));
    EXPECT_NEAR(filtered.Update(m).z(), expected, 1e-6 * std::abs(expected)) << "k = " << k;
    EXPECT_NEAR(raw.Update(m).z(), -1e7, 1e-6);
  }
}

TEST(ObserverPidController, DropoutOfAChannelKeepsTheLoopOnTheModel) {
  // 30 s without x at t = 1500 s, closed loop with waves and noise: the estimate coasts on
  // the model and the command stays finite and bounded. What limits the coasting: b_hat
  // carries a 7 s ripple K3 |y_tilde_wf| / omega_0 ~ 70 kN (the notch leaves 6 % of the
  // wave in y_tilde), frozen at whatever phase the dropout caught it; over 30 s that force
  // on 1.08e8 kg drifts the estimate by up to 0.5 a t^2 ~ 0.3 m. Asserted: 0.5 m.
  ObserverPidOptions options;
  options.model = TestModel();
  ObserverPidController controller(options, Vec3(0, 0, -135 * kDegree), 1.0);
  Plant plant;
  plant.eta = controller.setpoint();
  plant.disturbance_ned = Vec3(1.5e5, -1e5, 1e6);
  Sensor sensor;
  sensor.wave_amplitude = 1.0;
  sensor.noise_position = std::sqrt(0.005);
  sensor.noise_heading = 0.1 * kDegree;
  const ClosedLoopRecord r = RunClosedLoop(controller, plant, sensor, 1600.0, 1500.0, 1530.0);
  double worst_estimate = 0.0, worst_command = 0.0;
  for (std::size_t k = 1500; k < 1530; ++k) {
    ASSERT_TRUE(r.tau[k].allFinite());
    worst_estimate = std::max(worst_estimate, std::abs(r.eta_hat[k].x() - r.eta[k].x()));
    worst_command = std::max(worst_command, r.tau[k].head<2>().norm());
  }
  std::printf("dropout: worst |x_hat - x| %.3f m, worst |tau_xy| %.0f N\n", worst_estimate,
              worst_command);
  EXPECT_LT(worst_estimate, 0.5);
  EXPECT_LT(worst_command, 1e6);  // Kp 0.5 m + the bias it holds: well under 1 MN
}

// --- (5) observer: wave filtering and bias ----------------------------------------------

TEST(PassiveObserver, TracksTheLowFrequencyPoseAndTheNedBias) {
  // Open loop: the plant is pushed by a slow known thrust (periods 400 and 600 s), a
  // constant NED load d, and the measurement carries a 1 m, 7 s wave motion in x and y,
  // 1 deg in yaw, and white noise (sigma^2 = 0.005 m^2 as in the TAPM thesis; 0.1 deg).
  const ManoeuvringModel model = TestModel();
  PassiveObserver observer(model, PassiveObserverOptions{}, 1.0);
  observer.Reset(Vec3(0, 0, -135 * kDegree));
  Plant plant;
  plant.eta = Vec3(0, 0, -135 * kDegree);
  plant.disturbance_ned = Vec3(1.5e5, -1e5, 1e6);
  Sensor sensor;
  sensor.wave_amplitude = 1.0;
  sensor.wave_yaw_amplitude = 1.0 * kDegree;
  sensor.noise_position = std::sqrt(0.005);
  sensor.noise_heading = 0.1 * kDegree;

  const double duration = 3100.0;
  std::vector<Vec3> error, bias;
  std::vector<double> heading;
  Vec3 tau_previous = Vec3::Zero();
  for (int k = 0; k < static_cast<int>(duration); ++k) {
    const double t = k;
    observer.Update(sensor.Measure(t, plant.eta), tau_previous);  // the thrust of [t - 1, t]
    const Vec3 tau(2e5 * std::sin(2 * kPi * t / 400), 5e4 * std::cos(2 * kPi * t / 400),
                   5e7 * std::sin(2 * kPi * t / 600));
    tau_previous = tau;
    Vec3 e = observer.eta_hat() - plant.eta;
    e.z() = std::remainder(e.z(), 2 * kPi);
    error.push_back(e);
    bias.push_back(observer.bias());
    heading.push_back(plant.eta.z());
    for (int s = 0; s < 10; ++s) plant.Step(tau, 0.1);
  }
  // Judge the last 2100 s = 300 wave periods, after a 1000 s start-up.
  const std::size_t from = error.size() - 2100;
  double min_heading = 1e9, max_heading = -1e9;
  for (std::size_t k = from; k < heading.size(); ++k) {
    min_heading = std::min(min_heading, heading[k]);
    max_heading = std::max(max_heading, heading[k]);
  }
  std::printf("heading over the record: %.1f .. %.1f deg\n", min_heading / kDegree,
              max_heading / kDegree);
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> e = Channel(error, i, from);
    double square = 0.0;
    for (double v : e) square += v * v;
    const double rms = std::sqrt(square / e.size());
    const double wave = Amplitude(e, 1.0, kWavePeriod);
    const double input = i < 2 ? 1.0 : 1.0 * kDegree;
    std::printf("DOF %d: rms(eta_hat - eta) %.4f, 7 s part %.4f = %.1f %% of the input\n", i, rms,
                wave, 100 * wave / input);
    // The notch (depth lambda / zeta_n = 0.1) in series with the omega_c low-pass gives
    // 7.7 % at omega_0 in continuous time; 1 Hz sampling and the velocity loop move it a
    // little. Asserted: at least 18 dB (12.5 %) attenuation.
    EXPECT_LT(wave, 0.125 * input) << "DOF " << i;
  }
  // Position error overall (LF error + WF residual + filtered noise), x and y.
  const std::vector<double> ex = Channel(error, 0, from), ey = Channel(error, 1, from);
  double sx = 0, sy = 0;
  for (std::size_t k = 0; k < ex.size(); ++k) {
    sx += ex[k] * ex[k];
    sy += ey[k] * ey[k];
  }
  EXPECT_LT(std::sqrt(sx / ex.size()), 0.15);
  EXPECT_LT(std::sqrt(sy / ey.size()), 0.15);

  Vec3 mean_bias = Vec3::Zero();
  for (std::size_t k = from; k < bias.size(); ++k) mean_bias += bias[k];
  mean_bias /= static_cast<double>(bias.size() - from);
  // Bias: b_hat is an Earth-frame force, so its mean over the record is d itself, not
  // R^T d (the heading swings by tens of degrees). The leaky bias model under-reads by a
  // known factor: at rest b_hat = T K3 y_tilde and the model's force balance needs
  // b_hat + (D K2 + K4) y_tilde = d, so b_hat = d / (1 + (D K2 + K4) / (T K3)): 1.2 %,
  // 1.1 % and 6.5 % low for the seed FPSO. Asserted: within 1 % of d of that value (the
  // noise and the wave residual move the mean by a few tenths of a per cent).
  const PassiveObserverOptions defaults;
  for (int i = 0; i < 3; ++i) {
    const double m = model.mass(i, i), k2 = defaults.cutoff_ratio * defaults.wave_peak_frequency[i];
    const double k4 = m * defaults.k4_per_mass[i], k3 = defaults.k3_ratio * k4;
    const double expected =
        plant.disturbance_ned[i] /
        (1.0 + (model.damping(i, i) * k2 + k4) / (defaults.bias_time_constant[i] * k3));
    std::printf("DOF %d: mean b_hat %.0f, closed form %.0f, d %.0f\n", i, mean_bias[i], expected,
                plant.disturbance_ned[i]);
    EXPECT_NEAR(mean_bias[i], expected, 0.01 * std::abs(plant.disturbance_ned[i])) << "DOF " << i;
  }
}

TEST(PassiveObserver, ChannelMissingAtTheStartKeepsTheInitialGuessUntilItsFirstSample) {
  ManoeuvringModel model = TestModel();
  model.mooring_stiffness.setZero();  // so that nothing pulls the guess toward the origin
  PassiveObserver observer(model, PassiveObserverOptions{}, 1.0);
  observer.Reset(Vec3(10.0, 20.0, 0.5));
  PoseMeasurementInput m;
  m.pose = Vec3(std::nan(""), 21.0, 0.4);
  m.valid = {false, true, true};
  observer.Update(m, Vec3::Zero());
  EXPECT_DOUBLE_EQ(observer.eta_hat().x(), 10.0);  // the guess, untouched
  EXPECT_DOUBLE_EQ(observer.eta_hat().y(), 21.0);  // first sample taken as is
  EXPECT_DOUBLE_EQ(observer.eta_hat().z(), 0.4);
  EXPECT_FALSE(observer.fresh(0));
  for (int k = 1; k < 5; ++k) observer.Update(m, Vec3::Zero());
  EXPECT_NEAR(observer.eta_hat().x(), 10.0, 1e-6);  // open loop, at rest: stays
  m.pose.x() = 12.0;
  m.valid[0] = true;
  observer.Update(m, Vec3::Zero());
  EXPECT_DOUBLE_EQ(observer.eta_hat().x(), 12.0);  // snapped, not filtered in from 10 m
  EXPECT_TRUE(observer.eta_hat().allFinite() && observer.nu_hat().allFinite());
}

// --- (6) observer PID closed loop -------------------------------------------------------

TEST(ObserverPidController, SettlesWithTheWaveMotionFilteredOutOfTheCommand) {
  // From the TAPM thesis's initial pose (2 m, 2 m off, heading -135 deg) with a constant NED load,
  // measured through 1 m of 7 s wave motion and noise. Run with and without the wave
  // model and compare the 7 s content of the command.
  double wave_content[2] = {0.0, 0.0};
  for (const bool wave_filter : {true, false}) {
    ObserverPidOptions options;
    options.model = TestModel();
    options.observer.wave_filter = wave_filter;
    ObserverPidController controller(options, Vec3(0, 0, -135 * kDegree), 1.0);
    Plant plant;
    plant.eta = Vec3(2, 2, -135 * kDegree);
    plant.disturbance_ned = Vec3(1.5e5, -1e5, 1e6);
    Sensor sensor;
    sensor.wave_amplitude = 1.0;
    sensor.wave_yaw_amplitude = 1.0 * kDegree;
    sensor.noise_position = std::sqrt(0.005);
    sensor.noise_heading = 0.1 * kDegree;
    const ClosedLoopRecord r = RunClosedLoop(controller, plant, sensor, 3100.0);
    const std::size_t from = r.tau.size() - 2100;  // 300 wave periods after 1000 s
    const double wave_x = Amplitude(Channel(r.tau, 0, from), 1.0, kWavePeriod);
    const double wave_y = Amplitude(Channel(r.tau, 1, from), 1.0, kWavePeriod);
    wave_content[wave_filter ? 0 : 1] = std::hypot(wave_x, wave_y);
    Vec3 mean = Vec3::Zero();
    double worst = 0.0;
    for (std::size_t k = from; k < r.eta.size(); ++k) {
      mean += r.eta[k] - controller.setpoint();
      worst = std::max(worst, (r.eta[k] - controller.setpoint()).head<2>().norm());
    }
    mean /= static_cast<double>(r.eta.size() - from);
    std::printf(
        "wave_filter %d: mean offset [%.4f m, %.4f m, %.4f deg], worst %.3f m, "
        "7 s command %.0f N (X), %.0f N (Y)\n",
        wave_filter, mean.x(), mean.y(), mean.z() / kDegree, worst, wave_x, wave_y);
    std::printf("  from 2.83 m off: within 0.1 m from t = %.0f s on\n",
                SettlingTime(r.eta, controller.setpoint(), 0.1, 1.0));
    if (wave_filter) {
      EXPECT_LT(SettlingTime(r.eta, controller.setpoint(), 0.1, 1.0), 1000.0);
      // Settled: no mean offset (integral action) beyond 5 cm / 0.2 deg, and the
      // low-frequency pose stays within 0.5 m (noise through the loop) once settled.
      EXPECT_LT(mean.head<2>().norm(), 0.05);
      EXPECT_LT(std::abs(mean.z()), 0.2 * kDegree);
      EXPECT_LT(worst, 0.5);
    }
  }
  // Without the notch the command carries the 1 m wave through Kp (0.30 MN/m in surge)
  // and Kd; with it, the wave part is attenuated at least 5 times.
  EXPECT_LT(wave_content[0], 0.2 * wave_content[1]);
}

// --- (7) construction by name and bad options -------------------------------------------

TEST(MakeController, BuildsEveryTypeUnderItsName) {
  const std::span<const std::string_view> types = ChoiceNames<ControllerType>();
  ASSERT_EQ(types.size(), 3u);
  EXPECT_EQ(types[0], "none");
  EXPECT_EQ(types[1], "observer_pid");
  EXPECT_EQ(types[2], "pi");
  for (const ControllerType t :
       {ControllerType::kNone, ControllerType::kObserverPid, ControllerType::kPi}) {
    const std::string_view type = ChoiceName(t);
    ControllerSpec spec;
    spec.type = t;
    const auto controller = MakeController(spec, 0.5);
    EXPECT_EQ(controller->name(), type);
    EXPECT_DOUBLE_EQ(controller->sample_time(), 0.5);
    PoseMeasurementInput m;
    m.pose = Vec3(3.0, -4.0, 0.3);
    const Vec3 tau = controller->Update(m);
    EXPECT_TRUE(tau.allFinite());
    EXPECT_EQ(tau.isZero(0.0), type == "none") << type;
  }
}

// Runs `make` and returns the InputError's message ("" if nothing was thrown).
template <typename F>
std::string InputErrorOf(F make) {
  try {
    make();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MakeController, RejectsBadOptions) {
  ControllerSpec spec;
  spec.pi.kp.y() = -5.0;
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.pi.kp[1] = -5: must be finite and >= 0");
  spec = ControllerSpec{};
  spec.pi.ki.z() = std::nan("");
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.pi.ki[2] = nan: must be finite and >= 0");
  spec = ControllerSpec{};
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 0.0); }),
            "controller.sample_time = 0: must be finite and > 0 s");

  spec = ControllerSpec{};
  spec.type = ControllerType::kObserverPid;
  spec.observer_pid.natural_frequency = -0.05;
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.observer_pid.natural_frequency = -0.05: must be finite and > 0 rad/s");
  spec.observer_pid = ObserverPidOptions{};
  spec.observer_pid.observer.cutoff_ratio = 0.9;
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.observer_pid.observer.cutoff_ratio = 0.9: must be > 1 (passivity: "
            "omega_c > omega_0)");
  spec.observer_pid = ObserverPidOptions{};
  spec.observer_pid.observer.k3_ratio = 2.0;  // above omega_0 = 0.898 rad/s
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.observer_pid.observer.k3_ratio = 2: must be < wave_peak_frequency "
            "(passivity)");
  spec.observer_pid = ObserverPidOptions{};
  spec.observer_pid.model.mass(0, 1) = spec.observer_pid.model.mass(1, 0) = 1e9;
  EXPECT_EQ(InputErrorOf([&] { MakeController(spec, 1.0); }),
            "controller.observer_pid.model.mass: must be positive definite");

  PiController controller(PiControllerOptions{}, Vec3::Zero(), 1.0);
  EXPECT_EQ(InputErrorOf([&] { controller.SetSetpoint(Vec3(0, std::nan(""), 0)); }),
            "controller.setpoint[1] = nan: must be finite");
}

TEST(ObserverPidController, BandwidthGainsFollowTheMssRule) {
  ObserverPidOptions options;
  ObserverPidController controller(options, Vec3::Zero(), 1.0);
  const Vec3 mass = options.model.mass.diagonal();
  const double wn = options.natural_frequency, zeta = options.relative_damping;
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(controller.kp()[i], mass[i] * wn * wn);
    EXPECT_DOUBLE_EQ(controller.kd()[i], 2 * zeta * wn * mass[i]);
    EXPECT_DOUBLE_EQ(controller.ki()[i], mass[i] * wn * wn * wn / 10);
  }
  // Seed FPSO: Kp = 0.297 MN/m in surge at omega_n = 2 pi / 120 s.
  EXPECT_NEAR(controller.kp().x(), 2.97e5, 0.01e5);
}

// SizeAxisGains: with its kp and kd the loop m s^2 + (d + kd) s + (k + kp) has the asked
// natural frequency and damping (the integral a decade below moves them by ~1 %); a plant
// damped beyond zeta gets kd = 0, a stiffer one kp = 0.
TEST(SizeAxisGains, PlacesTheClosedLoopAtThePeriodAndDamping) {
  const double m = 4.38e11, d = m / 20.0;  // the seed FPSO's yaw, MSS damping rule
  const double period = 120.0, zeta = 0.9;
  const AxisGains g = SizeAxisGains(m, d, 0.0, period, zeta);
  const double wn = 2.0 * M_PI / period;
  EXPECT_NEAR(std::sqrt(g.kp / m), wn, 1e-12 * wn);
  EXPECT_NEAR((d + g.kd) / (2.0 * m * wn), zeta, 1e-12);
  EXPECT_NEAR(g.ki, g.kp * wn / 10.0, 1e-9 * g.ki);
  // 200 s at 0.8: the hull's own damping 1 / (2 x 20 s x omega_n) = 0.796 is nearly all.
  const AxisGains slow = SizeAxisGains(m, d, 0.0, 200.0, 0.5);
  EXPECT_EQ(slow.kd, 0.0);
  EXPECT_GT(slow.kp, 0.0);
  const AxisGains stiff = SizeAxisGains(m, d, 1e12, 200.0, 0.8);
  EXPECT_EQ(stiff.kp, 0.0);
  EXPECT_EQ(stiff.ki, 0.0);
  EXPECT_THROW(SizeAxisGains(m, d, 0.0, 0.0, 0.8), InputError);
  EXPECT_THROW(SizeAxisGains(m, d, 0.0, 200.0, -1.0), InputError);
  EXPECT_THROW(SizeAxisGains(-m, d, 0.0, 200.0, 0.8), InputError);
}

}  // namespace
}  // namespace moorsim::vessel
