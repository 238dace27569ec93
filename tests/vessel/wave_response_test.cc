// The hull's response to a realised sea (vessel/wave_response.h): first-order motion
// against HydroData's RAOs computed directly and against the kinematics of long waves
// (phase convention), Newman's drift against its mean and the spectrum, the seed FPSO's
// drift directions, the statistics of a long heave record, and bad options.
#include "vessel/wave_response.h"
#include "core/angles.h"
#include "tests/vessel/fpso_hydro.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "vessel/hydro_data.h"
#include "vessel/waves.h"

namespace moorsim::vessel {
namespace {

constexpr double kG = 9.81;
constexpr std::complex<double> kI(0.0, 1.0);

using test_data::Fpso;

/// A white spectrum: every component gets the same amplitude. Lets a test choose a
/// single component's frequency and amplitude exactly.
class FlatSpectrum final : public WaveSpectrum {
 public:
  FlatSpectrum(double density, double peak) : density_(density), peak_(peak) {}
  double Density(double omega) const override { return omega > 0.0 ? density_ : 0.0; }
  double PeakFrequency() const override { return peak_; }

 private:
  double density_;
  double peak_;
};

/// One regular wave of frequency omega [rad/s] and amplitude a [m] travelling toward the
/// compass direction `direction` [rad], with the phase the stream gives it: one bin of
/// width 2e-3 rad/s centred on omega, S = a^2 / (2 d_omega).
WaveRealisation OneComponentSea(double omega, double amplitude, double direction,
                                std::uint64_t seed) {
  const double bin = 2e-3;
  const FlatSpectrum spectrum(amplitude * amplitude / (2.0 * bin), omega);
  WaveRealisationOptions options;
  options.components = 1;
  options.omega_min = omega - 0.5 * bin;
  options.omega_max = omega + 0.5 * bin;
  options.frequency_sampling = FrequencySampling::kBinCentre;
  options.mean_direction = direction;
  RandomStream stream = RandomStream::Derive(seed, "waves");
  return WaveRealisation(spectrum, options, stream);
}

/// The seed sea state (JONSWAP Hs 2.5 m, Tp 7 s, gamma 3.3).
JonswapSpectrum SeedSpectrum() {
  JonswapParameters sea;
  sea.significant_height = 2.5;
  sea.peak_period = 7.0;
  sea.peak_enhancement = 3.3;
  return JonswapSpectrum(sea);
}

WaveRealisation SeedSea(const WaveRealisationOptions& options, std::uint64_t seed) {
  const JonswapSpectrum spectrum = SeedSpectrum();
  RandomStream stream = RandomStream::Derive(seed, "waves");
  return WaveRealisation(spectrum, options, stream);
}

/// The component's phase at (x, y), written out from waves.h.
double Phase(const WaveComponent& c, double t, double x, double y) {
  const double k = c.omega * c.omega / kG;
  return c.omega * t - k * (x * std::cos(c.direction) + y * std::sin(c.direction)) + c.phase;
}

/// The largest |average of cos(f t_n + c)| over samples t_n = n dt, n = 0 .. samples − 1,
/// for any c: |Σ e^{i f n dt}| / samples = |sin(samples f dt / 2)| / (samples |sin(f dt / 2)|)
/// ≤ 1 / (samples |sin(f dt / 2)|), and never more than 1.
double AverageCosineBound(double frequency, double dt, int samples) {
  const double s = std::abs(std::sin(0.5 * frequency * dt));
  return std::min(1.0, 1.0 / (samples * s));
}

/// Antisymmetric modes (sway, roll, yaw) vanish in head and following seas for a hull
/// symmetric about its centre plane, but WAMIT's numbers there are round-off, not zero
/// (drift: up to 16 N·m/m² of yaw against 1e6-1e7 elsewhere; RAOs: 1e-9 of the beam-sea
/// values). HydroData mirrors them, so its β dependence jumps from v to −v across β = 0
/// and ±π, while the heading grid blends linearly through the jump: within one cell of
/// those headings the two differ by at most the size of that noise, which this returns
/// (|v(0)| + |v(π)| of mode j at ω; zero for the symmetric modes).
double SymmetryNoise(const ComplexVec6& at_zero, const ComplexVec6& at_pi, int j) {
  return kPortStarboardMirror[j] < 0.0 ? std::abs(at_zero[j]) + std::abs(at_pi[j]) : 0.0;
}
double RaoSymmetryNoise(double omega, int j) {
  return SymmetryNoise(Fpso().Rao(omega, 0.0), Fpso().Rao(omega, kPi), j);
}
double DriftSymmetryNoise(double omega, int j) {
  return SymmetryNoise(Fpso().Drift(omega, 0.0).cast<std::complex<double>>(),
                       Fpso().Drift(omega, kPi).cast<std::complex<double>>(), j);
}

// ---------------------------------------------------------------------------------------
// First-order motion

TEST(WaveResponse, OneComponentMotionIsTheRaoTimesTheWave) {
  // ξ = Re{RAO(ω, θ − ψ) a e^{iχ}} written out with HydroData::Rao at the exact heading.
  // Default 2° grid: every WAMIT heading (10° apart) is a grid node, HydroData is linear in
  // β between them, so the grid's linear blend reproduces it up to the rounding of the
  // node positions and weights (~1e-15 relative; 1e-9 of the mode's amplitude leaves
  // room), and up to the data's symmetry noise near β = 0, ±π (SymmetryNoise). Headings
  // include grid nodes, off-grid values, the mirrored half (β > 0), head seas from either
  // side and ψ beyond ±2π.
  const HydroData& hydro = Fpso();
  const double omega = 0.8;
  const double amplitude = 1.3;
  const double direction = 0.7;
  const WaveRealisation sea = OneComponentSea(omega, amplitude, direction, 4);
  const WaveComponent& c = sea.components().front();
  ASSERT_NEAR(c.omega, omega, 1e-12);
  ASSERT_NEAR(c.amplitude, amplitude, 1e-12);
  const WaveResponse response(hydro, sea);
  EXPECT_EQ(response.heading_cells(), 180);

  const double x = 120.0;
  const double y = -45.0;
  for (const double psi :
       {0.0, 0.3, -2.1, 0.7 - kPi, 0.7 + kPi, 53.37 * kDegree, 3.0, 7.5, -13.0}) {
    const ComplexVec6 rao = hydro.Rao(omega, direction - psi);
    for (const double t : {0.0, 1.7, 33.3, 401.0}) {
      const std::complex<double> wave = amplitude * std::exp(kI * Phase(c, t, x, y));
      Vec6 xi;
      Vec6 xi_dot;
      response.Motion(t, x, y, psi, &xi, &xi_dot);
      for (int j = 0; j < 6; ++j) {
        const double tolerance =
            amplitude * (1e-9 * std::abs(rao[j]) + RaoSymmetryNoise(omega, j)) + 1e-300;
        EXPECT_NEAR(xi[j], (rao[j] * wave).real(), tolerance)
            << "mode " << j + 1 << ", psi = " << psi << ", t = " << t;
        EXPECT_NEAR(xi_dot[j], (kI * omega * rao[j] * wave).real(), tolerance * omega)
            << "mode " << j + 1 << ", psi = " << psi << ", t = " << t;
      }
    }
  }
}

TEST(WaveResponse, CoarseHeadingGridStaysWithinItsInterpolationBound) {
  // A 7° step (52 cells of 6.92°) does not divide WAMIT's 10°, so kinks of HydroData's
  // piecewise-linear β dependence fall inside grid cells. Linear interpolation across a
  // cell of width h holding one kink where the slope jumps by Δs errs by at most
  // c (h − c) / h |Δs| ≤ h |Δs| / 4 (c the kink's position in the cell; every cell here is
  // narrower than 10°, so it holds at most one kink). Δs is taken from HydroData at this ω
  // over the whole circle, per mode; the symmetry noise at β = 0, ±π adds to it.
  const HydroData& hydro = Fpso();
  const double omega = 0.8;
  const double amplitude = 1.0;
  const double direction = -0.4;
  const WaveRealisation sea = OneComponentSea(omega, amplitude, direction, 9);
  const WaveComponent& c = sea.components().front();
  WaveResponseOptions options;
  options.heading_step = 7.0 * kDegree;
  const WaveResponse response(hydro, sea, options);
  ASSERT_EQ(response.heading_cells(), 52);
  const double h = response.heading_step();

  // Slopes of the 36 ten-degree pieces from −180° to 180°, and their largest jump.
  std::array<double, 6> slope_jump{};
  std::vector<ComplexVec6> slopes;
  for (int p = 0; p < 36; ++p) {
    const double b0 = (-180.0 + 10.0 * p) * kDegree;
    slopes.push_back((hydro.Rao(omega, b0 + 10.0 * kDegree) - hydro.Rao(omega, b0)) /
                     (10.0 * kDegree));
  }
  for (int p = 0; p < 36; ++p) {
    for (int j = 0; j < 6; ++j) {
      slope_jump[j] = std::max(slope_jump[j], std::abs(slopes[(p + 1) % 36][j] - slopes[p][j]));
    }
  }

  std::array<double, 6> worst_error{};
  for (int step = 0; step < 720; ++step) {
    const double psi = (0.5 * step) * kDegree + 0.01;
    const ComplexVec6 rao = hydro.Rao(omega, direction - psi);
    const double t = 3.0;
    const std::complex<double> wave = amplitude * std::exp(kI * Phase(c, t, 10.0, 20.0));
    Vec6 xi;
    response.Motion(t, 10.0, 20.0, psi, &xi, nullptr);
    for (int j = 0; j < 6; ++j) {
      // |Re{e w}| ≤ |e| |w| for the complex interpolation error e.
      const double error = std::abs(xi[j] - (rao[j] * wave).real());
      worst_error[j] = std::max(worst_error[j], error);
      EXPECT_LE(error, amplitude * (h / 4.0 * slope_jump[j] * (1.0 + 1e-9) +
                                    RaoSymmetryNoise(omega, j) + 1e-12))
          << "mode " << j + 1 << ", psi = " << psi;
    }
  }
  for (int j = 0; j < 6; ++j) {
    RecordProperty("worst_error_over_bound_mode_" + std::to_string(j + 1),
                   std::to_string(worst_error[j] / (amplitude * h / 4.0 * slope_jump[j])));
  }
}

TEST(WaveResponse, MotionRateIsTheTimeDerivative) {
  // Central difference with step d: truncation error ≤ A ω³ d² / 6 per component
  // (A = a |RAO_j|), round-off ~ ε |χ| A / d from the phase's rounding. Summed over the
  // seed sea's components, with a factor 2 of room.
  WaveRealisationOptions options;
  options.spreading_exponent = 10.0;
  options.mean_direction = 1.1;
  const WaveRealisation sea = SeedSea(options, 17);
  const WaveResponse response(Fpso(), sea);
  const double d = 1e-3;
  const double x = -30.0;
  const double y = 75.0;
  const double psi = 0.35;
  for (const double t : {5.0, 61.0, 250.0}) {
    Vec6 xi_dot;
    Vec6 before;
    Vec6 after;
    response.Motion(t, x, y, psi, nullptr, &xi_dot);
    response.Motion(t - d, x, y, psi, &before, nullptr);
    response.Motion(t + d, x, y, psi, &after, nullptr);
    for (int j = 0; j < 6; ++j) {
      double tolerance = 0.0;
      for (const WaveComponent& c : sea.components()) {
        const double a = c.amplitude * std::abs(Fpso().Rao(c.omega, c.direction - psi)[j]);
        const double w = c.omega;
        tolerance += a * (w * w * w * d * d / 6.0 + 1e-15 * (w * t + 10.0) / d);
      }
      EXPECT_NEAR((after[j] - before[j]) / (2.0 * d), xi_dot[j], 2.0 * tolerance)
          << "mode " << j + 1 << ", t = " << t;
    }
  }
}

TEST(WaveResponse, LongWaveHeaveFollowsTheSurfaceDownward) {
  // In a long wave (ω = 0.06 rad/s, T = 105 s, λ = 17 km) the hull rides the surface:
  // heave, positive down, is −η at the body origin, in phase. Checked against
  // WaveRealisation::Elevation at the vessel's (x, y), so the phase convention of the
  // RAOs, of χ and of the realisation must all agree (a sign or conjugation error is an
  // error of 2a here). 2 % of a covers what physics allows: the heave resonance
  // (ω_n = 0.60 rad/s, 10.4 s) amplifies by 1 / (1 − (ω/ω_n)²) ≈ 1.01, and pressure decays
  // over the 12 m draught as e^{−kT} ≈ 0.996. Measured: 1.8e-4 of a.
  const double omega = 0.06;
  const double amplitude = 2.0;
  double worst_overall = 0.0;
  for (const double direction : {0.0, 1.3, -2.4, kPi}) {
    const WaveRealisation sea = OneComponentSea(omega, amplitude, direction, 21);
    const WaveResponse response(Fpso(), sea);
    for (const double psi : {0.0, 0.9, -1.7}) {
      const double x = 350.0;
      const double y = -1200.0;
      double worst = 0.0;
      for (int n = 0; n < 40; ++n) {
        const double t = 2.7 * n;  // one wave period in 40 samples
        Vec6 xi;
        response.Motion(t, x, y, psi, &xi, nullptr);
        worst = std::max(worst, std::abs(xi[2] + sea.Elevation(t, x, y)));
      }
      EXPECT_LT(worst, 0.02 * amplitude) << "direction " << direction << ", psi " << psi;
      worst_overall = std::max(worst_overall, worst);
    }
  }
  RecordProperty("worst_heave_plus_elevation_over_amplitude",
                 std::to_string(worst_overall / amplitude));
}

// ---------------------------------------------------------------------------------------
// Drift

TEST(WaveResponse, MeanDriftIsTheSpectralSum) {
  // MeanDrift = Σ a_i² D = Σ 2 S(ω_i) Δω D(ω_i, θ_i − ψ), from the spectrum and
  // HydroData::Drift at the exact heading. 1e-9 of Σ |terms|: a_i² = 2 S Δω is rounded
  // through a square root, and the 2° grid reproduces HydroData's headings (see above),
  // but for the data's symmetry noise near β = 0, ±π (SymmetryNoise).
  const JonswapSpectrum spectrum = SeedSpectrum();
  WaveRealisationOptions options;
  options.spreading_exponent = 4.0;
  options.mean_direction = -0.6;
  const WaveRealisation sea = SeedSea(options, 3);
  for (const bool all_modes : {false, true}) {
    WaveResponseOptions response_options;
    response_options.drift_all_modes = all_modes;
    const WaveResponse response(Fpso(), sea, response_options);
    for (const double psi : {0.0, 1.0, -2.5, 4.0}) {
      Vec6 expected = Vec6::Zero();
      Vec6 scale = Vec6::Zero();
      Vec6 noise = Vec6::Zero();
      for (const WaveComponent& c : sea.components()) {
        const Vec6 term = 2.0 * spectrum.Density(c.omega) * sea.bin_width() *
                          Fpso().Drift(c.omega, c.direction - psi);
        expected += term;
        scale += term.cwiseAbs();
        for (int j = 0; j < 6; ++j) {
          noise[j] +=
              2.0 * spectrum.Density(c.omega) * sea.bin_width() * DriftSymmetryNoise(c.omega, j);
        }
      }
      const Vec6 mean = response.MeanDrift(psi);
      for (int j = 0; j < 6; ++j) {
        const bool kept = all_modes || j == 0 || j == 1 || j == 5;
        if (kept) {
          EXPECT_NEAR(mean[j], expected[j], 1e-9 * scale[j] + noise[j])
              << "mode " << j + 1 << ", psi " << psi;
        } else {
          EXPECT_EQ(mean[j], 0.0) << "mode " << j + 1;
        }
      }
    }
  }
}

TEST(WaveResponse, DriftLoadAveragesToTheMeanDriftOverOnePeriod) {
  // On bin centres every difference frequency ω_i − ω_k is a multiple of Δω, so the drift
  // load repeats every 2π/Δω (400 s here) and its average over N_s equally spaced samples
  // of one period is exact once N_s exceeds the highest multiple (N − 1 = 199): what is
  // left is rounding, 1e-9 of Σ a_i² |D_ij|.
  WaveRealisationOptions options;
  options.frequency_sampling = FrequencySampling::kBinCentre;
  options.mean_direction = 2.0;
  options.spreading_exponent = 6.0;
  const WaveRealisation sea = SeedSea(options, 8);
  const WaveResponse response(Fpso(), sea);
  const double psi = 0.45;
  const double x = 60.0;
  const double y = 15.0;
  const int samples = 256;
  const double dt = 2.0 * kPi / sea.bin_width() / samples;
  Vec6 average = Vec6::Zero();
  for (int n = 0; n < samples; ++n) average += response.DriftLoad(n * dt, x, y, psi);
  average /= samples;

  Vec6 scale = Vec6::Zero();
  for (const WaveComponent& c : sea.components()) {
    scale += c.amplitude * c.amplitude * Fpso().Drift(c.omega, c.direction - psi).cwiseAbs();
  }
  const Vec6 mean = response.MeanDrift(psi);
  for (int j : {0, 1, 5}) {
    EXPECT_NEAR(average[j], mean[j], 1e-9 * scale[j]) << "mode " << j + 1;
  }
  for (int j : {2, 3, 4}) EXPECT_EQ(average[j], 0.0);
}

TEST(WaveResponse, DriftLoadAveragesToTheMeanDriftOverALongRecord) {
  // Random frequencies in their bins: no common period. |z₊|² − |z₋|² = Σ_i a_i² D_ij plus,
  // for each pair i ≠ k on the same side of the sign split, 2 q_i q_k cos((ω_i − ω_k) t + c)
  // with q = a √|D|. Each such cosine averages over the record to at most
  // 1 / (N_s |sin((ω_i − ω_k) dt / 2)|) ≈ 2 / (|ω_i − ω_k| T), so the slowest difference
  // frequencies set the tolerance, which is this sum over pairs (a strict bound, not a
  // statistical guess) plus rounding.
  WaveRealisationOptions options;
  options.mean_direction = -2.2;
  options.spreading_exponent = 10.0;
  const WaveRealisation sea = SeedSea(options, 12);
  const WaveResponse response(Fpso(), sea);
  const double psi = 0.8;
  const double dt = 1.0;
  const int samples = 10800;  // 3 h
  Vec6 average = Vec6::Zero();
  for (int n = 0; n < samples; ++n) average += response.DriftLoad(n * dt, 0.0, 0.0, psi);
  average /= samples;

  const std::vector<WaveComponent>& components = sea.components();
  const Vec6 mean = response.MeanDrift(psi);
  for (int j : {0, 1, 5}) {
    std::vector<double> q;
    std::vector<bool> positive;
    double scale = 0.0;
    for (const WaveComponent& c : components) {
      const double d = Fpso().Drift(c.omega, c.direction - psi)[j];
      q.push_back(c.amplitude * std::sqrt(std::abs(d)));
      positive.push_back(d > 0.0);
      scale += c.amplitude * c.amplitude * std::abs(d);
    }
    double bound = 1e-9 * scale;
    for (std::size_t i = 0; i < components.size(); ++i) {
      for (std::size_t k = i + 1; k < components.size(); ++k) {
        if (positive[i] != positive[k]) continue;
        bound += 2.0 * q[i] * q[k] *
                 AverageCosineBound(components[i].omega - components[k].omega, dt, samples);
      }
    }
    EXPECT_NEAR(average[j], mean[j], bound) << "mode " << j + 1;
    RecordProperty("mode_" + std::to_string(j + 1) + "_error_over_bound",
                   std::to_string(std::abs(average[j] - mean[j]) / bound));
    RecordProperty("mode_" + std::to_string(j + 1) + "_bound_over_mean",
                   std::to_string(bound / std::abs(mean[j])));
  }
}

TEST(WaveResponse, SeedFpsoDriftsDownWaveInHeadAndBeamSeas) {
  // The seed sea state, long-crested, realisation seed 1 (realised Hs 2.505 m). Head seas
  // (travelling toward −x body, β = ±π) push the hull aft; beam seas from starboard
  // (travelling to port, β = −π/2) push it to port. Measured: head seas −92.4 kN surge;
  // beam seas −737 kN sway, 94 % of the wall limit ρ g L m0 = 786 kN (full reflection,
  // ½ ρ g a² per metre of a 200 m side; Faltinsen 1990, ch. 5), +10.7 kN surge and
  // +1.15 MN·m yaw. Head seas are symmetric about the centre plane: sway and yaw vanish
  // to WAMIT's rounding.
  //
  // Each MeanDrift is also checked against the spectrum's own mean drift
  // ∫ 2 S(ω) D(ω, β) dω over the realisation's range (Simpson, 4000 panels). A realisation
  // samples the integrand f = 2 S D once per bin of width Δω, so it is off by at most
  // Σ_bins Δω (max − min of f in the bin) ≤ Δω TV(f), TV the total variation of f (summed
  // on the Simpson nodes), plus 1e-3 for the quadrature (the integrand has kinks at
  // the table's frequencies, so Simpson is only second order there; 4000 panels of
  // 8e-4 rad/s against table steps of 0.1 rad/s).
  const JonswapSpectrum spectrum = SeedSpectrum();
  const double psi = 0.4;  // any heading: only θ − ψ matters
  const auto mean_drift = [&](double beta, const char* name) {
    WaveRealisationOptions options;
    options.mean_direction = psi + beta;
    const WaveRealisation sea = SeedSea(options, 1);
    const Vec6 mean = WaveResponse(Fpso(), sea).MeanDrift(psi);

    const int panels = 4000;
    const double h = (sea.omega_max() - sea.omega_min()) / panels;
    Vec6 integral = Vec6::Zero();
    Vec6 variation = Vec6::Zero();
    Vec6 previous = Vec6::Zero();
    for (int n = 0; n <= panels; ++n) {
      const double omega = sea.omega_min() + n * h;
      const Vec6 f = 2.0 * spectrum.Density(omega) * Fpso().Drift(omega, beta);
      const double weight = (n == 0 || n == panels) ? 1.0 : (n % 2 == 1 ? 4.0 : 2.0);
      integral += weight * h / 3.0 * f;
      if (n > 0) variation += (f - previous).cwiseAbs();
      previous = f;
    }
    for (int j : {0, 1, 5}) {
      EXPECT_NEAR(mean[j], integral[j],
                  sea.bin_width() * variation[j] + 1e-3 * std::abs(integral[j]))
          << name << ", mode " << j + 1;
      RecordProperty(std::string(name) + "_mode_" + std::to_string(j + 1) + "_spectral",
                     std::to_string(integral[j]));
      RecordProperty(std::string(name) + "_mode_" + std::to_string(j + 1) + "_realised",
                     std::to_string(mean[j]));
    }
    RecordProperty(std::string(name) + "_realised_hs_m",
                   std::to_string(sea.RealisedSignificantHeight()));
    return mean;
  };

  const Vec6 head = mean_drift(kPi, "head");
  EXPECT_LT(head[0], 0.0);
  EXPECT_LT(std::abs(head[1]), 1e-3 * std::abs(head[0]));
  EXPECT_LT(std::abs(head[5]), 1e-3 * 100.0 * std::abs(head[0]));  // 100 m lever arm

  const Vec6 beam = mean_drift(-kPi / 2.0, "beam");
  EXPECT_LT(beam[1], 0.0);
  EXPECT_GT(std::abs(beam[1]), 5.0 * std::abs(head[0]));
}

// ---------------------------------------------------------------------------------------
// Statistics of the motion

TEST(WaveResponse, HeaveVarianceIsTheSumOfComponentVariances) {
  // var ξ₃ = Σ A_i² / 2 with A_i = a_i |RAO₃(ω_i, β_i)| for a random-phase sum.
  //
  // Exact form first: with ω_i = (m + i + ½) Δω every sum and difference frequency is a
  // multiple of Δω/2, so ξ₃² repeats every 4π/Δω; averaged over N_s > 2 ω_max / (Δω/2)
  // equally spaced samples of that period the cross terms cancel exactly. Rounding only:
  // 1e-9.
  const FlatSpectrum white(0.2, 1.0);  // 0.2 m² s: Hs = 4 sqrt(0.2 · 3.2) = 3.2 m
  WaveRealisationOptions options;
  options.frequency_sampling = FrequencySampling::kBinCentre;
  options.omega_min = 28 * 0.016;
  options.omega_max = 228 * 0.016;
  options.mean_direction = 0.9;
  options.spreading_exponent = 8.0;
  RandomStream stream = RandomStream::Derive(2, "waves");
  const WaveRealisation periodic_sea(white, options, stream);
  ASSERT_NEAR(periodic_sea.bin_width(), 0.016, 1e-15);
  const double psi = -0.3;

  const auto expected_variance = [&](const WaveRealisation& sea) {
    double variance = 0.0;
    for (const WaveComponent& c : sea.components()) {
      const double a = c.amplitude * std::abs(Fpso().Rao(c.omega, c.direction - psi)[2]);
      variance += 0.5 * a * a;
    }
    return variance;
  };
  const auto mean_square = [&](const WaveResponse& response, double dt, int samples) {
    double sum = 0.0;
    for (int n = 0; n < samples; ++n) {
      Vec6 xi;
      response.Motion(n * dt, 40.0, -25.0, psi, &xi, nullptr);
      sum += xi[2] * xi[2];
    }
    return sum / samples;
  };

  {
    const WaveResponse response(Fpso(), periodic_sea);
    const int samples = 1024;  // > 2 · 228 · 0.016 / 0.008 = 912
    const double period = 4.0 * kPi / 0.016;
    const double expected = expected_variance(periodic_sea);
    EXPECT_NEAR(mean_square(response, period / samples, samples), expected, 1e-9 * expected);
  }

  // The seed sea over 3 h. ξ₃² = ½ Σ_i A_i² + ½ Σ_{i≠k} A_i A_k cos(Δ_ik t + c) +
  // ½ Σ_{i,k} A_i A_k cos(Σ_ik t + c'): the tolerance bounds each cosine's average by
  // AverageCosineBound, dominated by the slowest difference frequencies.
  {
    WaveRealisationOptions seed_options;
    seed_options.mean_direction = 2.6;
    seed_options.spreading_exponent = 10.0;
    const WaveRealisation sea = SeedSea(seed_options, 5);
    const WaveResponse response(Fpso(), sea);
    // 0.5 s keeps every sum frequency (≤ 7.2 rad/s) below the sampling's 2π / dt: no
    // aliasing to zero frequency, |sin(f dt / 2)| ≥ 0.97 at the top.
    const double dt = 0.5;
    const int samples = 21600;  // 3 h
    std::vector<double> a;
    for (const WaveComponent& c : sea.components()) {
      a.push_back(c.amplitude * std::abs(Fpso().Rao(c.omega, c.direction - psi)[2]));
    }
    const std::vector<WaveComponent>& components = sea.components();
    double bound = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t k = 0; k < a.size(); ++k) {
        const double wi = components[i].omega;
        const double wk = components[k].omega;
        if (i != k) bound += 0.5 * a[i] * a[k] * AverageCosineBound(wi - wk, dt, samples);
        bound += 0.5 * a[i] * a[k] * AverageCosineBound(wi + wk, dt, samples);
      }
    }
    const double expected = expected_variance(sea);
    const double measured = mean_square(response, dt, samples);
    EXPECT_NEAR(measured, expected, bound + 1e-9 * expected);
    RecordProperty("heave_std_m", std::to_string(std::sqrt(expected)));
    RecordProperty("relative_error", std::to_string(measured / expected - 1.0));
    RecordProperty("relative_bound", std::to_string(bound / expected));
  }
}

