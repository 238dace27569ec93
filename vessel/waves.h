// Irregular first-order waves: the JONSWAP spectrum, cos-2s directional spreading and
// random-phase realisations of the sea surface.
//
// Conventions (docs/design.md section 2): SI units, angles in radians, Earth frame NED (x north,
// y east, z down). The wave elevation eta is positive UP (eta = -z of the free surface).
// A direction theta is the direction the waves travel TO, measured from north (+x)
// toward east (+y): theta = 0 travels north, theta = pi/2 travels east. Waves "from the
// north-west" (coming from 315 deg) travel to 135 deg; whoever reads a "from" direction
// (the scenario loader) adds pi.
//
// Linear (Airy) deep-water theory throughout: the wave number is k = omega^2 / g. In the
// seed case's 1000 m of water, deep water (k h > pi, i.e. tanh(k h) > 0.996) holds above
// omega = sqrt(pi g / h) = 0.18 rad/s, well below the default lowest component (0.45 rad/s
// for Tp = 7 s).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "core/random.h"

namespace moorsim::vessel {

/// One-sided wave spectrum of the sea surface elevation: the variance of eta is the
/// integral of Density over omega in (0, inf). A small interface so other spectra
/// (Pierson-Moskowitz, Torsethaugen, measured) can sit next to JONSWAP in the spectrum
/// registry.
class WaveSpectrum {
 public:
  virtual ~WaveSpectrum() = default;
  /// Spectral density S(omega) [m^2 s/rad] at angular frequency omega [rad/s]; 0 for
  /// omega <= 0.
  virtual double Density(double omega) const = 0;
  /// Angular frequency of the spectral maximum omega_p [rad/s].
  virtual double PeakFrequency() const = 0;
};

/// Sea state of a JONSWAP spectrum. Hs and Tp have no defaults on purpose: a sea state
/// left unset is an input error, not a calm sea.
struct JonswapParameters {
  double significant_height = 0.0;  ///< Hs = 4 sqrt(m0) [m], > 0
  double peak_period = 0.0;         ///< Tp = 2 pi / omega_p [s], > 0
  double peak_enhancement = 3.3;    ///< gamma [-], 1 <= gamma <= 7; 3.3 is DNV's average
};

/// JONSWAP spectrum in the form of DNV-RP-C205 (2010) section 3.5.5, a Pierson-Moskowitz
/// spectrum with a peak enhancement and DNV's approximate normalisation:
///
///   S(omega) = A_gamma S_PM(omega) gamma^exp(-(omega - omega_p)^2 / (2 sigma^2 omega_p^2))
///   S_PM(omega) = 5/16 Hs^2 omega_p^4 omega^-5 exp(-5/4 (omega / omega_p)^-4)
///   A_gamma = 1 - 0.287 ln(gamma)
///   sigma = 0.07 for omega <= omega_p, 0.09 for omega > omega_p
///
/// With A_gamma the variance is Hs^2/16 only approximately: integrated over (0, inf) it is
/// off by -0.22 % at gamma = 2, +0.24 % at 3.3, +0.0003 % at 5 and -1.75 % at 7 (gamma = 1
/// is exact: S_PM integrates to Hs^2/16 in closed form). DNV states the model is
/// reasonable for 3.6 < Tp / sqrt(Hs) < 5 (Tp in s, Hs in m); the seed sea state (2.5 m,
/// 7 s) gives 4.43. That range is documented here, not enforced: it is a statement about
/// real seas, not about the formula.
class JonswapSpectrum final : public WaveSpectrum {
 public:
  /// Throws moorsim::InputError naming the field and value if Hs <= 0, Tp <= 0 or gamma is
  /// outside DNV's range [1, 7] (A_gamma was fitted there; at gamma = 32.6 it reaches 0).
  explicit JonswapSpectrum(const JonswapParameters& parameters);

  double Density(double omega) const override;
  double PeakFrequency() const override { return peak_frequency_; }

  const JonswapParameters& parameters() const { return parameters_; }
  /// DNV's normalising factor A_gamma [-].
  double normalising_factor() const { return normalising_factor_; }

