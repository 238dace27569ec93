// The observers' sensor checks (detectors/sensor_monitor.h) on a simulated pose stream: a
// vessel drifting slowly about its moored pose (a 0.5 m, 120 s sway of the low-frequency
// motion and a 0.2 m, 8 s wave motion) seen by a GNSS and gyro with the seed case's white
// noise, and the intact filter of the seed bank taking the screened samples, as the observer
// bank does. Each fault is put on the readings by hand: a healthy stream raises no finding;
// a frozen receiver is withheld and named within `frozen_samples`; a 2.5 m step is withheld,
// named a jump and re-anchored, so the filter's pose does not follow it, and its end clears
// the finding; five times the noise is named noisy and weighted less, within seconds of its
// onset, ten times the noise from its first withheld samples, while a motion the filter did
// not predict is not; a noisier sensor's first samples that happen to agree are re-anchored
// as a jump, and taken back once the noise is named; a lone outlier is withheld and named
// nothing; a frozen cell is named and withheld; a noisy cell is named, and a parted line's
// cell is not.
#include "detectors/sensor_monitor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "detectors/ekf_observer.h"
#include "detectors/passive_observer.h"
#include "tests/detectors/observer_test_support.h"

namespace moorsim::detectors::sensor_monitor_test {
namespace {

constexpr double kPi = std::numbers::pi;
const double kNoise = std::sqrt(0.005);  // the seed case's GNSS and gyro [m, rad]

// What the sensors read at t from the vessel's true pose, before any fault.
struct Stream {
  explicit Stream(std::uint64_t seed)
      : north(RandomStream::Derive(seed, "north")),
        east(RandomStream::Derive(seed, "east")),
        heading(RandomStream::Derive(seed, "heading")) {}
  static Vec3 Truth(double t) {
    return Vec3(0.5 * std::sin(2 * kPi * t / 120) + 0.2 * std::sin(2 * kPi * t / 8),
                0.3 * std::cos(2 * kPi * t / 150) + 0.2 * std::sin(2 * kPi * t / 8 + 1),
                0.01 * std::sin(2 * kPi * t / 200));
  }
  /// `noise_factor` multiplies the GNSS noise.
  Observation Next(double t, double noise_factor = 1.0) {
    Observation obs;
    obs.t = t;
    obs.pose = Truth(t) + kNoise * Vec3(noise_factor * north.Normal(), noise_factor * east.Normal(),
                                        0.2 * heading.Normal());
    return obs;
  }
  RandomStream north, east, heading;
};

// The intact filter of the seed bank, fed the monitor's screened samples.
struct Screened {
  Screened()
      : filter(testing::SeedBank().mooring(0), SeedLowFrequencyModel(), Mat3::Zero()),
        monitor(SensorCheckOptions{}, EkfOptions{}.measurement_variance) {}
  const Observation& Take(const Observation& raw) {
    const Observation& used = monitor.Screen(raw, filter);
    filter.SetMeasurementNoiseScale(monitor.noise_scale());
    filter.Update(used);
    return used;
  }
  bool Judged(SensorId::Kind kind, SensorSymptom symptom) const {
    return std::any_of(
        monitor.findings().begin(), monitor.findings().end(),
        [&](const SensorFinding& f) { return f.sensor.kind == kind && f.symptom == symptom; });
  }
  HypothesisEkf filter;
  SensorMonitor monitor;
};

// Runs `seconds` of 1 Hz samples, `fault(obs)` altering each reading; returns the first
// time `judged()` held (nullopt if never) and leaves the last screened sample in *last.
std::optional<double> Feed(Screened& s, Stream& stream, double t0, double seconds,
                           const std::function<void(Observation&)>& fault,
                           const std::function<bool()>& judged, Observation* last = nullptr,
                           double noise_factor = 1.0) {
  std::optional<double> first;
  for (double t = t0; t < t0 + seconds; t += 1.0) {
    Observation obs = stream.Next(t, noise_factor);
    fault(obs);
    const Observation& used = s.Take(obs);
    if (last != nullptr) *last = used;
    if (!first && judged()) first = t;
  }
  return first;
}

const auto kNoFault = [](Observation&) {};

TEST(SensorMonitor, AHealthyStreamRaisesNoFinding) {
  for (std::uint64_t seed : {1, 2, 3}) {
    Screened s;
    Stream stream(seed);
    int withheld = 0;
    for (double t = 0; t < 3000; t += 1.0) {
      const Observation& used = s.Take(stream.Next(t));
      withheld += used.valid[0] ? 0 : 1;
      ASSERT_TRUE(s.monitor.findings().empty()) << "seed " << seed << " t " << t;
      ASSERT_EQ(s.monitor.noise_scale(), Vec3::Ones());
    }
    // About 5 standard deviations: a healthy sample is withheld hardly ever.
    EXPECT_LE(withheld, 3) << "seed " << seed;
  }
}

TEST(SensorMonitor, AFrozenReceiverIsWithheldAndNamedUntilItMovesAgain) {
  Screened s;
  Stream stream(4);
  Feed(s, stream, 0, 600, kNoFault, [] { return false; });
  Vec3 frozen = Vec3::Zero();
  Observation last;
  const auto freeze = [&](Observation& obs) {
    if (obs.t == 600) frozen = obs.pose;
    obs.pose.head<2>() = frozen.head<2>();
  };
  const std::optional<double> named = Feed(
      s, stream, 600, 60, freeze,
      [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kFrozen); }, &last);
  ASSERT_TRUE(named.has_value());
  // The fourth identical reading (the default frozen_samples) makes it frozen.
  EXPECT_EQ(*named, 603.0);
  EXPECT_FALSE(last.valid[0]);
  EXPECT_FALSE(last.valid[1]);
  EXPECT_TRUE(last.valid[2]);  // the gyro is another instrument
  Feed(
      s, stream, 660, 5, kNoFault, [] { return false; }, &last);
  EXPECT_FALSE(s.Judged(SensorId::Kind::kGnss, SensorSymptom::kFrozen));
  EXPECT_TRUE(last.valid[0]);
}

TEST(SensorMonitor, AJumpIsReanchoredSoTheFilterDoesNotFollowIt) {
  Screened s;
  Stream stream(5);
  Feed(s, stream, 0, 600, kNoFault, [] { return false; });
  const auto step = [](Observation& obs) { obs.pose.x() += 2.5; };
  Observation last;
  const std::optional<double> named = Feed(
      s, stream, 600, 300, step,
      [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump); }, &last);
  ASSERT_TRUE(named.has_value());
  EXPECT_EQ(*named, 602.0);  // the third withheld sample that agrees (jump_samples)
  EXPECT_TRUE(s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump));
  // Re-anchored: the screened reading is the true pose again, within the noise, and so is
  // the filter's estimate of the low-frequency pose plus wave motion.
  const Vec3 truth = Stream::Truth(899);
  EXPECT_NEAR(last.pose.x(), truth.x(), 5 * kNoise);
  EXPECT_TRUE(last.valid[0]);
  EXPECT_NEAR(s.filter.pose().x() + s.filter.wave_motion().x(), truth.x(), 0.3);
  // The step ends: a jump back, and the finding clears.
  Feed(
      s, stream, 900, 10, kNoFault, [] { return false; }, &last);
  EXPECT_FALSE(s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump));
  EXPECT_NEAR(last.pose.x(), Stream::Truth(909).x(), 5 * kNoise);
}