// ---------------------------------------------------------------------------------------
// Evaluate's contract

TEST(WaveResponse, EvaluateAgreesWithTheSeparateMethods) {
  WaveRealisationOptions options;
  options.spreading_exponent = 5.0;
  const WaveRealisation sea = SeedSea(options, 31);
  WaveResponseOptions response_options;
  response_options.drift_all_modes = true;
  const WaveResponse response(Fpso(), sea, response_options);
  EXPECT_EQ(response.drift_modes().size(), 6u);
  const double t = 77.0;
  const double x = 12.0;
  const double y = -8.0;
  const double psi = 2.2;
  Vec6 xi;
  Vec6 xi_dot;
  Vec6 drift;
  response.Evaluate(t, x, y, psi, &xi, &xi_dot, &drift);
  Vec6 xi_alone;
  Vec6 xi_dot_alone;
  response.Motion(t, x, y, psi, &xi_alone, &xi_dot_alone);
  EXPECT_EQ(xi, xi_alone);
  EXPECT_EQ(xi_dot, xi_dot_alone);
  EXPECT_EQ(drift, response.DriftLoad(t, x, y, psi));
  // All six modes kept: heave, roll and pitch drift are not zero.
  EXPECT_NE(drift[2], 0.0);
  EXPECT_NE(drift[3], 0.0);
  // Only ψ mod 2π matters (to the rounding of ψ / 2π).
  Vec6 turned;
  response.Evaluate(t, x, y, psi + 4.0 * kPi, &turned, nullptr, nullptr);
  EXPECT_LT((turned - xi).norm(), 1e-9 * xi.norm());
  // Nothing asked, nothing done; no crash.
  response.Evaluate(t, x, y, psi, nullptr, nullptr, nullptr);
}

