// Every detector on synthetic evidence whose truth is known, and the battery every
// registered detector type runs through (one battery per plugin family: a new
// detector joins it by its registry row alone).
//
// The synthetic bank: 9 hypotheses (0 intact, 1-8 single-line failures) whose models differ
// only by the pose offset they predict, m_0 = 0 and m_k = L (delta u_k), where S = L L' is
// the innovation covariance all share and the u_k are unit vectors 45 deg apart in the
// horizontal plane with a yaw part, like the push of the seed case's eight lines. The true pose
// is y = m_truth + e with e ~ N(0, S); hypothesis k's innovation is y - m_k and its
// log-likelihood the exact Gaussian one. So the true hypothesis's innovations are white
// N(0, S) and every other one's have mean m_truth - m_k, of whitened size
// delta |u_truth - u_k| (>= 0.77 delta between neighbours).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "core/angles.h"
#include "core/random.h"
#include "detectors/dht.h"
#include "detectors/glr.h"
#include "detectors/mle.h"
#include "detectors/registry.h"

// Counts the operator-new allocations of this test binary, to check that the detectors'
// sample updates allocate nothing. (Eigen allocates through malloc, not operator new; the
// detectors use fixed-size Eigen types only in their updates.)
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// noinline: GCC would otherwise see free() on a pointer from operator new after inlining.
[[gnu::noinline]] void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// The other plain forms must come from the same allocator, or ASan reports a mismatch when
// the library's nothrow/array new meets these deletes (std::stable_sort uses nothrow new).
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
[[gnu::noinline]] void* operator new[](std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace moorsim::detectors {
namespace {

// The TAPM thesis's MLE (forgetting 0.999, and the hold and margin these tests were written
// for); MleOptions' defaults are tuned for the coupled plant instead (detectors/mle.h).
constexpr MleOptions kSeedMle{.forgetting_factor = 0.999, .hold = 30.0, .margin = 10.0};

constexpr int kHypotheses = 9;
constexpr double kDt = 0.1;  // [s] detector sample period in these tests (10 Hz)

class SyntheticBank {
 public:
  SyntheticBank(double delta, std::uint64_t seed)
      : noise_x_(RandomStream::Derive(seed, "bank.x")),
        noise_y_(RandomStream::Derive(seed, "bank.y")),
        noise_psi_(RandomStream::Derive(seed, "bank.psi")) {
    // x, y [m] and psi [rad]: GNSS-like 0.1 m and gyro-like 0.01 rad noise, correlated.
    Mat3 a;
    a << 0.10, 0.00, 0.000,  //
        0.03, 0.08, 0.000,   //
        0.002, -0.001, 0.01;
    covariance_ = a * a.transpose();
    cholesky_ = covariance_.llt().matrixL();
    information_ = covariance_.inverse();
    log_normaliser_ = -0.5 * std::log(covariance_.determinant()) - 1.5 * std::log(2.0 * kPi);
    offsets_.assign(kHypotheses, Vec3::Zero());
    for (int k = 1; k < kHypotheses; ++k) offsets_[k] = cholesky_ * (delta * Direction(k));
    evidence_.hypotheses.resize(kHypotheses);
  }

  /// u_k: line k pushes the vessel toward 45 (k - 1) deg; lines k and k + 4 are opposite.
  static Vec3 Direction(int k) {
    const double theta = kPi / 4.0 * (k - 1);
    return Vec3(std::cos(theta), std::sin(theta), 0.3 * std::sin(theta)).normalized();
  }
  /// s_k, the whitened mean of the intact innovation while hypothesis k holds.
  Vec3 Signature(int k) const {
    return cholesky_.triangularView<Eigen::Lower>().solve(offsets_[k]);
  }
  std::vector<Vec3> Signatures() const {
    std::vector<Vec3> s;
    for (int k = 1; k < kHypotheses; ++k) s.push_back(Signature(k));
    return s;
  }
  const Mat3& covariance() const { return covariance_; }

  /// The evidence at time t when hypothesis `truth` holds; reuses one Evidence object, so
  /// drawing a sample allocates nothing.
  const Evidence& Sample(double t, int truth) {
    const Vec3 z(noise_x_.Normal(), noise_y_.Normal(), noise_psi_.Normal());
    const Vec3 y = offsets_[truth] + cholesky_ * z;
    evidence_.t = t;
    for (int k = 0; k < kHypotheses; ++k) {
      HypothesisEvidence& e = evidence_.hypotheses[k];
      e.innovation = y - offsets_[k];
      e.covariance = covariance_;
      e.log_likelihood = log_normaliser_ - 0.5 * e.innovation.dot(information_ * e.innovation);
      e.dimension = 3;
    }
    return evidence_;
  }

 private:
  RandomStream noise_x_;
  RandomStream noise_y_;
  RandomStream noise_psi_;
  Mat3 covariance_;
  Mat3 cholesky_;
  Mat3 information_;
  double log_normaliser_ = 0.0;
  std::vector<Vec3> offsets_;
  Evidence evidence_;
};

// ---------------------------------------------------------------------------------------
// DHT

TEST(DhtSyntheticTest, PosteriorOfTheTrueHypothesisGoesToOneAndStaysADistribution) {
  // Hassani et al. 2018, Theorem 1, at every sample: h_k >= floor and sum h_k = 1. The sum is
  // formed from 9 terms each rounded once after the floor's scaling, so 1e-12 is ~1000 ulp of
  // slack. Theorem 2: the true hypothesis's posterior -> 1. With delta = 1 the nearest wrong
  // hypothesis loses on average 0.5 * 0.77^2 = 0.29 nats per sample, so from the uniform
  // prior the log odds need ~ ln(999 * 8) / 0.29 = 31 samples to reach 0.999; 200 is ample.
  // Afterwards a wrong hypothesis sits near the floor (log odds -20.7) and drifts down, so
  // the true one stays above 0.999.
  for (const int truth : {0, 3, 6}) {
    SCOPED_TRACE("truth " + std::to_string(truth));
    SyntheticBank bank(1.0, 11 + truth);
    Dht dht;
    dht.Reset(kHypotheses);
    int first_confident = -1;
    for (int i = 0; i < 3000; ++i) {
      const Verdict& v = dht.Step(bank.Sample(i * kDt, truth));
      double sum = 0.0;
      for (const double h : v.score) {
        ASSERT_GE(h, 1e-9);
        sum += h;
      }
      ASSERT_NEAR(sum, 1.0, 1e-12) << "sample " << i;
      if (first_confident < 0 && v.score[truth] > 0.999) first_confident = i;
      if (i >= 200) {
        ASSERT_GT(v.score[truth], 0.999) << "sample " << i;
        ASSERT_EQ(v.hypothesis, truth);
      }
    }
    EXPECT_GE(first_confident, 0);
    EXPECT_LE(first_confident, 200);
  }
}

TEST(DhtSyntheticTest, AlarmsOnAFailureAfterTheHoldAndNeverOnIntactData) {
  // Line 6 fails at 200 s. Hypothesis 6 starts at the floor, log odds ln(1e-9) = -20.7
  // against the intact one, and gains 0.5 delta^2 = 0.5 nats a sample on it (its
  // neighbours, also at the floor, fall behind it by 0.29 a sample): h_6 >= 0.99 after
  // about (20.7 + 4.6) / 0.5 = 51 samples (5 s at 10 Hz), then the 10 s hold: alarm
  // expected near 215 s. Bound (210, 240]: 210 = failure + hold.
  SyntheticBank bank(1.0, 5);
  Dht dht;
  dht.Reset(kHypotheses);
  double alarm_time = -1.0;
  for (int i = 0; i < 3000; ++i) {
    const double t = i * kDt;
    const Verdict& v = dht.Step(bank.Sample(t, t < 200.0 ? 0 : 6));
    if (t < 200.0) {
      ASSERT_FALSE(v.alarm) << "t = " << t;
    }
    if (v.alarm && alarm_time < 0.0) {
      alarm_time = t;
      EXPECT_EQ(v.hypothesis, 6);
    }
  }
  EXPECT_GT(alarm_time, 210.0);
  EXPECT_LE(alarm_time, 240.0);
}

// ---------------------------------------------------------------------------------------
// MLE

TEST(MleSyntheticTest, RanksTheTrueModelFirst) {
  for (const int truth : {0, 2, 7}) {
    SCOPED_TRACE("truth " + std::to_string(truth));
    SyntheticBank bank(1.0, 21 + truth);
    Mle mle(kSeedMle);
    mle.Reset(kHypotheses);
    for (int i = 0; i < 2000; ++i) {
      const Verdict& v = mle.Step(bank.Sample(i * kDt, truth));
      // Each wrong model gains >= 0.29 nats a sample on average; after 100 samples the
      // lead is ~29 nats against a standard deviation of ~8.
      if (i >= 100) {
        ASSERT_EQ(v.hypothesis, truth) << "sample " << i;
      }
    }
    // Steady state: J_k - J_truth -> E[per-sample gap] / (1 - lambda) = 0.5 delta^2
    // |u_k - u_truth|^2 * 1000, i.e. 500 |u_k - u_truth|^2 nats (+- ~15 %, the noise of
    // ~1000 effective samples).
    const std::vector<double>& j = mle.negative_log_likelihood();
    for (int k = 0; k < kHypotheses; ++k) {
      if (k == truth) continue;
      const Vec3 du = (k == 0 ? Vec3::Zero() : SyntheticBank::Direction(k)) -
                      (truth == 0 ? Vec3::Zero() : SyntheticBank::Direction(truth));
      const double expected = 500.0 * du.squaredNorm() * (1.0 - std::pow(0.999, 2000));
      EXPECT_NEAR(j[k] - j[truth], expected, 0.2 * expected + 5.0) << "k " << k;
    }
  }
}

TEST(MleSyntheticTest, AlarmDelayIsTheForgettingMemory) {
  // After a long intact stretch J_6 - J_0 sits near +D (D = 500 delta^2 here, times
  // 1 - 0.999^2000 = 0.86 after 200 s). After line 6 fails, J_0 - J_6 grows by the same
  // 0.5 delta^2 a sample while the old gap decays as lambda^n: line 6 becomes the argmin
  // when lambda^n ~ 0.5 / 0.93, n ~ 620 samples (62 s), whatever delta is (the Gaussian
  // KL divergence is symmetric for equal covariances). Then the 30 s hold: alarm expected
  // near 292 s. Bound [270, 320].
  SyntheticBank bank(1.0, 8);
  Mle mle(kSeedMle);
  mle.Reset(kHypotheses);
  double alarm_time = -1.0;
  for (int i = 0; i < 4000; ++i) {
    const double t = i * kDt;
    const Verdict& v = mle.Step(bank.Sample(t, t < 200.0 ? 0 : 6));
    if (t < 200.0) {
      ASSERT_FALSE(v.alarm) << "t = " << t;
    }
    if (v.alarm && alarm_time < 0.0) {
      alarm_time = t;
      EXPECT_EQ(v.hypothesis, 6);
    }
  }
  EXPECT_GE(alarm_time, 270.0);
  EXPECT_LE(alarm_time, 320.0);
}

// ---------------------------------------------------------------------------------------
// GLR on the bank: signatures from the models, and the log-likelihood fallback.

TEST(GlrSyntheticTest, IsolatesTheFailedLineWithAndWithoutSignatures) {
  // delta = 1.5: over a full window the fallback's 2 (sum LL_truth - sum LL_neighbour) has
  // mean 2 * 50 * 0.5 * 1.5^2 * 0.59 = 66 and standard deviation 16, a 4-sigma lead.
  for (const bool with_signatures : {true, false}) {
    SCOPED_TRACE(with_signatures ? "signatures" : "log-likelihood fallback");
    for (const int truth : {1, 4, 5, 8}) {
      SyntheticBank bank(1.5, 31 + truth);
      Glr glr;
      glr.Reset(kHypotheses);
      if (with_signatures) glr.SetSignatures(bank.Signatures());
      for (int i = 0; i < 600; ++i) {
        const double t = i * kDt;
        const Verdict& v = glr.Step(bank.Sample(t, t < 30.0 ? 0 : truth));
        if (t < 30.0) {
          ASSERT_FALSE(v.alarm);
        }
      }
      // 30 s after the break the window holds only failed samples.
      const Verdict& v = glr.Step(bank.Sample(60.0, truth));
      EXPECT_TRUE(v.alarm);
      EXPECT_EQ(v.hypothesis, truth);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Log space

TEST(LogSpaceTest, LikelihoodsOfMinus1e4NatsDoNotUnderflow) {
  // exp(-1e4) is 0 in double; the posterior must still follow the differences: with
  // log-likelihoods -1e4 - d_k the one-step posterior from a uniform prior is
  // softmax(-d), and J = 1e4 + d.
  Evidence evidence;
  evidence.hypotheses.resize(3);
  const double d[3] = {2.0, 0.0, 1.0};
  for (int k = 0; k < 3; ++k) evidence.hypotheses[k].log_likelihood = -1e4 - d[k];
  DhtOptions options;
  options.floor = 1e-12;
  Dht dht(options);
  dht.Reset(3);
  const Verdict dv = dht.Update(evidence);
  const double z = std::exp(-2.0) + 1.0 + std::exp(-1.0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(dv.score[k], std::exp(-d[k]) / z, 1e-14);
  EXPECT_EQ(dv.hypothesis, 1);

  Mle mle(kSeedMle);
  mle.Reset(3);
  const Verdict mv = mle.Update(evidence);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(mv.score[k], 1e4 + d[k]);
  EXPECT_EQ(mv.hypothesis, 1);
}

// ---------------------------------------------------------------------------------------
// The battery: every registered type, built by name with its defaults.

class DetectorBattery : public ::testing::TestWithParam<std::string_view> {
 protected:
  std::unique_ptr<Detector> Make(const std::map<std::string, double>& parameters = {},
                                 bool white_residuals = true) {
    DetectorSpec spec;
    spec.type = std::string(GetParam());
    spec.label = spec.type;
    spec.parameters = parameters;
    // The synthetic residuals here are white: the GLR gets the white-residual threshold
    // (chi-square at 1e-6 per sample) and no hold, not the plant-tuned defaults.
    if (white_residuals && spec.type == "glr" && parameters.empty()) {
      spec.parameters = {{"false_alarm_probability", 1e-6}, {"hold", 0.0}};
    }
    return MakeDetector(spec, "detectors[1]");
  }
};

TEST_P(DetectorBattery, NoAlarmOnLongIntactRun) {
  // 20 000 samples (2000 s at 10 Hz) of white intact residuals: the DHT and MLE alarms
  // need a failure hypothesis to win for 10 / 30 s, which the drift against it forbids;
  // the GLR's per-sample false-alarm probability is <= 1e-6 (union bound), 2 % per run.
  std::unique_ptr<Detector> detector = Make();
  EXPECT_EQ(detector->type(), GetParam());
  SyntheticBank bank(1.0, 41);
  detector->Reset(kHypotheses);
  int alarms = 0;
  for (int i = 0; i < 20000; ++i) {
    const Verdict v = detector->Update(bank.Sample(i * kDt, 0));
    ASSERT_EQ(v.score.size(), static_cast<std::size_t>(kHypotheses));
    alarms += v.alarm ? 1 : 0;
  }
  EXPECT_EQ(alarms, 0);
}

TEST_P(DetectorBattery, DetectsAndIsolatesAStep) {
  // Line 6 fails at 200 s; every type must declare it within 150 s (the MLE, slowest, needs
  // ~92 s, see MleSyntheticTest) and name line 6 at the end. delta = 1.5 as in
  // GlrSyntheticTest, for the GLR's log-likelihood isolation.
  std::unique_ptr<Detector> detector = Make();
  if (detector->NeedsLoadEvidence()) {
    GTEST_SKIP() << "the synthetic bank gives residuals, no load evidence (deficit_test.cc "
                    "steps a bias instead)";
  }
  SyntheticBank bank(1.5, 43);
  detector->Reset(kHypotheses);
  double alarm_time = -1.0;
  Verdict v;
  for (int i = 0; i < 3500; ++i) {
    const double t = i * kDt;
    v = detector->Update(bank.Sample(t, t < 200.0 ? 0 : 6));
    if (t < 200.0) {
      ASSERT_FALSE(v.alarm) << "t = " << t;
    }
    if (v.alarm && alarm_time < 0.0) alarm_time = t;
  }
  EXPECT_GT(alarm_time, 200.0);
  EXPECT_LT(alarm_time, 350.0);
  EXPECT_TRUE(v.alarm);
  EXPECT_EQ(v.hypothesis, 6);
}

TEST_P(DetectorBattery, ResetStartsOver) {
  std::unique_ptr<Detector> detector = Make();
  std::vector<Verdict> first;
  for (int pass = 0; pass < 2; ++pass) {
    SyntheticBank bank(1.0, 47);  // the same samples in both passes
    detector->Reset(kHypotheses);
    for (int i = 0; i < 1500; ++i) {
      const double t = i * kDt;
      const Verdict v = detector->Update(bank.Sample(t, t < 60.0 ? 0 : 3));
      if (pass == 0) {
        first.push_back(v);
      } else {
        ASSERT_EQ(v.score, first[i].score) << "sample " << i;
        ASSERT_EQ(v.hypothesis, first[i].hypothesis);
        ASSERT_EQ(v.alarm, first[i].alarm);
      }
    }
  }
}

TEST_P(DetectorBattery, DefaultsGivenExplicitlyChangeNothing) {
  // Config round trip: a spec that states every default gives the same detector.
  std::map<std::string, double> defaults;
  for (const DetectorType& type : DetectorTable()) {
    if (type.name != GetParam()) continue;
    for (const DetectorParameter& p : type.parameters) {
      if (p.default_value) defaults[std::string(p.name)] = *p.default_value;
    }
  }
  std::unique_ptr<Detector> implicit = Make({}, false);
  std::unique_ptr<Detector> expl = Make(defaults, false);
  SyntheticBank bank_a(1.0, 53);
  SyntheticBank bank_b(1.0, 53);
  implicit->Reset(kHypotheses);
  expl->Reset(kHypotheses);
  for (int i = 0; i < 1500; ++i) {
    const double t = i * kDt;
    const int truth = t < 60.0 ? 0 : 2;
    const Verdict a = implicit->Update(bank_a.Sample(t, truth));
    const Verdict b = expl->Update(bank_b.Sample(t, truth));
    ASSERT_EQ(a.score, b.score);
    ASSERT_EQ(a.alarm, b.alarm);
  }
}

TEST_P(DetectorBattery, UpdateAllocatesOnlyTheReturnedScore) {
  // The interface returns the Verdict by value, so Update() costs exactly one allocation,
  // the copy of the score vector; the detectors' own work allocates nothing.
  std::unique_ptr<Detector> detector = Make();
  SyntheticBank bank(1.0, 59);
  detector->Reset(kHypotheses);
  Verdict v;
  for (int i = 0; i < 100; ++i) v = detector->Update(bank.Sample(i * kDt, 0));
  const long before = g_allocations.load();
  for (int i = 100; i < 1100; ++i) v = detector->Update(bank.Sample(i * kDt, i < 500 ? 0 : 4));
  EXPECT_EQ(g_allocations.load() - before, 1000);
}

INSTANTIATE_TEST_SUITE_P(Registered, DetectorBattery, ::testing::ValuesIn(DetectorTypes()),
                         [](const ::testing::TestParamInfo<std::string_view>& info) {
                           return std::string(info.param);
                         });

TEST(DetectorStepTest, StepAllocatesNothingAfterReset) {
  SyntheticBank bank(1.0, 61);
  Dht dht;
  Mle mle(kSeedMle);
  Glr glr;
  dht.Reset(kHypotheses);
  mle.Reset(kHypotheses);
  glr.Reset(kHypotheses);
  Glr glr_signatures;
  glr_signatures.Reset(kHypotheses);
  glr_signatures.SetSignatures(bank.Signatures());
  const long before = g_allocations.load();
  int alarms = 0;
  for (int i = 0; i < 2000; ++i) {
    const Evidence& e = bank.Sample(i * kDt, i < 1000 ? 0 : 5);
    alarms +=
        dht.Step(e).alarm + mle.Step(e).alarm + glr.Step(e).alarm + glr_signatures.Step(e).alarm;
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(alarms, 0);
}

}  // namespace
}  // namespace moorsim::detectors
