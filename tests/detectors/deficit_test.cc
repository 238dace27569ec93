// The force-deficit detector on synthetic load evidence: eight lines whose loads of 3.5 MN
// point at their anchors (the seed mooring's bearings), a bias that a parted line shifts by
// minus its load (approached with the intact filter's ~10 s time constant) and a slowly
// varying disturbance on top.
#include "detectors/deficit.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "detectors/alarm_history.h"

namespace moorsim::detectors {
namespace {

constexpr double kLineLoad = 3.5e6;  // [N]
constexpr int kBankSize = 9;         // intact + 8 lines

// Anchor bearings of the seed mooring (line 1 north, 2 east, 3 south, 4 west, 5-8 between).
constexpr double kBearingDeg[8] = {0, 90, 180, 270, 45, 135, 225, 315};

Vec3 LineLoad(int line) {
  const double bearing = kBearingDeg[line - 1] * kPi / 180.0;
  return Vec3(kLineLoad * std::cos(bearing), kLineLoad * std::sin(bearing), 0.0);
}

// A bias stream: environment b_env, a first-order (AR(1)) disturbance of standard deviation
// `std` and correlation time `correlation`, minus the load of every parted line (approached
// with time constant 10 s), plus any extra load the test adds.
class BiasStream {
 public:
  BiasStream(std::uint64_t seed, double std, double correlation)
      : x_(RandomStream::Derive(seed, "deficit.x")),
        y_(RandomStream::Derive(seed, "deficit.y")),
        std_(std),
        decay_(std::exp(-1.0 / correlation)) {
    evidence_.hypotheses.resize(kBankSize);
    evidence_.load.emplace();
    evidence_.load->line_load.assign(kBankSize, Vec3::Zero());
    for (int k = 1; k < kBankSize; ++k) evidence_.load->line_load[k] = LineLoad(k);
    disturbance_ = std * Vec3(x_.Normal(), y_.Normal(), 0.0);
  }

  void Part(int line) { parted_.push_back(line); }
  /// Adds a slowly varying wave drift gain * E, E = wave-motion energy [m^2] = E0 exp(u),
  /// u first-order with standard deviation 0.7 and correlation 40 s; the wave motion the
  /// evidence carries is sqrt(E) along x.
  void AddDrift(const Vec3& gain, double mean_energy) {
    drift_gain_ = gain;
    mean_energy_ = mean_energy;
  }
  /// Turns the wave motion's direction: theta first-order about 0 with standard deviation
  /// `std` [rad] and correlation 120 s, the motion sqrt(E) (cos theta, sin theta), and
  /// adds the horizontal drift `gain` (x^2, y^2, xy) [N/m^2] on top of AddDrift's.
  void TurnWaveMotion(double std, const Deficit::Gain& gain) {
    direction_std_ = std;
    directional_gain_ = gain;
  }
  /// One sample at t (1 s apart) with `extra` added to the bias.
  const Evidence& Sample(double t, const Vec3& extra = Vec3::Zero()) {
    const double innovation = std_ * std::sqrt(1.0 - decay_ * decay_);
    disturbance_ = decay_ * disturbance_ + innovation * Vec3(x_.Normal(), y_.Normal(), 0.0);
    Vec3 deficit = Vec3::Zero();
    for (int line : parted_) deficit += LineLoad(line);
    lag_ += (deficit - lag_) * (1.0 - std::exp(-1.0 / 10.0));
    evidence_.t = t;
    evidence_.load->bias = environment_ + disturbance_ - lag_ + extra;
    if (mean_energy_ > 0.0) {
      const double decay = std::exp(-1.0 / 40.0);
      envelope_ =
          decay * envelope_ + 0.7 * std::sqrt(1.0 - decay * decay) * envelope_stream_.Normal();
      const double energy = mean_energy_ * std::exp(envelope_);
      const double turn = std::exp(-1.0 / 120.0);
      direction_ = turn * direction_ +
                   direction_std_ * std::sqrt(1.0 - turn * turn) * direction_stream_.Normal();
      const double x = std::sqrt(energy) * std::cos(direction_);
      const double y = std::sqrt(energy) * std::sin(direction_);
      evidence_.load->bias += drift_gain_ * energy;
      evidence_.load->bias.head<2>() += directional_gain_ * Vec3(x * x, y * y, x * y);
      evidence_.load->wave_motion = Vec3(x, y, 0.0);
    }
    return evidence_;
  }