 private:
  JonswapParameters parameters_;
  double peak_frequency_ = 0.0;      // omega_p [rad/s]
  double normalising_factor_ = 1.0;  // A_gamma
};

/// Spectral moment m_n = integral of omega^n S(omega) over [omega_min, omega_max]
/// [m^2 (rad/s)^n], by composite Simpson's rule on `intervals` panels, split at the
/// spectral peak so the kink of JONSWAP's two-sided sigma falls on a panel edge. m0 is the
/// elevation variance (Hs = 4 sqrt(m0)); Tz = 2 pi sqrt(m0 / m2). A negative order needs
/// omega_min > 0. Throws moorsim::InputError on an empty or negative range or
/// intervals < 2.
double SpectralMoment(const WaveSpectrum& spectrum, int order, double omega_min, double omega_max,
                      int intervals = 20000);

/// Deep-water dispersion relation k = omega^2 / g [rad/m].
inline double DeepWaterWaveNumber(double omega, double gravity) { return omega * omega / gravity; }

/// The cos-2s directional spreading function of Longuet-Higgins, Cartwright & Smith (1963),
/// normalised over one full turn (Goda, "Random Seas and Design of Maritime Structures",
/// 3rd ed. 2010, section 2.3):
///
///   D(theta) = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2)) cos^(2s)((theta - theta_0) / 2)
///
/// for theta - theta_0 in [-pi, pi]. s = 0 spreads uniformly over all directions; s -> inf
/// tends to long-crested waves. Its mean resultant length E[cos(theta - theta_0)] is
/// s / (s + 1) (s = 10: 0.909, a circular standard deviation of 25 deg).
class CosineSpreading {
 public:
  /// mean_direction theta_0 [rad] (travel-to, see the file comment); exponent s >= 0.
  /// Throws moorsim::InputError if s is negative or not finite.
  CosineSpreading(double mean_direction, double exponent);

  /// D(theta) [1/rad]; periodic in theta with period 2 pi.
  double Density(double direction) const;

  /// The direction whose cumulative probability (from theta_0 - pi) is `probability` in
  /// [0, 1): the inverse CDF, so a uniform probability gives a direction distributed as D.
  /// Returned in (-pi, pi].
  double Quantile(double probability) const;

  double mean_direction() const { return mean_direction_; }
  double exponent() const { return exponent_; }

