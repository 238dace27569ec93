// Tests of the hypothesis EKFs (detectors/ekf_observer.h).
//
// The main check is consistency: data simulated from the filter's OWN model (the nonlinear
// low-frequency dynamics with the hypothesis's quasi-static mooring, the wave filter, the
// bias, with process and measurement noise drawn from independent RandomStreams) must give
// innovations whose normalised square e^T S^-1 e averages to the number of channels. The
// simulator here is written separately from the filter: 50 RK4 substeps per sample with
// the noise injected half before and half after each substep (Euler-Maruyama split
// symmetrically, so the injected covariance is right to O(h^2)), not the filter's exact
// wave discretisation and tangent-linear transition.
#include "detectors/ekf_observer.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "detectors/hypothesis_bank.h"
#include "tests/detectors/observer_test_support.h"

namespace moorsim::detectors {
namespace {

using Vec15 = Eigen::Matrix<double, 15, 1>;
using testing::SeedBank;

/// The filter's model as a stochastic simulation: state [xi1 (3), xi2 (3), eta, b, nu].
class OwnModelSimulator {
 public:
  OwnModelSimulator(const QuasiStaticMooring& mooring, const LowFrequencyModel& model,
                    const EkfOptions& options, std::uint64_t seed, const Vec3& eta0)
      : mooring_(&mooring),
        model_(model),
        options_(options),
        mass_inverse_(model.mass.inverse()),
        wave_(RandomStream::Derive(seed, "process.wave")),
        bias_(RandomStream::Derive(seed, "process.bias")),
        force_(RandomStream::Derive(seed, "process.force")),
        measure_x_(RandomStream::Derive(seed, "measurement.x")),
        measure_y_(RandomStream::Derive(seed, "measurement.y")),
        measure_psi_(RandomStream::Derive(seed, "measurement.psi")) {
    RandomStream initial = RandomStream::Derive(seed, "initial");
    x_.setZero();
    for (int i = 0; i < 3; ++i) {
      const double std_xi2 = options.wave_motion_std(i);
      x_(i) = std_xi2 / options.wave_frequency(i) * initial.Normal();
      x_(3 + i) = std_xi2 * initial.Normal();
      x_(9 + i) = options.bias_std(i) * initial.Normal();
      x_(12 + i) = options.initial_velocity_std(i) * initial.Normal();
    }
    x_.segment<3>(6) = eta0;
  }

  const Vec15& state() const { return x_; }
  /// Switches the truth to another mooring (a line parting); the state carries on.
  void SetMooring(const QuasiStaticMooring& mooring) { mooring_ = &mooring; }

  /// Advances by dt with the body thrust tau held.
  void Advance(double dt, const Vec3& tau) {
    constexpr int kSubsteps = 50;
    const double h = dt / kSubsteps;
    for (int k = 0; k < kSubsteps; ++k) {
      Inject(0.5 * h);
      const Vec15 k1 = Derivative(x_, tau);
      const Vec15 k2 = Derivative(x_ + 0.5 * h * k1, tau);
      const Vec15 k3 = Derivative(x_ + 0.5 * h * k2, tau);
      const Vec15 k4 = Derivative(x_ + h * k3, tau);
      x_ += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      Inject(0.5 * h);
    }
  }

  /// y = eta + xi2 + v, heading wrapped to (-pi, pi] as a gyro would give it.
  Observation Measure(double t, const Vec3& tau) {
    Observation obs;
    obs.t = t;
    const Vec3 r = options_.measurement_variance.cwiseSqrt();
    obs.pose =
        x_.segment<3>(6) + x_.segment<3>(3) +
        Vec3(r(0) * measure_x_.Normal(), r(1) * measure_y_.Normal(), r(2) * measure_psi_.Normal());
    obs.pose.z() = std::remainder(obs.pose.z(), 2.0 * kPi);
    obs.tau_command = tau;
    return obs;
  }