 private:
  RandomStream x_, y_;
  double std_;
  double decay_;
  Vec3 environment_ = Vec3(-8e5, 6e5, 2e7);
  RandomStream envelope_stream_ = RandomStream::Derive(0, "deficit.envelope");
  Vec3 drift_gain_ = Vec3::Zero();
  double mean_energy_ = 0.0;
  double envelope_ = 0.0;
  RandomStream direction_stream_ = RandomStream::Derive(0, "deficit.direction");
  double direction_std_ = 0.0;
  double direction_ = 0.0;
  Deficit::Gain directional_gain_ = Deficit::Gain::Zero();
  Vec3 disturbance_ = Vec3::Zero();
  Vec3 lag_ = Vec3::Zero();
  std::vector<int> parted_;
  Evidence evidence_;
};

// Runs the detector over `seconds` samples of `stream`; `at(t)` may part lines or return a
// load to add at that sample.
template <typename At>
AlarmHistory RunDetector(Deficit& deficit, BiasStream& stream, int seconds, At at) {
  deficit.Reset(kBankSize);
  AlarmHistory history;
  for (int t = 0; t <= seconds; ++t) {
    const Verdict& v = deficit.Step(stream.Sample(t, at(t)));
    history.Update(t, v.alarm, v.hypothesis);
  }
  return history;
}

TEST(Deficit, APartedLineIsNamedWithinAMinuteAndStaysNamed) {
  // 0.3 MN of disturbance with a 60 s correlation: the window mean's C ~ (0.3 MN)^2 + floor^2,
  // d'C^-1 d ~ 120, m ~ 100 samples per value, so a full deficit adds ~0.6 nats a sample:
  // 8 nats ~15 s after the 10 s approach and the 15 s window.
  for (int line = 1; line <= 8; ++line) {
    SCOPED_TRACE("line " + std::to_string(line));
    Deficit deficit;
    BiasStream stream(static_cast<std::uint64_t>(line), 3e5, 60.0);
    const AlarmHistory history = RunDetector(deficit, stream, 2000, [&](int t) {
      if (t == 400) stream.Part(line);
      return Vec3::Zero();
    });
    EXPECT_EQ(history.OnsetsBefore(400.0), 0);
    ASSERT_EQ(history.events().size(), 1u);  // one onset, no revision, no end
    EXPECT_EQ(history.events()[0].hypothesis, line);
    EXPECT_GT(history.events()[0].time, 400.0);
    EXPECT_LT(history.events()[0].time, 460.0);
    EXPECT_TRUE(history.alarm());
    EXPECT_EQ(history.hypothesis(), line);
  }
}

TEST(Deficit, TheLeadUndoesTheFiltersBiasLag) {
  // The stream's bias approaches a deficit with a first-order lag of 10 s, which the lead
  // b + T db/dt with T = 10 s inverts (up to the sampling: the exact inverse of the 1 s
  // discrete lag is T = 9.5 s). The compensated bias carries the disturbance's increments
  // times T as well; the learned C and m take them in. Over the eight lines: no alarm
  // before the break either way, every line named, and with the lead at least 10 s sooner
  // on average, within 30 s of every break.
  double delay_plain = 0.0;
  double delay_lead = 0.0;
  for (const double lead : {0.0, 10.0}) {
    for (int line = 1; line <= 8; ++line) {
      SCOPED_TRACE("line " + std::to_string(line) + ", lead " + std::to_string(lead));
      DeficitOptions options;
      options.confirm = 0.0;  // one stage: the lead on its own
      options.lead = lead;
      Deficit deficit(options);
      BiasStream stream(static_cast<std::uint64_t>(line), 3e5, 60.0);
      const AlarmHistory history = RunDetector(deficit, stream, 1000, [&](int t) {
        if (t == 400) stream.Part(line);
        return Vec3::Zero();
      });
      EXPECT_EQ(history.OnsetsBefore(400.0), 0);
      const std::optional<double> named = history.FirstNamed(line, 400.0);
      ASSERT_TRUE(named.has_value());
      EXPECT_EQ(history.hypothesis(), line);
      (lead > 0.0 ? delay_lead : delay_plain) += (*named - 400.0) / 8.0;
      if (lead > 0.0) {
        EXPECT_LE(*named - 400.0, 30.0);
      }
    }
  }
  std::printf("mean delay: plain %.1f s, lead 10 s %.1f s\n", delay_plain, delay_lead);
  EXPECT_LE(delay_lead, delay_plain - 10.0);
}

TEST(Deficit, APassingGroupEndsItsAlarmAndALineThatPartsUnderItIsNamed) {
  // A 5 MN drift group along line 6's deficit for 60 s raises an alarm on line 6 (while it
  // lasts it looks like the break); once it has passed, the evidence for "no change"
  // drains the alarm. In a second run line 2 parts during the group: once the group has
  // passed, the alarm is revised to line 2 and stays.
  const Vec3 group = -LineLoad(6) * (5e6 / kLineLoad);
  for (const bool part : {false, true}) {
    SCOPED_TRACE(part ? "line 2 parts under the alarm" : "the group alone");
    Deficit deficit;
    BiasStream stream(11, 2e5, 60.0);
    const AlarmHistory history = RunDetector(deficit, stream, 1500, [&](int t) {
      if (part && t == 530) stream.Part(2);
      return t >= 500 && t < 560 ? group : Vec3::Zero();
    });
    ASSERT_EQ(history.events().size(), 2u);
    EXPECT_EQ(history.events()[0].kind, AlarmEvent::Kind::kOnset);
    EXPECT_EQ(history.events()[0].hypothesis, 6);
    EXPECT_LT(history.events()[0].time, 540.0);
    // The group ends at 560 s; the window (15 s) and ~1 nat a sample: within a minute.
    EXPECT_LT(history.events()[1].time, 620.0);
    if (!part) {
      EXPECT_EQ(history.events()[1].kind, AlarmEvent::Kind::kEnd);
      EXPECT_FALSE(history.alarm());
    } else {
      EXPECT_EQ(history.events()[1].kind, AlarmEvent::Kind::kRevision);
      EXPECT_EQ(history.events()[1].hypothesis, 2);
      EXPECT_TRUE(history.alarm());
      EXPECT_EQ(history.hypothesis(), 2);
    }
  }
}

TEST(Deficit, TheRevisionHasItsOwnThreshold) {
  // The group and the break under it of the test above, the onset at 20 nats: the revision
  // to line 2 comes when R_2 passes `revision`, sooner at 8 nats than at 20, and never at
  // 1e9; the onset is the same in all three. One stage: with two, the fast test's revision
  // (its own `revision`) revises this test's alarm too.
  const Vec3 group = -LineLoad(6) * (5e6 / kLineLoad);
  std::vector<double> onset, revised;
  for (const double revision : {20.0, 8.0, 1e9}) {
    SCOPED_TRACE("revision " + std::to_string(revision));
    DeficitOptions options;
    options.confirm = 0.0;
    options.threshold = 20.0;
    options.revision = revision;
    Deficit deficit(options);
    BiasStream stream(11, 2e5, 60.0);
    const AlarmHistory history = RunDetector(deficit, stream, 1500, [&](int t) {
      if (t == 530) stream.Part(2);
      return t >= 500 && t < 560 ? group : Vec3::Zero();
    });
    ASSERT_GE(history.events().size(), 1u);
    EXPECT_EQ(history.events()[0].hypothesis, 6);
    onset.push_back(history.events()[0].time);
    if (revision > 1e8) {
      EXPECT_EQ(history.events().size(), 1u);  // line 6 named to the end
      EXPECT_EQ(history.hypothesis(), 6);
    } else {
      ASSERT_EQ(history.events().size(), 2u);
      EXPECT_EQ(history.events()[1].kind, AlarmEvent::Kind::kRevision);
      EXPECT_EQ(history.events()[1].hypothesis, 2);
      revised.push_back(history.events()[1].time);
    }
  }
  EXPECT_EQ(onset[0], onset[1]);
  EXPECT_EQ(onset[0], onset[2]);
  EXPECT_LT(revised[1], revised[0]);
}

TEST(Deficit, AFalseAlarmsSamplesAreLearnedOnceTheEvidenceReverses) {
  // The 5 MN group of the test above raises an alarm that ends once it has passed. With
  // `relearn` the samples held while the alarm stood (and those waiting at its onset) are
  // then learned as the disturbance they turned out to be, so the learned C carries the
  // group; without, they are dropped and C is what it was before the group. A parted line's
  // alarm never ends, so its samples are never learned (the first test of this file).
  const Vec3 group = -LineLoad(6) * (5e6 / kLineLoad);
  double learned[2] = {0.0, 0.0};
  for (const bool relearn : {false, true}) {
    DeficitOptions options;
    options.confirm = 0.0;
    options.relearn = relearn;
    Deficit deficit(options);
    BiasStream stream(11, 2e5, 60.0);
    const AlarmHistory history = RunDetector(
        deficit, stream, 700, [&](int t) { return t >= 500 && t < 560 ? group : Vec3::Zero(); });
    ASSERT_EQ(history.events().size(), 2u);
    EXPECT_EQ(history.events()[1].kind, AlarmEvent::Kind::kEnd);
    learned[relearn ? 1 : 0] = std::sqrt(deficit.disturbance().trace() / 2.0);
  }
  std::printf("learned disturbance after the group: dropped %.3g N, relearned %.3g N\n", learned[0],
              learned[1]);
  EXPECT_GT(learned[1], 2.0 * learned[0]);
}

TEST(Deficit, LearnsTheDisturbanceOfItsWindowMeanAndItsCorrelation) {
  // White bias noise of standard deviation sigma: the mean of W samples has variance
  // sigma^2 / W per axis, and the raw samples are uncorrelated, so a window mean is worth
  // m = W independent samples. With a baseline time longer than the run, C is the plain
  // sample covariance of ~20000 / W independent window means: relative standard error
  // sqrt(2 W / 20000) = 3.9 %; the bound is 4 of them. m's error is that of the ratio of
  // the two variances plus the lag-1 correlation's (1 / sqrt(20000) ~ 0.7 %, doubled): 15 %.
  const double sigma = 5e5;
  DeficitOptions options;
  options.baseline_time = 1e6;
  Deficit deficit(options);
  BiasStream stream(5, sigma, 1e-9);
  RunDetector(deficit, stream, 20000, [](int) { return Vec3::Zero(); });
  const double expected = sigma * sigma / options.window;
  const double bound = 4.0 * std::sqrt(2.0 * options.window / 20000.0);
  EXPECT_NEAR(deficit.disturbance()(0, 0) / expected, 1.0, bound);
  EXPECT_NEAR(deficit.disturbance()(1, 1) / expected, 1.0, bound);
  EXPECT_NEAR(deficit.disturbance()(0, 1) / expected, 0.0, bound);
  EXPECT_NEAR(deficit.baseline().x(), -8e5, 4.0 * sigma / std::sqrt(20000.0));
  EXPECT_NEAR(deficit.samples_per_value() / options.window, 1.0, 0.15);
}

TEST(Deficit, ARoughSeaRaisesTheEvidenceNeededInsteadOfFalseAlarms) {
  // 1 MN of slowly varying disturbance (60 s), under a third of a parted line's 3.5 MN: at
  // the floor's 0.1 MN, as a fixed calm-sea level, every excursion would read as a break.
  // Learned, 40 intact hours give at most 4 onsets (measured: 2), and the breaks are still
  // named, minutes rather than seconds after them: each sample carries ~0.04 nats. One
  // stage (confirm 0): the two stages' price in this sea is in the test below. At 12 nats:
  // at the default 20, in this sea with none of the disturbance explained, ~0.04 nats a
  // sample do not reach the threshold before the break's samples, learn_delay old, enter
  // the baseline (1 of 8 named; the default was chosen on the plant's campaigns, where
  // such breaks carry more evidence per sample).
  DeficitOptions options;
  options.confirm = 0.0;
  options.threshold = 12.0;
  int onsets = 0;
  int named = 0;
  for (std::uint64_t seed = 0; seed < 4; ++seed) {
    Deficit deficit(options);
    BiasStream intact(100 + seed, 1e6, 60.0);
    onsets +=
        RunDetector(deficit, intact, 36000, [](int) { return Vec3::Zero(); }).OnsetsBefore(1e9);
    BiasStream stream(200 + seed, 1e6, 60.0);
    const int line = 1 + static_cast<int>(seed);
    const AlarmHistory history = RunDetector(deficit, stream, 3600, [&](int t) {
      if (t == 2000) stream.Part(line);
      return Vec3::Zero();
    });
    const std::optional<double> first = history.FirstNamed(line, 2000.0);
    if (first && *first < 2000.0 + 1500.0 && history.hypothesis() == line) ++named;
  }
  EXPECT_LE(onsets, 4);
  EXPECT_GE(named, 3);
}

TEST(Deficit, TheDriftThatTheWaveMotionExplainsLeavesTheDisturbance) {
  // A drift of 2 MN per m^2 of wave-motion energy toward the north-west (E0 = 1 m^2,
  // log-normal with 0.7: ~1.8 MN of slowly varying load, more than half a line's) on 0.2 MN
  // of other disturbance. Regressed on the energy, C is what is left: the disturbance's
  // standard deviation within 30 % of the 0.2 MN (the window mean of a 60 s process keeps
  // most of it); without the regression it carries the drift. With it, line 6 (whose
  // deficit points the drift's way) is named within a minute of its break.
  const Vec3 gain = Vec3(2e6, -2e6, 0.0) / std::sqrt(2.0);
  double with_drift = 0.0;
  double without = 0.0;
  for (const bool drift : {true, false}) {
    DeficitOptions options;
    options.drift = drift;
    Deficit deficit(options);
    BiasStream stream(41, 2e5, 60.0);
    stream.AddDrift(gain, 1.0);
    const AlarmHistory history = RunDetector(deficit, stream, 3000, [&](int t) {
      if (t == 2000) stream.Part(6);
      return Vec3::Zero();
    });
    (drift ? with_drift : without) = std::sqrt(deficit.disturbance().trace() / 2.0);
    if (drift) {
      EXPECT_NEAR(deficit.drift_gain()(0, 0), gain.x(), 0.1 * gain.norm());
      EXPECT_NEAR(deficit.drift_gain()(1, 0), gain.y(), 0.1 * gain.norm());
      EXPECT_EQ(history.OnsetsBefore(2000.0), 0);
      const std::optional<double> named = history.FirstNamed(6, 2000.0);
      ASSERT_TRUE(named.has_value());
      EXPECT_LT(*named, 2060.0);
    }
  }
  EXPECT_NEAR(with_drift, 2e5, 0.3 * 2e5);
  EXPECT_GT(without, 3.0 * with_drift);
}

TEST(Deficit, TheDirectionOfTheWaveMotionExplainsTheSwayDrift) {
  // Waves whose direction wanders by 0.3 rad (17 deg) about the x axis, as with a hull that
  // yaws off the weather: a surge drift of 2 MN per m^2 of wave motion along x (x^2 term)
  // and a sway drift of 6 MN per m^2 on the cross term xy, which changes sign with the side
  // the waves come from, so that the energy x^2 + y^2 cannot explain it (E0 = 1 m^2,
  // log-normal with 0.7: ~1 MN of slowly varying sway load) on 0.2 MN of other disturbance.
  // With the direction and no prior, the learned gains are within 10 % of the true ones;
  // with the default prior (the energy-only gain, worth direction_prior independent values
  // against the n learned, ~13 here) the sway gain lies between the prior's 0 and the
  // truth, weighted n / (n + direction_prior) within 10 %. C is back within 30 % of the
  // 0.2 MN without the prior, within 50 % with it, and either way no alarm comes before line 2
  // parts (east, the sway drift's axis) and is named within a minute; on the energy alone the sway
  // drift stays in C (at least twice the standard deviation).
  Deficit::Gain gain = Deficit::Gain::Zero();
  gain(0, 0) = 2e6;
  gain(1, 2) = 6e6;
  struct Case {
    bool direction;
    double prior;
    double deviation = 0.0;  // sqrt(tr C / 2) at the end
  };
  std::array<Case, 3> cases = {
      {{true, 0.0}, {true, DeficitOptions{}.direction_prior}, {false, 0.0}}};
  for (Case& c : cases) {
    DeficitOptions options;
    options.drift_direction = c.direction;
    options.direction_prior = c.prior;
    Deficit deficit(options);
    BiasStream stream(43, 2e5, 60.0);
    stream.AddDrift(Vec3::Zero(), 1.0);
    stream.TurnWaveMotion(0.3, gain);
    const AlarmHistory history = RunDetector(deficit, stream, 3000, [&](int t) {
      if (t == 2000) stream.Part(2);
      return Vec3::Zero();
    });
    c.deviation = std::sqrt(deficit.disturbance().trace() / 2.0);
    if (!c.direction) continue;
    if (c.prior == 0.0) {
      EXPECT_NEAR(deficit.drift_gain()(0, 0), gain(0, 0), 0.1 * gain.norm());
      EXPECT_NEAR(deficit.drift_gain()(1, 2), gain(1, 2), 0.1 * gain.norm());
    } else {
      // n as the detector counts it: its memory over the samples per independent value.
      const double n = options.baseline_time / deficit.samples_per_value();
      const double weight = n / (n + c.prior);
      EXPECT_NEAR(deficit.drift_gain()(1, 2), weight * gain(1, 2), 0.1 * gain.norm());
      EXPECT_GT(weight, 0.5);
    }
    EXPECT_EQ(history.OnsetsBefore(2000.0), 0);
    const std::optional<double> named = history.FirstNamed(2, 2000.0);
    ASSERT_TRUE(named.has_value());
    EXPECT_LT(*named, 2060.0);
    // The shrunk sway gain leaves a fifth of the sway drift (~0.2 MN) in C.
    EXPECT_NEAR(c.deviation, 2e5, (c.prior == 0.0 ? 0.3 : 0.5) * 2e5);
  }
  EXPECT_GT(cases[2].deviation, 2.0 * cases[1].deviation);
}

TEST(Deficit, FewLearnedValuesInflateTheDisturbance) {
  // In the first minutes of a rough sea C rests on one or two independent values of a
  // 1.5 MN, 60 s disturbance and is mostly too small: over 20 runs of 900 s, the raw C
  // raises alarms after the warm-up, C (1 + 4 / n) at most half as many (one stage).
  int raw = 0;
  int inflated = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    for (const double c : {0.0, 4.0}) {
      DeficitOptions options;
      options.confirm = 0.0;
      options.threshold = 8.0;  // the test the inflation was measured on: whole load, 8 nats
      options.min_fraction = 1.0;
      options.small_sample = c;
      Deficit deficit(options);
      BiasStream stream(300 + seed, 1.5e6, 60.0);
      const int onsets =
          RunDetector(deficit, stream, 900, [](int) { return Vec3::Zero(); }).OnsetsBefore(1e9);
      (c == 0.0 ? raw : inflated) += onsets;
    }
  }
  std::printf("onsets in 20 x 900 s: raw C %d, inflated %d\n", raw, inflated);
  EXPECT_GT(raw, 0);
  EXPECT_LE(2 * inflated, raw);
}

TEST(Deficit, LearningTheWarmUpRaisesFewerStartUpAlarms) {
  // The same rough sea (1.5 MN, 60 s), the default test: learning only the samples
  // learn_delay old, C rests on the warm-up's first half minute when the test starts and
  // alarms follow; with warmup_learning it rests on the whole warm-up, and the start-up
  // alarms (onsets in the first 300 s) fall by a fifth or more over 400 runs (measured 241
  // -> 161: three correlation times of warm-up still make a small sample).
  int delayed = 0;
  int at_once = 0;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    for (const bool learn : {false, true}) {
      DeficitOptions options;
      options.warmup_learning = learn;
      Deficit deficit(options);
      BiasStream stream(500 + seed, 1.5e6, 60.0);
      const int onsets =
          RunDetector(deficit, stream, 300, [](int) { return Vec3::Zero(); }).OnsetsBefore(1e9);
      (learn ? at_once : delayed) += onsets;
    }
  }
  std::printf("start-up onsets in 400 x 300 s: learned late %d, learned at once %d\n", delayed,
              at_once);
  EXPECT_GT(delayed, 0);
  EXPECT_LE(5 * at_once, 4 * delayed);
}

