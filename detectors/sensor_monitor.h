// Checks on the sensors themselves, made before the observers take a sample: a position
// reference that freezes, jumps or grows noisy, a heading that does the same, a load cell
// that freezes or grows noisy. Without them every such fault reaches the observers as vessel
// motion, and a force-deficit or residual test reads the motion as a lost line.
//
// The checks, per sensor (the GNSS receiver's north and east together, the gyro, each cell):
//  - Frozen: a reading that repeats bit for bit for `frozen_samples` samples has stopped
//    measuring (a live sensor's noise never repeats to the last bit). The channel is
//    withheld from the observers until it changes. A pose sensor that delivers no reading
//    for as many samples is silent (its channels are invalid anyway).
//  - Outlier and jump: the intact model's one-step prediction gives each sample an innovation e. A
//    sample whose innovation, normalised by the larger of the filter's own innovation variance S
//    and the variance the sensor's innovations usually show (below), is beyond `gate` is withheld.
//    (The filter's S alone is too small in a seaway: its wave model predicts the wave-frequency
//    motion only roughly.) If `jump_samples` consecutive samples are withheld, their innovations
//    stepped by more than the gate from the one before (itself within the gate, and not within 30
//    samples of a gap in the sensor's readings, after which the filter is still finding where the
//    vessel went), and they agree (each within `agree` of their mean, the last within `agree` of
//    the first: flat, where a motion the filter failed to predict grows), the sensor has jumped:
//    its channels are re-anchored by that mean (later readings have it subtracted), so the step
//    does not reach the observers as a motion. If they do not, the next sample is taken whatever
//    its innovation: outliers come alone, and a run of them that is no step is the vessel moving as
//    the filter did not predict (a line parting), which the observers must see. Such a run's
//    innovations are not learned as noise, unless they scatter from sample to sample (the mean of
//    half their successive differences' normalised squares beyond half the gate): that is a much
//    noisier sensor's onset, learned at once so the noise is named before it moves the observers.
//    The sensor stays judged "jump" while its offset is beyond the gate of its rated noise; a jump
//    back clears it. A vessel cannot move metres between two samples a second apart, a position
//    reference can. A much noisier sensor's first samples can happen to agree: a jump judged
//    within twice `fast_time` before the sensor is judged noisy was that noise (the jump test
//    assumes the noise the gate was set for), and its re-anchoring is taken back.
//  - Noisy: each channel's squared innovations averaged over `noise_time` (recent) and over
//    `baseline_time` (usual, learned while the recent level stays within half the ratio). Recent
//    beyond `noisy_ratio` times usual, the sensor is judged noisy, and the observers take the
//    excess as measurement noise: R + (recent - usual) in place of R (covariance matching,
//    after Mehra 1972). Below half the ratio it is trusted again. Judged against its own
//    usual level, the check does not mistake a rough sea for a noisy sensor.
//    The recent level takes a minute to rise, and meanwhile the noise moves the filters'
//    bias as a lost load would. So a fast estimate judges the onset: half the mean squared
//    difference of successive innovations over `fast_time` (von Neumann's estimator of a
//    variance, von Neumann et al. 1941), beyond `fast_ratio` times usual. A sensor's noise
//    is white, and the differences carry all of it; a motion the filter did not predict (a
//    parting line's drift, tens of centimetres a sample) changes little from one sample to
//    the next, and they carry almost none of it, however large the innovations grow. The
//    observers take the larger of the two levels' excess, and the sensor is trusted again
//    once both are below half their ratios.
//    A load cell's noise is judged the same way, by its readings' successive differences
//    (the line's own wave-frequency tension is in the usual level): a cell judged noisy is
//    named, and still read (the cells test averages its readings).
//
// The intact filter's prediction is taken from a copy of it advanced to the sample, so
// every hypothesis's filter then sees the same screened sample.
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "detectors/detector.h"
#include "detectors/ekf_observer.h"