 private:
  Vec15 Derivative(const Vec15& x, const Vec3& tau) const {
    Vec15 d;
    for (int i = 0; i < 3; ++i) {
      const double w0 = options_.wave_frequency(i);
      d(i) = x(3 + i);
      d(3 + i) = -w0 * w0 * x(i) - 2.0 * options_.wave_damping(i) * w0 * x(3 + i);
    }
    const Vec3 eta = x.segment<3>(6);
    const Vec3 b = x.segment<3>(9);
    const Vec3 nu = x.segment<3>(12);
    const double c = std::cos(eta.z()), s = std::sin(eta.z());
    d.segment<3>(6) = Vec3(c * nu.x() - s * nu.y(), s * nu.x() + c * nu.y(), nu.z());
    d.segment<3>(9) = -b.cwiseQuotient(options_.bias_time_constant);
    const Vec3 f = mooring_->Load(eta) + b;  // Earth
    const Vec3 f_body(c * f.x() + s * f.y(), -s * f.x() + c * f.y(), f.z());
    d.segment<3>(12) = mass_inverse_ * (-model_.damping * nu + f_body + tau);
    return d;
  }

  void Inject(double h) {
    const double root = std::sqrt(h);
    for (int i = 0; i < 3; ++i) {
      const double sigma = options_.wave_motion_std(i) *
                           std::sqrt(4.0 * options_.wave_damping(i) * options_.wave_frequency(i));
      x_(3 + i) += sigma * root * wave_.Normal();
      const double q_b = options_.bias_std(i) * std::sqrt(2.0 / options_.bias_time_constant(i));
      x_(9 + i) += q_b * root * bias_.Normal();
    }
    const Vec3 force(options_.force_noise(0) * force_.Normal(),
                     options_.force_noise(1) * force_.Normal(),
                     options_.force_noise(2) * force_.Normal());
    x_.segment<3>(12) += mass_inverse_ * force * root;
  }