TEST(Deficit, ABreakRightAfterALearnedWarmUpIsNamed) {
  // The warm-up's samples are learned at once; those after it wait learn_delay as before,
  // so a line that parts 30 s after the warm-up is named within a minute.
  for (int line = 1; line <= 8; ++line) {
    SCOPED_TRACE("line " + std::to_string(line));
    DeficitOptions options;
    ASSERT_TRUE(options.warmup_learning);  // the default
    const int parts = static_cast<int>(options.warmup) + 30;
    Deficit deficit(options);
    BiasStream stream(static_cast<std::uint64_t>(line), 3e5, 60.0);
    const AlarmHistory history = RunDetector(deficit, stream, 700, [&](int t) {
      if (t == parts) stream.Part(line);
      return Vec3::Zero();
    });
    ASSERT_EQ(history.events().size(), 1u);
    EXPECT_EQ(history.events()[0].hypothesis, line);
    EXPECT_GT(history.events()[0].time, parts);
    EXPECT_LT(history.events()[0].time, parts + 60.0);
  }
}

TEST(Deficit, TheTwoStageVerdictTakesTheFastOnsetThatThisTestConfirms) {
  // A rough sea, as above (1 MN, 60 s): the fast test alone (window 5, lead 10 s) raises
  // alarms the one-stage test (confirm 0) does not; the two stages (the default) take a
  // fast alarm only once the slow sum for its line has reached 2 nats, so over 4 x 10 intact
  // hours they raise at most a fifth of the fast test's onsets, and over 8 breaks they name
  // every line the one-stage test names, in at most half its mean delay. Measured: 3, 388
  // and 75 onsets; 5, 7 and 8 lines named (the fast test alone ends on a neighbour of the
  // parted line), in 209, 27 and 64 s. In this sea, with none of the disturbance explained
  // by the wave motion, the two stages raise many more false alarms than one stage; on the
  // plant's campaigns (benchmarks/README.md) a few more.
  // At 12 nats, like the test above (at the default 20, in this sea: 0, 229 and 79 onsets;
  // 1, 7 and 8 lines named).
  DeficitOptions two_stages;
  two_stages.threshold = 12.0;
  DeficitOptions one_stage = two_stages;
  one_stage.confirm = 0.0;
  DeficitOptions fast = one_stage;
  fast.window = 5;
  fast.lead = 10.0;
  const std::vector<DeficitOptions> variants = {one_stage, fast, two_stages};
  std::vector<int> onsets(variants.size(), 0);
  std::vector<double> delay(variants.size(), 0.0);
  std::vector<int> named(variants.size(), 0);
  for (std::size_t v = 0; v < variants.size(); ++v) {
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
      Deficit deficit(variants[v]);
      BiasStream intact(100 + seed, 1e6, 60.0);
      onsets[v] +=
          RunDetector(deficit, intact, 36000, [](int) { return Vec3::Zero(); }).OnsetsBefore(1e9);
    }
    for (int line = 1; line <= 8; ++line) {
      Deficit deficit(variants[v]);
      BiasStream stream(200 + static_cast<std::uint64_t>(line), 1e6, 60.0);
      const AlarmHistory history = RunDetector(deficit, stream, 3600, [&](int t) {
        if (t == 2000) stream.Part(line);
        return Vec3::Zero();
      });
      const std::optional<double> first = history.FirstNamed(line, 2000.0);
      if (first && history.hypothesis() == line) {
        ++named[v];
        delay[v] += *first - 2000.0;
      }
    }
    delay[v] /= std::max(named[v], 1);
    std::printf("variant %zu: %d onsets in 40 intact h, %d of 8 named, mean delay %.1f s\n", v,
                onsets[v], named[v], delay[v]);
  }
  EXPECT_GT(onsets[1], 10 * std::max(onsets[0], 1));
  EXPECT_LE(5 * onsets[2], onsets[1]);
  EXPECT_GE(named[2], named[0]);
  EXPECT_LE(delay[2], 0.5 * delay[0]);
}