TEST(SensorMonitor, AfterAGapADisplacementIsTheVesselsTravelNotAJump) {
  // The receiver is silent for a minute, and when it speaks again the vessel is 10 m
  // further north (it drifted meanwhile: a line parted while the GNSS was out). That is not a
  // jump: it is let through, and the filter follows.
  Screened s;
  Stream stream(9);
  Feed(s, stream, 0, 600, kNoFault, [] { return false; });
  Observation last;
  const std::optional<double> silent = Feed(
      s, stream, 600, 60,
      [](Observation& obs) {
        obs.valid = {false, false, true};
      },
      [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kSilent); });
  ASSERT_TRUE(silent.has_value());
  EXPECT_EQ(*silent, 603.0);  // the fourth sample without a reading
  const auto moved = [](Observation& obs) { obs.pose.x() += 10.0; };
  EXPECT_FALSE(Feed(
                   s, stream, 660, 100, moved,
                   [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump); }, &last)
                   .has_value());
  EXPECT_TRUE(s.monitor.findings().empty());
  EXPECT_TRUE(last.valid[0]);
  EXPECT_NEAR(last.pose.x(), Stream::Truth(759).x() + 10.0, 5 * kNoise);  // not re-anchored
  EXPECT_NEAR(s.filter.pose().x() + s.filter.wave_motion().x(), Stream::Truth(759).x() + 10.0, 0.3);
}

TEST(SensorMonitor, FiveTimesTheNoiseIsNamedNoisyAndWeightedLess) {
  Screened s;
  Stream stream(6);
  Feed(s, stream, 0, 600, kNoFault, [] { return false; });
  const std::optional<double> named = Feed(
      s, stream, 600, 300, kNoFault,
      [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy); }, nullptr, 5.0);
  ASSERT_TRUE(named.has_value());
  EXPECT_LT(*named - 600, 90.0);  // within the recent level's averaging time
  EXPECT_GT(s.monitor.noise_scale().x(), 5.0);
  EXPECT_EQ(s.monitor.noise_scale().z(), 1.0);  // the gyro is healthy
  // Healthy again: trusted within a few averaging times, at full weight.
  const std::optional<double> trusted = Feed(s, stream, 900, 600, kNoFault, [&] {
    return !s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy);
  });
  ASSERT_TRUE(trusted.has_value());
  EXPECT_EQ(s.monitor.noise_scale(), Vec3::Ones());
}