  const QuasiStaticMooring* mooring_;
  LowFrequencyModel model_;
  EkfOptions options_;
  Mat3 mass_inverse_;
  RandomStream wave_, bias_, force_, measure_x_, measure_y_, measure_psi_;
  Vec15 x_;
};

/// A proportional controller on the measured pose, body axes: exercises the thrust path.
Vec3 Command(const Vec3& measured) {
  const double c = std::cos(measured.z()), s = std::sin(measured.z());
  const Vec3 f_earth(-1e5 * measured.x(), -1e5 * measured.y(), -1e7 * measured.z());
  return Vec3(c * f_earth.x() + s * f_earth.y(), -s * f_earth.x() + c * f_earth.y(), f_earth.z());
}

struct RunStatistics {
  double mean_nis = 0.0;
  int samples = 0;
};

/// Runs one filter on `samples` seconds of own-model data from `truth_mooring`.
RunStatistics RunConsistency(const QuasiStaticMooring& truth_mooring, std::uint64_t seed,
                             int samples, bool control, const Vec3& eta0 = Vec3::Zero()) {
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  OwnModelSimulator truth(truth_mooring, model, options, seed, eta0);
  HypothesisEkf filter(truth_mooring, model, Mat3::Zero(), options);
  RunStatistics stats;
  Vec3 tau = Vec3::Zero();
  for (int k = 0; k <= samples; ++k) {
    if (k > 0) truth.Advance(1.0, tau);
    const Observation obs = truth.Measure(k, tau);
    const Vec3 next_tau = control ? Command(obs.pose) : Vec3::Zero();
    Observation fed = obs;
    fed.tau_command = next_tau;  // the command issued at this sample, held until the next
    const HypothesisEvidence e = filter.Update(fed);
    if (k > 0) {
      EXPECT_EQ(e.dimension, 3);
      stats.mean_nis += filter.normalised_innovation_squared();
      ++stats.samples;
    }
    tau = next_tau;
  }
  stats.mean_nis /= stats.samples;
  return stats;
}

// Consistency on data from the filter's own model. If the filter is right, e^T S^-1 e is
// chi-square with 3 degrees of freedom per sample and independent between samples, so the
// mean over 2000 samples has mean 3 and standard deviation sqrt(2 * 3 / 2000) = 0.055; the
// bound [2.82, 3.18] is +-3.3 sigma (two-sided 99.9 %). A Q or a discretisation off by 10 %
// moves the mean by about 0.1-0.3 and fails it. Intact mooring with a P controller
// (commands from the noisy measurements, which the filter sees as known inputs).
TEST(EkfConsistencyTest, IntactOwnModelWithControl) {
  const RunStatistics stats = RunConsistency(SeedBank().mooring(0), 11, 2000, true);
  EXPECT_GT(stats.mean_nis, 2.82);
  EXPECT_LT(stats.mean_nis, 3.18);
}

// The same for line 6 failed, uncontrolled: the vessel drifts ~45 m to its new
// equilibrium under the 3.5 MN imbalance, so the linearisation moves along the way.
TEST(EkfConsistencyTest, LineSixOwnModelDrifting) {
  const RunStatistics stats = RunConsistency(SeedBank().mooring(6), 12, 2000, false);
  EXPECT_GT(stats.mean_nis, 2.82);
  EXPECT_LT(stats.mean_nis, 3.18);
}

/// Summed log-likelihood of every hypothesis of the bank on `samples` of own-model data
/// generated with hypothesis `truth_h`.
std::vector<double> SummedLogLikelihood(int truth_h, std::uint64_t seed, int samples) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  OwnModelSimulator truth(bank.mooring(truth_h), model, options, seed, Vec3::Zero());
  ObserverBank observers(
      bank, model, options,
      ObserverBankOptions{.switch_rate = 0.0, .sensor_checks = {}});  // independent
  std::vector<double> sum(bank.size(), 0.0);
  for (int k = 0; k <= samples; ++k) {
    if (k > 0) truth.Advance(1.0, Vec3::Zero());
    const Evidence& evidence = observers.Update(truth.Measure(k, Vec3::Zero()));
    EXPECT_EQ(static_cast<int>(evidence.hypotheses.size()), bank.size());
    for (int h = 0; h < bank.size(); ++h) sum[h] += evidence.hypotheses[h].log_likelihood;
  }
  return sum;
}

// On data from a line-k model the line-k filter has a higher summed log-likelihood than
// the intact one, and on intact data the intact filter beats the line-6 one. 300 s from
// the origin. The evidence comes from the first minutes: a parted line is, to a wrong
// filter, a constant force that its bias b (stationary spread 1 MN) can take up at a prior
// cost of about (3.5 MN / 1 MN)^2 / 2 = 6 nats, after which only the 1/8 change in
// stiffness separates the models. Over 6 seeds x 8 lines the margins were 47 of 48
// positive, median about 12 nats, which is why this is a pairwise check on fixed seeds and
// not a claim that the true hypothesis is the best of all nine on every realisation.
TEST(EkfLikelihoodTest, TrueHypothesisBeatsTheAlternative) {
  struct Case {
    int truth, other;
    std::uint64_t seed;
  };
  for (const Case& c : {Case{6, 0, 27}, Case{0, 6, 21}, Case{7, 0, 28}, Case{8, 0, 29}}) {
    const std::vector<double> sum = SummedLogLikelihood(c.truth, c.seed, 300);
    EXPECT_GT(sum[c.truth] - sum[c.other], 2.0) << "truth " << c.truth << " vs " << c.other;
  }
}

// The filter's transition matrix is the exact Jacobian of its RK4 step: central
// differences of the step agree to 1e-6 of each column's scale.
TEST(EkfModelTest, TransitionIsTheJacobianOfTheStep) {
  const HypothesisEkf filter(SeedBank().mooring(6), SeedLowFrequencyModel(), Mat3::Zero());
  HypothesisEkf::LfState x;
  x << 20.0, -35.0, 0.4, 2e5, -1e5, 3e6, 0.3, -0.2, 0.004;
  const Vec3 tau(1e5, -2e5, 1e6);
  HypothesisEkf::LfMatrix Phi, A;
  filter.LowFrequencyStep(x, tau, 0.5, &Phi);
  filter.LowFrequencyDerivative(x, tau, &A);
  const double steps[9] = {1e-3, 1e-3, 1e-6, 1.0, 1.0, 100.0, 1e-5, 1e-5, 1e-7};
  for (int j = 0; j < 9; ++j) {
    HypothesisEkf::LfState plus = x, minus = x;
    plus(j) += steps[j];
    minus(j) -= steps[j];
    const HypothesisEkf::LfState fd_step = (filter.LowFrequencyStep(plus, tau, 0.5, nullptr) -
                                            filter.LowFrequencyStep(minus, tau, 0.5, nullptr)) /
                                           (2.0 * steps[j]);
    const HypothesisEkf::LfState fd_rate = (filter.LowFrequencyDerivative(plus, tau, nullptr) -
                                            filter.LowFrequencyDerivative(minus, tau, nullptr)) /
                                           (2.0 * steps[j]);
    for (int i = 0; i < 9; ++i) {
      const double scale_step = Phi.col(j).cwiseAbs().maxCoeff();
      const double scale_rate = A.col(j).cwiseAbs().maxCoeff();
      EXPECT_NEAR(Phi(i, j), fd_step(i), 1e-6 * scale_step) << "Phi(" << i << "," << j << ")";
      EXPECT_NEAR(A(i, j), fd_rate(i), 1e-6 * scale_rate + 1e-300) << "A(" << i << "," << j << ")";
    }
  }
}

/// A filter already running for 20 s on a still vessel at `eta`.
HypothesisEkf WarmFilter(const QuasiStaticMooring& mooring, const Vec3& eta) {
  return testing::Warm(HypothesisEkf(mooring, SeedLowFrequencyModel(), Mat3::Zero()), eta);
}

// A missing channel drops out of the likelihood: dimension 2, and the log-likelihood is
// the 2-D Gaussian of the valid innovation under the valid block of S.
TEST(EkfMissingChannelTest, DimensionAndLikelihoodFollowTheValidChannels) {
  const QuasiStaticMooring& mooring = SeedBank().mooring(0);
  HypothesisEkf filter = WarmFilter(mooring, Vec3::Zero());
  Observation obs;
  obs.t = 21.0;
  obs.pose = Vec3(0.3, 9.0, -0.05);  // y is garbage and flagged invalid
  obs.valid = {true, false, true};
  const HypothesisEvidence e = filter.Update(obs);
  EXPECT_EQ(e.dimension, 2);
  EXPECT_EQ(e.innovation.y(), 0.0);
  Eigen::Matrix2d S;
  S << e.covariance(0, 0), e.covariance(0, 2), e.covariance(2, 0), e.covariance(2, 2);
  const Eigen::Vector2d v(e.innovation.x(), e.innovation.z());
  const double expected =
      -0.5 * (v.dot(S.inverse() * v) + std::log(S.determinant()) + 2.0 * std::log(2.0 * kPi));
  EXPECT_NEAR(e.log_likelihood, expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(filter.normalised_innovation_squared(), v.dot(S.inverse() * v), 1e-9);
  // The garbage y did not move the estimate.
  EXPECT_LT(std::abs(filter.pose().y()), 0.1);

  // Nothing valid: predicted only, dimension 0, likelihood 0 (log of an empty product).
  obs.t = 22.0;
  obs.valid = {false, false, false};
  const double variance_before = filter.covariance()(HypothesisEkf::kPose, HypothesisEkf::kPose);
  const HypothesisEvidence none = filter.Update(obs);
  EXPECT_EQ(none.dimension, 0);
  EXPECT_EQ(none.log_likelihood, 0.0);
  EXPECT_DOUBLE_EQ(filter.time(), 22.0);
  EXPECT_GT(filter.covariance()(HypothesisEkf::kPose, HypothesisEkf::kPose), variance_before);

  // The first observation only initialises, and only once all channels are there.
  testing::ExpectInitialisesOnACompleteObservation(
      HypothesisEkf(mooring, SeedLowFrequencyModel(), Mat3::Zero()));
}

// Heading across +-pi: a vessel at heading 180 deg whose gyro reports values on both sides
// of the branch cut. The innovation is wrapped, so it stays small, and the estimate stays
// in (-pi, pi]. No mooring (a free vessel): the seed case's body-fixed turret would make 180
// deg an unstable equilibrium.
TEST(EkfHeadingWrapTest, InnovationWrapsAcrossPi) {
  const QuasiStaticMooring no_lines;
  HypothesisEkf filter = WarmFilter(no_lines, Vec3(0.0, 0.0, kPi - 0.01));
  testing::ExpectHeadingWrapsAcrossPi(filter, [](const HypothesisEkf& f, int k) {
    EXPECT_LT(f.normalised_innovation_squared(), 20.0) << "t " << k;
  });
  // Own-model data near 180 deg, wrapped: still consistent (500 samples: mean 3 +- 0.11,
  // bound +-3.3 sigma).
  const RunStatistics stats = RunConsistency(no_lines, 31, 500, false, Vec3(5.0, -3.0, kPi));
  EXPECT_GT(stats.mean_nis, 2.64);
  EXPECT_LT(stats.mean_nis, 3.36);
}

TEST(EkfInputTest, BadParametersNameTheField) {
  EkfOptions options;
  options.bias_std = Vec3(1e5, -1.0, 1e7);
  try {
    Validate(options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ekf.bias_std[2] = -1"), std::string::npos) << e.what();
  }
  options = {};
  options.max_substep = 0.0;
  EXPECT_THROW(HypothesisEkf(QuasiStaticMooring(), SeedLowFrequencyModel(), Mat3::Zero(), options),
               InputError);
  LowFrequencyModel singular = SeedLowFrequencyModel();
  singular.mass(2, 2) = 0.0;
  EXPECT_THROW(HypothesisEkf(QuasiStaticMooring(), singular, Mat3::Zero()), InputError);

  // Time must advance; a valid channel must be finite.
  testing::ExpectBadObservationsThrow(WarmFilter(QuasiStaticMooring(), Vec3::Zero()));
}

// With use_thrust_command = false the command is ignored: two filters fed the same poses
// with different commands agree exactly.
TEST(EkfThrustTest, CommandCanBeIgnored) {
  EkfOptions options;
  options.use_thrust_command = false;
  HypothesisEkf a(SeedBank().mooring(0), SeedLowFrequencyModel(), Mat3::Zero(), options);
  HypothesisEkf b(SeedBank().mooring(0), SeedLowFrequencyModel(), Mat3::Zero(), options);
  HypothesisEkf used(SeedBank().mooring(0), SeedLowFrequencyModel(), Mat3::Zero());
  testing::FeedDifferentCommands(a, b, used);
  EXPECT_GT((used.state() - a.state()).segment<3>(HypothesisEkf::kVelocity).norm(), 1e-3);
}

// The bank runs one filter per hypothesis and hands back evidence for each; Reset starts
// every filter over.
TEST(ObserverBankTest, OneFilterPerHypothesis) {
  const HypothesisBank& bank = SeedBank();
  EkfOptions options;
  options.mooring_damping_ratio = Vec3(0.1, 0.1, 0.1);
  ObserverBank observers(bank, SeedLowFrequencyModel(), options);
  testing::ExpectEvidenceForEachHypothesis(observers, 5);
  observers.Reset();
  EXPECT_FALSE(observers.filter(3).initialised());
}

// Without mixing the bank's probabilities are the plain Bayesian posterior of its filters'
// likelihoods from a uniform prior: softmax of the summed log-likelihoods.
TEST(ObserverBankTest, UnmixedProbabilitiesAreTheBayesianPosterior) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  ObserverBank observers(bank, model, options,
                         ObserverBankOptions{.switch_rate = 0.0, .sensor_checks = {}});
  OwnModelSimulator truth(bank.mooring(7), model, options, 31, Vec3::Zero());
  std::vector<double> sum(bank.size(), 0.0);
  for (int k = 0; k <= 40; ++k) {
    if (k > 0) truth.Advance(1.0, Vec3::Zero());
    const Evidence& e = observers.Update(truth.Measure(k, Vec3::Zero()));
    EXPECT_FALSE(e.nominal.has_value());
    for (int h = 0; h < bank.size(); ++h) sum[h] += e.hypotheses[h].log_likelihood;
  }
  const double top = *std::max_element(sum.begin(), sum.end());
  double total = 0.0;
  for (double v : sum) total += std::exp(v - top);
  for (int h = 0; h < bank.size(); ++h) {
    EXPECT_NEAR(observers.probabilities()[h], std::exp(sum[h] - top) / total, 1e-12) << h;
  }
}

struct BreakRun {
  double gain = 0.0;          // sum of log-likelihood(line k) - log-likelihood(intact), 60 s
  double probability = 0.0;   // the bank's probability of line k 60 s after the break
  double worst_before = 1.0;  // the lowest probability of intact in the 200 s before it
  double nominal_nis = 0.0;   // mean NIS of the unmixed intact filter over the 60 s
};

/// Own-model truth, intact for 600 s, then line `line` parts; a bank with `switch_rate`.
BreakRun RunBreak(int line, double switch_rate, std::uint64_t seed) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  ObserverBank observers(bank, model, options,
                         ObserverBankOptions{.switch_rate = switch_rate, .sensor_checks = {}});
  OwnModelSimulator truth(bank.mooring(0), model, options, seed, Vec3::Zero());
  BreakRun run;
  int nominal_samples = 0;
  for (int k = 0; k <= 660; ++k) {
    if (k == 600) truth.SetMooring(bank.mooring(line));
    if (k > 0) truth.Advance(1.0, Vec3::Zero());
    const Evidence& e = observers.Update(truth.Measure(k, Vec3::Zero()));
    double p_sum = 0.0;
    for (double p : observers.probabilities()) {
      EXPECT_GT(p, 0.0);
      p_sum += p;
    }
    EXPECT_NEAR(p_sum, 1.0, 1e-12);
    if (k >= 400 && k < 600)
      run.worst_before = std::min(run.worst_before, observers.probabilities()[0]);
    if (k > 600) {
      run.gain += e.hypotheses[line].log_likelihood - e.hypotheses[0].log_likelihood;
      if (e.nominal) {
        const HypothesisEvidence& n = *e.nominal;
        run.nominal_nis += n.innovation.dot(n.covariance.ldlt().solve(n.innovation));
        ++nominal_samples;
      }
    }
  }
  run.probability = observers.probabilities()[line];
  if (nominal_samples > 0) run.nominal_nis /= nominal_samples;
  return run;
}

// Why the bank mixes (ObserverBank): independent filters let each failure hypothesis's bias
// carry its missing line's pretension, so a break moves every bias alike and the evidence
// is only the stiffness change. The mixing bank keeps the failure filters on the intact
// estimate while intact holds, so the parted line's filter is the only one that predicts
// the drift. On own-model data (intact 600 s, then the line parts), for lines 6 and 3:
// the mixing bank gains at least 10 nats more for the parted line in the 60 s after the
// break than the independent bank, and ends with probability > 0.9 on it; before the break
// it never lets intact fall below 0.5. The unmixed nominal filter (for the GLR) shows the
// break as inconsistency: mean NIS over the 60 s above 6, twice its 3 (the 60-sample mean
// of a consistent filter is 3 +- 0.32). Measured: gains 23.4 / 27.4 nats against 9.4 /
// 15.3, probabilities 0.92 / 0.97, intact never below 0.60, NIS 8.5 / 8.2.
TEST(ObserverBankTest, MixingFindsALineThatPartsMidRun) {
  for (const int line : {6, 3}) {
    const BreakRun independent = RunBreak(line, 0.0, 40 + line);
    const BreakRun mixing = RunBreak(line, 1e-2, 40 + line);
    EXPECT_GT(mixing.gain, independent.gain + 10.0) << line;
    EXPECT_GT(mixing.probability, 0.9) << line;
    EXPECT_GT(mixing.worst_before, 0.5) << line;
    EXPECT_GT(mixing.nominal_nis, 6.0) << line;
  }
}

// The load evidence is the intact filter's bias with, per hypothesis, the load its failed
// lines exert at that filter's pose (unmixed bank: filter 0 is the intact filter).
TEST(ObserverBankTest, LoadEvidenceIsTheIntactBiasAndTheFailedLinesLoad) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  ObserverBank observers(bank, model, options,
                         ObserverBankOptions{.switch_rate = 0.0, .sensor_checks = {}});
  OwnModelSimulator truth(bank.mooring(0), model, options, 17, Vec3(3.0, -2.0, 0.02));
  for (int k = 0; k <= 30; ++k) {
    if (k > 0) truth.Advance(1.0, Vec3::Zero());
    const Evidence& e = observers.Update(truth.Measure(k, Vec3::Zero()));
    ASSERT_TRUE(e.load.has_value());
    const HypothesisEkf& intact = observers.filter(0);
    EXPECT_EQ(e.load->bias, intact.bias());
    ASSERT_EQ(e.load->line_load.size(), static_cast<std::size_t>(bank.size()));
    EXPECT_EQ(e.load->line_load[0], Vec3::Zero());
    for (int h = 1; h < bank.size(); ++h) {
      Vec3 expected = Vec3::Zero();
      for (int id : bank.failed_lines(h))
        expected += bank.mooring(0).LineLoad(id - 1, intact.pose());
      EXPECT_LT((e.load->line_load[h] - expected).norm(), 1e-9 * expected.norm()) << h;
    }
  }
}