namespace moorsim::detectors {

class SensorMonitor {
 public:
  /// `rated_variance`: the observers' R per channel [m^2, m^2, rad^2].
  SensorMonitor(const SensorCheckOptions& options, const Vec3& rated_variance);

  void Reset();
  /// The sample the observers should take in place of `observation`: frozen channels and
  /// withheld samples marked invalid, jumped channels re-anchored, frozen cells NaN.
  /// `intact` is the intact filter before this sample. Valid until the next call.
  const Observation& Screen(const Observation& observation, const HypothesisEkf& intact);
  /// Per channel, the factor on the observers' R (1 unless the sensor is noisy).
  const Vec3& noise_scale() const { return noise_scale_; }
  /// The sensors judged faulty after the latest sample.
  const std::vector<SensorFinding>& findings() const { return findings_; }

 private:
  // A reading and how many samples in a row repeated it bit for bit.
  struct Repeats {
    double last = 0.0;
    bool seen = false;
    int repeats = 0;  // consecutive samples equal to `last`, after the first
    /// Takes a delivered reading; whether it has now been frozen for `samples` samples.
    bool Frozen(double reading, int samples);
  };
  // A noise level, recent and usual (the means of a squared innovation or difference).
  struct NoiseLevel {
    double recent = 0.0, usual = 0.0;
    double learned = 0.0;  // [s] time the usual level has been learned
    long samples = 0, usual_samples = 0;
    /// Takes a squared value; `noisy`: the sensor is judged noisy (the usual level waits).
    void Learn(double square, double dt, const SensorCheckOptions& options, bool noisy);
    /// Whether the usual level has been learned long enough to judge by.
    bool Warm(const SensorCheckOptions& options) const;
    /// Noisy beyond `limit` times usual, trusted again below half of it.
    static bool Judge(double ratio, double limit, bool noisy);
  };
  struct Channel {
    Repeats readings;
    int missing = 0;  // consecutive samples without a reading
    double offset = 0.0;
    NoiseLevel level;   // of its squared innovations
    double fast = 0.0;  // half the mean squared difference of successive innovations
    long fast_samples = 0;
    double previous = 0.0;  // the innovation learned last
    bool follows = false;   // ... and the next one learned follows it
    int since_gap = 0;      // samples since it last had none or a frozen one
  };
  struct Cell {
    Repeats readings;
    NoiseLevel level;  // of half its successive readings' squared difference
    double previous = 0.0;
    bool follows = false;
    bool noisy = false;
  };
  struct PoseSensor {
    SensorId id;
    int first = 0, count = 0;              // its channels
    std::vector<Eigen::Vector2d> pending;  // innovations of the consecutive withheld samples
    Eigen::Vector2d before = Eigen::Vector2d::Zero();  // the innovation before them
    bool before_in_gate = false;                       // ... and it was within the gate
    bool noisy = false;
    Eigen::Vector2d jump = Eigen::Vector2d::Zero();  // the latest jump's re-anchoring step
    double jump_time = -std::numeric_limits<double>::infinity();  // ... and when judged
  };
  void CheckPoseSensor(PoseSensor& sensor, const HypothesisEvidence& predicted, double dt);
  void LearnNoise(int channel, double innovation, double gate_variance, double dt);
  // The noise check of a cell: its reading (NaN: withheld).
  void CheckCell(Cell& cell, double reading, double dt);
  // The variance an innovation of channel i is judged against: the larger of S_ii and the
  // usual level once learned.
  double GateVariance(int i, const Mat3& S) const;

  SensorCheckOptions options_;
  Vec3 rated_;
  std::vector<Channel> channels_;  // north, east, heading
  std::vector<PoseSensor> sensors_;
  std::vector<Cell> cells_;
  std::optional<HypothesisEkf> probe_;
  Observation screened_;
  std::array<bool, 3> observation_valid_ = {true, true, true};  // after the frozen check
  Vec3 noise_scale_ = Vec3::Ones();
  std::vector<SensorFinding> findings_;
  double t_ = 0.0;
  bool started_ = false;
};

}  // namespace moorsim::detectors