TEST(SensorMonitor, NoiseIsNamedAtItsOnsetByTheFastWindow) {
  for (std::uint64_t seed : {11, 12, 13}) {
    Screened s;
    Stream stream(seed);
    Feed(s, stream, 0, 600, kNoFault, [] { return false; });
    const std::optional<double> named = Feed(
        s, stream, 600, 120, kNoFault,
        [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy); }, nullptr, 5.0);
    ASSERT_TRUE(named.has_value()) << "seed " << seed;
    EXPECT_LT(*named - 600, 15.0) << "seed " << seed;  // the recent level would take a minute
  }
}

TEST(SensorMonitor, AMuchNoisierSensorIsNamedFromItsFirstWithheldRun) {
  // Ten times the noise: most samples fall outside the gate and are withheld in runs. A run
  // that scatters from sample to sample is the noise itself, learned at once.
  for (std::uint64_t seed = 17; seed < 37; ++seed) {
    Screened s;
    Stream stream(seed);
    Feed(s, stream, 0, 600, kNoFault, [] { return false; });
    const std::optional<double> named = Feed(
        s, stream, 600, 60, kNoFault,
        [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy); }, nullptr, 10.0);
    ASSERT_TRUE(named.has_value()) << "seed " << seed;
    // 1-8 s; taking the run's samples only once they are back in the gate, 1-16 s.
    EXPECT_LE(*named - 600, 10.0) << "seed " << seed;
  }
}

TEST(SensorMonitor, ANoisierSensorsFirstSamplesThatHappenToAgreeAreNoJump) {
  // A receiver turns 9.4 times noisier, and its first three samples happen to lie together,
  // 2 m north of the vessel: they pass for a jump and are re-anchored. Once the noise is
  // named, seconds later, the re-anchoring is taken back, so the filter is not left 2 m off.
  for (std::uint64_t seed : {41, 42, 43}) {
    Screened s;
    Stream stream(seed);
    Feed(s, stream, 0, 600, kNoFault, [] { return false; });
    for (double t = 600; t < 603; t += 1.0) {
      Observation obs = stream.Next(t);
      obs.pose.x() += 2.0;
      s.Take(obs);
    }
    EXPECT_TRUE(s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump)) << "seed " << seed;
    const std::optional<double> named = Feed(
        s, stream, 603, 120, kNoFault,
        [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy); }, nullptr, 9.4);
    ASSERT_TRUE(named.has_value()) << "seed " << seed;
    EXPECT_LE(*named - 603, 10.0) << "seed " << seed;
    EXPECT_FALSE(s.Judged(SensorId::Kind::kGnss, SensorSymptom::kJump)) << "seed " << seed;
    // The filter follows the vessel, within the noisy sensor's reach (0.66 m a sample).
    EXPECT_NEAR(s.filter.pose().x() + s.filter.wave_motion().x(), Stream::Truth(722).x(), 1.0)
        << "seed " << seed;
  }
}

TEST(SensorMonitor, AMotionTheFilterDidNotPredictIsNotNoise) {
  // The vessel sets off 8 m north over a minute and a half, as it does when a line parts:
  // the intact filter lags, and its innovations grow large but keep one sign.
  for (std::uint64_t seed : {14, 15, 16}) {
    Screened s;
    Stream stream(seed);
    Feed(s, stream, 0, 600, kNoFault, [] { return false; });
    double largest = 0.0;  // the largest innovation the drift gave, in noise deviations
    const auto drift = [&](Observation& obs) {
      const double x = 8.0 * (1.0 - std::exp(-(obs.t - 600.0) / 30.0));
      obs.pose.x() += x;
      largest = std::max(
          largest,
          std::abs(obs.pose.x() - s.filter.pose().x() - s.filter.wave_motion().x()) / kNoise);
    };
    EXPECT_FALSE(Feed(s, stream, 600, 300, drift,
                      [&] { return s.Judged(SensorId::Kind::kGnss, SensorSymptom::kNoisy); })
                     .has_value())
        << "seed " << seed;
    EXPECT_GT(largest, 5.0) << "seed " << seed;  // the fast window's ratio, had it no mean
  }
}

TEST(SensorMonitor, ALoneOutlierIsWithheldAndNamesNothing) {
  Screened s;
  Stream stream(7);
  Feed(s, stream, 0, 600, kNoFault, [] { return false; });
  Observation last;
  Feed(
      s, stream, 600, 1, [](Observation& obs) { obs.pose.y() -= 2.0; }, [] { return false; },
      &last);
  EXPECT_FALSE(last.valid[0]);
  EXPECT_FALSE(last.valid[1]);
  Feed(
      s, stream, 601, 60, kNoFault, [] { return false; }, &last);
  EXPECT_TRUE(s.monitor.findings().empty());
  EXPECT_TRUE(last.valid[1]);
}