TEST(Deficit, AShareOfTheLoadIsFoundWithMinFraction) {
  // An anchor release leaves the chain hanging from the fairlead: the vessel first loses
  // only a share of the line's load. A lasting loss of 40 % of line 3's load: tested as the
  // whole load, the shift fits "no change" better (z = 0.4 q - q / 2 < 0) and nothing is
  // raised in 1000 s; with min_fraction 0.3 the share is estimated and line 3 is named.
  for (const double min_fraction : {1.0, 0.3}) {
    SCOPED_TRACE("min_fraction " + std::to_string(min_fraction));
    DeficitOptions options;
    options.min_fraction = min_fraction;
    Deficit deficit(options);
    BiasStream stream(21, 2e5, 60.0);
    const AlarmHistory history = RunDetector(deficit, stream, 1400, [&](int t) {
      return t >= 400 ? Vec3(-0.4 * LineLoad(3)) : Vec3::Zero();
    });
    EXPECT_EQ(history.OnsetsBefore(400.0), 0);
    if (min_fraction == 1.0) {
      EXPECT_FALSE(history.FirstNamed(3, 400.0).has_value());
    } else {
      const std::optional<double> named = history.FirstNamed(3, 400.0);
      ASSERT_TRUE(named.has_value());
      EXPECT_LT(*named, 520.0);
      EXPECT_EQ(history.hypothesis(), 3);
    }
  }
}