// What the force-deficit detector relies on: when a line parts, the intact filter's bias
// settles by minus that line's load. Own-model truth (its bias a random process of its
// own), line 6 or 3 parts at 600 s; over 200-300 s after the break the estimate minus the
// truth's bias, against its mean over the 100 s before the break, is -line_load within
// 15 % of the line's load (the estimate's own error: ~0.2 MN of the 3.5 MN).
TEST(ObserverBankTest, AfterABreakTheIntactBiasSettlesByMinusTheLinesLoad) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const EkfOptions options;
  for (const int line : {6, 3}) {
    ObserverBank observers(bank, model, options,
                           ObserverBankOptions{.switch_rate = 1e-2, .sensor_checks = {}});
    OwnModelSimulator truth(bank.mooring(0), model, options, 60 + line, Vec3::Zero());
    Eigen::Vector2d before = Eigen::Vector2d::Zero();
    Eigen::Vector2d after = Eigen::Vector2d::Zero();
    Eigen::Vector2d load = Eigen::Vector2d::Zero();
    for (int k = 0; k <= 900; ++k) {
      if (k == 600) truth.SetMooring(bank.mooring(line));
      if (k > 0) truth.Advance(1.0, Vec3::Zero());
      const Evidence& e = observers.Update(truth.Measure(k, Vec3::Zero()));
      const Eigen::Vector2d error = e.load->bias.head<2>() - truth.state().segment<2>(9);
      if (k >= 500 && k < 600) before += error / 100.0;
      if (k >= 800) {
        after += error / 101.0;
        load += e.load->line_load[line].head<2>() / 101.0;
      }
    }
    EXPECT_LT((after - before + load).norm(), 0.15 * load.norm()) << "line " << line;
  }
}

TEST(ObserverBankTest, BadSwitchRateNamesTheField) {
  try {
    ObserverBank observers(SeedBank(), SeedLowFrequencyModel(), EkfOptions{},
                           ObserverBankOptions{.switch_rate = -1.0, .sensor_checks = {}});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("detection.switch_rate = -1"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace moorsim::detectors
