// The detector interface (docs/design.md section 6). A detector watches the evidence the
// hypothesis observers derive from the noisy pose stream and says, at every sample, which
// hypothesis it believes (0 = all lines intact, k = line k failed, further indices for
// pairs) and whether it declares a failure.
//
// Detectors are built by name from the scenario's `detectors:` list through the registry
// (detectors/registry.h); several run side by side on the same evidence.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"

namespace moorsim::detectors {

/// One sample of what the vessel's instruments and controller give a detector.
struct Observation {
  double t = 0.0;                                  ///< [s]
  Vec3 pose = Vec3::Zero();                        ///< measured x, y [m] (NED), psi [rad]
  std::array<bool, 3> valid = {true, true, true};  ///< channels delivered at this sample
  /// Commanded thrust X, Y, N [N, N, N m], body frame, issued at this sample and held until
  /// the next: the observers predict the coming interval with it.
  Vec3 tau_command = Vec3::Zero();
  std::optional<VecX> tensions;  ///< fairlead tension cells [N], if fitted
};

/// What one hypothesis's observer makes of a sample: its innovation (measurement minus
/// prediction, x, y, psi with psi wrapped), the innovation covariance S and the Gaussian
/// log-likelihood log N(innovation; 0, S) over the valid channels.
struct HypothesisEvidence {
  Vec3 innovation = Vec3::Zero();
  Mat3 covariance = Mat3::Identity();
  double log_likelihood = 0.0;
  int dimension = 3;  ///< number of valid channels used
};

/// The load picture of the intact model, for detectors that test persistent changes of
/// force rather than residuals: the slowly varying load that the intact filter estimates
/// (its bias state) and, per hypothesis, the load of the lines that hypothesis says have
/// failed. The intact model keeps every line; if hypothesis h is true it over-predicts
/// the restoring load by line_load[h], so its bias settles line_load[h] lower than the
/// environment alone would put it (a parted line is, to the intact filter, a steady force).
struct LoadEvidence {
  Vec3 bias = Vec3::Zero();  ///< b [N, N, N m], Earth frame
  Mat3 bias_covariance = Mat3::Identity();
  /// line_load[h]: Earth-frame load [N, N, N m] at the filter's pose estimate of the lines
  /// failed under hypothesis h (line_load[0] = 0).
  std::vector<Vec3> line_load;
  /// The filter's wave-frequency motion estimate C_w xi [m, m, rad], Earth frame: its
  /// envelope drives the slowly varying wave drift, which moves the bias too.
  Vec3 wave_motion = Vec3::Zero();
};

/// Fairlead load cells, where the vessel has them: their latest readings and what the intact
/// model says each should read with the vessel where the filter puts it (the quasi-static
/// fairlead tension sqrt(H^2 + V^2) of each line at the intact filter's pose). A parted
/// line's cell falls far below its expectation (to zero after a fairlead break, to the
/// hanging chain's weight after an anchor release); a faulty cell does too, which is what
/// the pose evidence is there to tell apart.
///
/// Where lines meet at free points, one line's parting changes what the other cells of its
/// network read (a bridle's legs go slack when its anchor line parts; a leg that parts
/// leaves its twin the whole load): column k of expected_if_parted holds what each cell
/// should read with line k parted, at the same pose, for the lines k of networks; NaN where
/// that model has no expectation (a line whose points then reach no anchor, a line outside
/// the networks). Empty without networks.
struct TensionEvidence {
  VecX measured;  ///< [N] per line, in line order
  VecX expected;  ///< [N] per line; NaN where the intact model holds no expectation
  Eigen::MatrixXd expected_if_parted;  ///< [N] lines x lines, or empty
};

/// A sensor a detector can judge faulty: the GNSS receiver, the gyro, a line's load cell, or
/// the pose the GNSS and gyro give together (where the cells show it wrong, and not which).
struct SensorId {
  enum class Kind { kGnss, kGyro, kCell, kPose };
  Kind kind = Kind::kCell;
  int line = 0;  ///< kCell: the cell's line, 1-based
  bool operator==(const SensorId&) const = default;
  /// "GNSS", "gyro", "cell 3", "pose".
  std::string Name() const;
};

/// Why a sensor is judged faulty.
enum class SensorSymptom {
  kDisagrees,  ///< it tells of a change the other sensors do not see
  kFrozen,     ///< it repeats its reading bit for bit: it has stopped measuring
  kJump,       ///< its reading stepped by more than the vessel can move, and stayed there
  kNoisy,      ///< its scatter has grown well beyond its rated noise
  kSilent,     ///< it has delivered no reading for a while
};

/// "disagrees", "frozen", "jump", "noisy", "silent".
std::string_view SensorSymptomName(SensorSymptom symptom);

/// A sensor judged faulty, and why.
struct SensorFinding {
  SensorId sensor;
  SensorSymptom symptom = SensorSymptom::kDisagrees;
  bool operator==(const SensorFinding&) const = default;
};

/// The evidence of every hypothesis at one sample; hypotheses[0] is "all intact".
struct Evidence {
  double t = 0.0;
  std::vector<HypothesisEvidence> hypotheses;
  /// The intact model's evidence from a filter that nothing but the observations touches
  /// (an IMM bank mixes hypotheses[0] with the others; see ObserverBank). Detectors that
  /// test the nominal model's residuals (GLR) use it when present, else hypotheses[0].
  std::optional<HypothesisEvidence> nominal;
  /// From the same filter as `nominal` (the intact filter where the bank does not mix);
  /// unset where the observers estimate no load (the passive observers).
  std::optional<LoadEvidence> load;
  /// Set with `load` when the observation carries load-cell readings.
  std::optional<TensionEvidence> tensions;
  /// The sensors the observers' own checks judge faulty now (detectors/sensor_monitor.h);
  /// their readings are withheld, re-anchored or weighted less. Empty without the checks.
  std::vector<SensorFinding> sensor_faults;
};

/// A detector's state after a sample.
struct Verdict {
  /// Per hypothesis: probability (DHT), negative log-likelihood (MLE) or test statistic
  /// (GLR); what it is is documented by each detector.
  std::vector<double> score;
  int hypothesis = 0;  ///< the detector's best hypothesis, 0 = intact
  bool alarm = false;  ///< a failure is declared (by the detector's documented rule)
  /// The sensors the detector judges faulty now (their readings are not a line's failure);
  /// empty for a detector that does not judge its sensors.
  std::vector<SensorFinding> faulty_sensors;
};

/// What the detection's models give a detector at set-up, computed once per set-up and
/// shared: the failure signatures, signatures[k - 1] the mean whitened intact innovation
/// while hypothesis k holds, over a window of `window` samples (detectors/glr_signatures.h).
class SignatureSource {
 public:
  virtual ~SignatureSource() = default;
  virtual const std::vector<Vec3>& Signatures(int window) const = 0;
};

class Detector {
 public:
  virtual ~Detector() = default;
  virtual std::string_view type() const = 0;
  /// Starts over for `hypotheses` hypotheses (hypothesis 0 intact).
  virtual void Reset(int hypotheses) = 0;
  virtual Verdict Update(const Evidence& evidence) = 0;
  /// Whether the detector reads Evidence::load (which only the EKF observer bank gives).
  virtual bool NeedsLoadEvidence() const { return false; }
  /// Takes what it needs of the detection's models, once before the first Reset().
  virtual void Prepare(const SignatureSource& /*source*/) {}
  /// The threshold its alarm rule compares its score with, for plots; none by default.
  virtual std::optional<double> AlarmThreshold() const { return std::nullopt; }
};

/// A detector as the scenario names it: its type, a unique label (default: the type) and
/// its numeric parameters by name. The registry checks the names and ranges.
struct DetectorSpec {
  std::string type;
  std::string label;
  std::map<std::string, double> parameters;
  /// The shared library that provides `type` (detectors/plugin_detector.h); empty: a
  /// built-in detector of the registry.
  std::string plugin;
};

}  // namespace moorsim::detectors