 private:
  double mean_direction_ = 0.0;
  double exponent_ = 0.0;
  double normalisation_ = 0.0;  // Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2))
  // Cumulative distribution of the offset theta - theta_0 on a uniform grid over
  // [-table_half_width_, table_half_width_] (pi, or less where D has fallen below 1e-16 of
  // its peak), exactly 0 at the first node and 1 at the last; the inverse CDF interpolates
  // it linearly (D piecewise constant per cell).
  double table_half_width_ = 0.0;
  std::vector<double> offset_cdf_;
};

/// One regular wave of a realisation:
/// eta_i = amplitude cos(omega t - k (x cos(direction) + y sin(direction)) + phase).
struct WaveComponent {
  double omega = 0.0;      ///< angular frequency [rad/s]
  double amplitude = 0.0;  ///< elevation amplitude a_i [m]
  double phase = 0.0;      ///< phase phi_i [rad], in [0, 2 pi)
  double direction = 0.0;  ///< travel-to direction theta_i [rad], from north toward east
};

/// How component frequencies are placed in their equal-width bins.
enum class FrequencySampling {
  /// One uniformly random frequency per bin (default). A fixed grid makes the record
  /// periodic: with omega_i = omega_0 + i d_omega every component returns to its phase
  /// after 2 pi / d_omega (400 s for the defaults at Tp = 7 s), so a 3-hour record would
  /// be the same 400 s twenty-seven times over.
  kRandomInBin,
  /// Bin centres: deterministic frequencies, for comparison with frequency-domain tools.
  kBinCentre,
};

struct WaveRealisationOptions {
  /// theta_0 [rad]: the mean travel-to direction, from north toward east.
  double mean_direction = 0.0;
  /// s of the cos-2s spreading; unset means long-crested (every component at theta_0).
  std::optional<double> spreading_exponent;
  /// N, number of frequency components, >= 1. 200 over the default range gives
  /// d_omega = 0.0157 rad/s at Tp = 7 s, about four bins per JONSWAP peak half-width
  /// (sigma omega_p = 0.063 rad/s), and is cheap to sum in the RHS. N also sets how far a
  /// realisation's Hs strays from the spectrum's, because a_i samples S at one random
  /// point per bin. Measured over 10^4 seeds at the seed sea state (2.5 m, 7 s, 3.3): the
  /// standard deviation of the realised Hs is 0.84 % at N = 100 (1.4 % of seeds beyond
  /// 2 %), 0.30 % at N = 200 (worst 1.03 %) and 0.11 % at N = 400. Keep N >= 200 where the
  /// realised Hs must be within 2 % of the target.
  int components = 200;
  /// Frequency range [rad/s]; the defaults follow the spectrum's energy, not fixed
  /// numbers: 0.5 omega_p and 4 omega_p. For Pierson-Moskowitz the energy outside is
  /// exp(-20) = 2e-9 below and 1 - exp(-1.25 / 4^4) = 0.49 % above (closed form of the
  /// PM cumulative); for JONSWAP gamma = 3.3 it is 0.32 % above, i.e. Hs 0.16 % low.
  /// For Tp = 7 s: 0.449 to 3.59 rad/s (periods 14 s to 1.75 s).
  std::optional<double> omega_min;
  std::optional<double> omega_max;
  FrequencySampling frequency_sampling = FrequencySampling::kRandomInBin;
  /// Acceleration of gravity g [m/s^2] for the dispersion relation.
  double gravity = 9.81;
};

/// One random-phase realisation of a (possibly short-crested) irregular sea, the
/// single-summation model (each frequency carries exactly one direction, so the sea is
/// ergodic; Jefferys, "Directional seas should be ergodic", Applied Ocean Research 9(4),
/// 1987; Faltinsen, "Sea Loads on Ships and Offshore Structures", 1990, chapter 2):
///
///   eta(t, x, y) = sum_i a_i cos(omega_i t - k_i (x cos theta_i + y sin theta_i) + phi_i)
///   a_i = sqrt(2 S(omega_i) d_omega),  k_i = omega_i^2 / g
///
/// with N equal bins of width d_omega over [omega_min, omega_max], one frequency per bin
/// (random within it by default), phi_i uniform on [0, 2 pi) and theta_i drawn from the
/// spreading function by its inverse CDF. The realised variance sum a_i^2 / 2 is a
/// stratified estimate of the spectrum's m0 over the range.
///
/// Every component takes exactly three uniforms from the stream, in this order:
/// frequency offset, phase, direction (drawn even when long-crested or on bin centres).
/// So turning spreading on or off with the same stream keeps the frequencies and phases.
class WaveRealisation {
 public:
  /// Throws moorsim::InputError naming the field and value for N < 1, a non-positive or
  /// inverted frequency range, negative spreading exponent, g <= 0 or a non-finite value.
  WaveRealisation(const WaveSpectrum& spectrum, const WaveRealisationOptions& options,
                  RandomStream& stream);
  /// A given sea: these components as they are (no draw; bin_width() is 0). Throws
  /// moorsim::InputError for none, a frequency not > 0, an amplitude < 0, a value not
  /// finite, or g <= 0.
  WaveRealisation(std::vector<WaveComponent> given, double gravity);

  /// Surface elevation eta [m], positive up, at time t [s] and horizontal position
  /// (x north, y east) [m]. Allocation-free; cost N cosines.
  double Elevation(double t, double x, double y) const;

  /// eta at times t_start + j dt, j = 0 .. samples - 1, at (x, y): the same sum as
  /// Elevation, evaluated with one complex rotation per component and sample (vectorised
  /// over components) instead of N cosines, re-anchored with exact cosines every 512
  /// samples so rounding cannot accumulate (agrees with Elevation to ~1e-12 m).
  Eigen::VectorXd ElevationSeries(double t_start, double dt, int samples, double x = 0.0,
                                  double y = 0.0) const;

  const std::vector<WaveComponent>& components() const { return components_; }
  /// Variance of the realised elevation, sum a_i^2 / 2 [m^2] (the realisation's m0).
  double RealisedVariance() const;
  /// 4 sqrt(RealisedVariance()) [m].
  double RealisedSignificantHeight() const;

  double omega_min() const { return omega_min_; }
  double omega_max() const { return omega_max_; }
  /// Bin width d_omega [rad/s].
  double bin_width() const { return bin_width_; }

 private:
  std::vector<WaveComponent> components_;
  double omega_min_ = 0.0;
  double omega_max_ = 0.0;
  double bin_width_ = 0.0;
  // Structure-of-arrays copies for the sums: omega_i, a_i, phi_i and the wave-number
  // vector k_i (cos theta_i, sin theta_i).
  Eigen::ArrayXd omega_;
  Eigen::ArrayXd amplitude_;
  Eigen::ArrayXd phase_;
  Eigen::ArrayXd wave_number_north_;
  Eigen::ArrayXd wave_number_east_;

  void FillSums(double gravity);  // the arrays above from components_
};

}  // namespace moorsim::vessel