TEST(WaveResponse, NonFiniteStateGivesNan) {
  // No exception on the RHS path: NaN reaches the ODE adapter, which cuts the step.
  const WaveRealisation sea = SeedSea(WaveRealisationOptions{}, 1);
  const WaveResponse response(Fpso(), sea);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const std::array<double, 4>& state :
       {std::array<double, 4>{nan, 0.0, 0.0, 0.0}, std::array<double, 4>{0.0, inf, 0.0, 0.0},
        std::array<double, 4>{0.0, 0.0, -inf, 0.0}, std::array<double, 4>{0.0, 0.0, 0.0, nan}}) {
    Vec6 xi;
    Vec6 xi_dot;
    Vec6 drift;
    response.Evaluate(state[0], state[1], state[2], state[3], &xi, &xi_dot, &drift);
    EXPECT_TRUE(xi.array().isNaN().all());
    EXPECT_TRUE(xi_dot.array().isNaN().all());
    EXPECT_TRUE(drift.array().isNaN().all());
  }
  EXPECT_TRUE(response.MeanDrift(nan).array().isNaN().all());
}

// ---------------------------------------------------------------------------------------
// Bad input

TEST(WaveResponseOptionsTest, BadHeadingStepIsRejectedByName) {
  const WaveRealisation sea = OneComponentSea(0.8, 1.0, 0.0, 1);
  for (const double step :
       {0.0, -2.0 * kDegree, 46.0 * kDegree, 0.05 * kDegree,
        std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    WaveResponseOptions options;
    options.heading_step = step;
    try {
      WaveResponse response(Fpso(), sea, options);
      ADD_FAILURE() << "heading_step = " << step << " was accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("WaveResponseOptions.heading_step"),
                std::string::npos)
          << error.what();
    }
  }
  // The limits themselves are fine.
  for (const double step : {45.0 * kDegree, kPi / 4.0, 0.1 * kDegree}) {
    WaveResponseOptions options;
    options.heading_step = step;
    EXPECT_NO_THROW(WaveResponse(Fpso(), sea, options)) << step;
  }
}

TEST(WaveResponseOptionsTest, BadGravityAndMissingTablesAreRejected) {
  const WaveRealisation sea = OneComponentSea(0.8, 1.0, 0.0, 1);
  for (const double gravity : {0.0, -9.81, std::numeric_limits<double>::quiet_NaN()}) {
    WaveResponseOptions options;
    options.gravity = gravity;
    EXPECT_THROW(WaveResponse(Fpso(), sea, options), InputError) << gravity;
  }
  HydroData no_rao = Fpso();
  no_rao.motion_rao.clear();
  try {
    WaveResponse response(no_rao, sea);
    ADD_FAILURE() << "accepted data without RAOs";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(".4'"), std::string::npos) << error.what();
  }
  HydroData no_drift = Fpso();
  no_drift.mean_drift.clear();
  try {
    WaveResponse response(no_drift, sea);
    ADD_FAILURE() << "accepted data without drift";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(".9'"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace moorsim::vessel