TEST(Deficit, ResetIsTheOperatorsReset) {
  Deficit deficit;
  BiasStream stream(3, 3e5, 60.0);
  const AlarmHistory history = RunDetector(deficit, stream, 600, [&](int t) {
    if (t == 300) stream.Part(4);
    return Vec3::Zero();
  });
  ASSERT_TRUE(history.alarm());
  deficit.Reset(kBankSize);
  const Verdict& v = deficit.Step(stream.Sample(601));
  EXPECT_FALSE(v.alarm);
  EXPECT_EQ(v.hypothesis, 0);
}

TEST(Deficit, EvidenceWithoutLoadChangesNothingAndABadBiasThrows) {
  Deficit deficit;
  EXPECT_TRUE(deficit.NeedsLoadEvidence());
  deficit.Reset(kBankSize);
  Evidence bare;
  bare.hypotheses.resize(kBankSize);
  bare.t = 1.0;
  const Verdict& v = deficit.Step(bare);
  EXPECT_FALSE(v.alarm);
  BiasStream stream(4, 3e5, 60.0);
  Evidence bad = stream.Sample(2.0);
  bad.load->bias.x() = std::nan("");
  EXPECT_THROW(deficit.Step(bad), SolverError);
}

}  // namespace
}  // namespace moorsim::detectors