TEST(SensorMonitor, AFrozenCellIsNamedAndWithheld) {
  Screened s;
  Stream stream(8);
  RandomStream cells(RandomStream::Derive(8, "cells"));
  Observation last;
  const auto with_cells = [&](Observation& obs) {
    VecX readings(3);
    for (int k = 0; k < 3; ++k) readings(k) = 6e6 + 1e4 * cells.Normal();
    if (obs.t >= 100) readings(1) = 5.9e6;  // cell 2 stuck
    obs.tensions = readings;
  };
  const std::optional<double> named = Feed(
      s, stream, 0, 200, with_cells,
      [&] {
        return std::any_of(
            s.monitor.findings().begin(), s.monitor.findings().end(), [](const SensorFinding& f) {
              return f.sensor == SensorId{.kind = SensorId::Kind::kCell, .line = 2} &&
                     f.symptom == SensorSymptom::kFrozen;
            });
      },
      &last);
  ASSERT_TRUE(named.has_value());
  EXPECT_EQ(*named, 103.0);
  ASSERT_TRUE(last.tensions.has_value());
  EXPECT_TRUE(std::isnan((*last.tensions)(1)));
  EXPECT_TRUE(std::isfinite((*last.tensions)(0)));
}

TEST(SensorMonitor, ANoisyCellIsNamedAndAPartedLinesCellIsNot) {
  // Three cells reading a line's wave-frequency tension (50 kN at 9 s, a moderate sea's) with
  // 10 kN noise.
  // From 600 s, cell 2 is ten times as noisy and cell 3's line parts (its reading falls to
  // the noise about zero within two seconds).
  Screened s;
  Stream stream(17);
  RandomStream noise(RandomStream::Derive(17, "cells"));
  const auto with_cells = [&](Observation& obs) {
    VecX readings(3);
    for (int k = 0; k < 3; ++k) {
      readings(k) = 6e6 + 5e4 * std::sin(2 * kPi * obs.t / 9 + k) + 1e4 * noise.Normal();
    }
    if (obs.t >= 600) readings(1) += 9e4 * noise.Normal();
    if (obs.t >= 600) readings(2) = (obs.t >= 601 ? 0.0 : 3e6) + 1e4 * noise.Normal();
    obs.tensions = readings;
  };
  const auto noisy = [&](int line) {
    return std::any_of(s.monitor.findings().begin(), s.monitor.findings().end(),
                       [&](const SensorFinding& f) {
                         return f.sensor == SensorId{.kind = SensorId::Kind::kCell, .line = line} &&
                                f.symptom == SensorSymptom::kNoisy;
                       });
  };
  EXPECT_FALSE(Feed(s, stream, 0, 600, with_cells, [&] {
                 return noisy(1) || noisy(2) || noisy(3);
               }).has_value());
  bool parted_named = false, healthy_named = false;
  const std::optional<double> named = Feed(s, stream, 600, 300, with_cells, [&] {
    parted_named = parted_named || noisy(3);
    healthy_named = healthy_named || noisy(1);
    return noisy(2);
  });
  ASSERT_TRUE(named.has_value());
  EXPECT_LT(*named - 600, 90.0);
  EXPECT_FALSE(parted_named);
  EXPECT_FALSE(healthy_named);
}

TEST(SensorMonitor, BadOptionsNameTheirField) {
  const auto message = [](SensorCheckOptions options) {
    try {
      Validate(options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SensorCheckOptions o;
  o.frozen_samples = 1;
  EXPECT_EQ(message(o), "detection.sensor_checks.frozen_samples: 1 must be >= 2");
  o = {};
  o.gate = 0.0;
  EXPECT_EQ(message(o), "detection.sensor_checks.gate: 0 must be finite and > 0");
  o = {};
  o.baseline_time = o.noise_time;
  EXPECT_EQ(message(o),
            "detection.sensor_checks.baseline_time: 90 must be finite and > noise_time");
  o = {};
  o.noisy_ratio = 1.0;
  EXPECT_EQ(message(o), "detection.sensor_checks.noisy_ratio: 1 must be finite and > 1");
  o = {};
  o.fast_time = o.noise_time;
  EXPECT_EQ(message(o),
            "detection.sensor_checks.fast_time: 90 must be finite, > 0 and < noise_time");
  o = {};
  o.fast_ratio = 0.5;
  EXPECT_EQ(message(o), "detection.sensor_checks.fast_ratio: 0.5 must be finite and > 1");
  EXPECT_EQ(message(SensorCheckOptions{}), "");
}

}  // namespace
}  // namespace moorsim::detectors::sensor_monitor_test
