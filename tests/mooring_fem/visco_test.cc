// The visco-elastic rope (Hall, Duong & Lozon 2023) against its closed form: a segment is
// a spring EA_d in series with a creep spring K and a dashpot c in parallel, so under a
// harmonic strain at frequency w its tension answers with the complex stiffness
//   K*(w) = EA_d (K + i w c) / (EA_d + K + i w c),
// EA_s = EA_d K / (EA_d + K) as w -> 0 and EA_d as w -> infinity. A vertical one-segment
// line heaved by its fairlead is exactly that strain; its tension, read as a load cell at
// the fairlead would, is fitted over whole periods once the start has died out. At rest it
// pulls with the quasi-static stiffness.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <numbers>
#include <ostream>
#include <vector>

#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kStatic = 1.0e8;    // EA_s [N]
constexpr double kDynamic = 3.0e8;   // EA_d [N]
constexpr double kCreepTime = 10.0;  // [s]
constexpr double kLength = 980.0;    // [m], the fairlead 988 m above the anchor: 0.82 % strain

MooringParameters VerticalRope(double slope = 0.0) {
  MooringParameters spec;
  spec.water.depth = 1000.0;
  LineType rope = testing::PolyesterType();
  rope.name = "rope";
  rope.axial_stiffness = kStatic;
  rope.visco_elastic = ViscoElastic{kDynamic, kCreepTime, slope};
  rope.axial_damping = 0.0;  // the creep element alone
  rope.axial_damping_ratio.reset();
  rope.drag_normal = rope.drag_tangential = 0.0;
  rope.added_mass_normal = rope.added_mass_tangential = 0.0;
  spec.line_types = {rope};
  spec.lines = {
      LineParameters::Uniform(1, "rope", kLength, 1, Vec3(0.0, 0.0, 1000.0), Vec3(0.0, 0.0, 12.0))};
  return spec;
}

// The segment's tension from the fairlead force: F_z = T + its half of the weight, less the
// half segment's mass times the fairlead's acceleration.
double Tension(LineSimulation& sim) {
  const SectionProperties& sp = sim.mooring().line(0).sections.front();
  const double half = 0.5 * sp.segment_length;
  return sim.FairleadForces()[0].z() - sp.weight_per_length * half +
         sp.mass_per_length * half * sim.Fairleads()[0].acceleration.z();
}

TEST(ViscoElasticRope, AtRestItPullsWithItsQuasiStaticStiffness) {
  LineSimulation sim(VerticalRope(), SolverSettings{}, PrescribedMotion{});
  const double strain = 988.0 / kLength - 1.0;
  EXPECT_NEAR(Tension(sim), kStatic * strain, 1e-9 * kStatic * strain);
  // And stays there: its creep is at rest.
  sim.AdvanceTo(50.0);
  EXPECT_NEAR(Tension(sim), kStatic * strain, 1e-6 * kStatic * strain);
}

// The rope's complex stiffness about its rest, from closed forms independent of the code
// under test. At rest both springs carry T0 = EA_s e0 (e0 the strain); the dynamic
// stiffness is D = EA_d + b T0, the creep spring K = EA_s D / (D - EA_s) and the creep
// strain T0 / K. Linearised there, T = D (strain - e) and c de/dt = T - T_m(e), with
//   M = dT_m/de = K / (1 + b EA_s^2 e / (D - EA_s)^2)   (T_m = K e, D = EA_d + b T_m),
//   D' = dD/de (strain - e) = b M T0 / D,
// give K*(w) = D (M + i w c) / (M + i w c + D - D'): EA_s as w -> 0 (the quasi-static
// line stays linear), D as w -> infinity. With b = 0: M = K, D' = 0, the constant rope.
std::complex<double> ComplexStiffness(double w, double slope) {
  const double strain = 988.0 / kLength - 1.0;
  const double T0 = kStatic * strain;
  const double K0 = kStatic * kDynamic / (kDynamic - kStatic);
  const double c = K0 * kCreepTime;  // the dashpot of the unloaded rope
  const double D = kDynamic + slope * T0;
  const double K = kStatic * D / (D - kStatic);
  const double e = T0 / K;
  const double M = K / (1.0 + slope * kStatic * kStatic * e / ((D - kStatic) * (D - kStatic)));
  const double D_prime = slope * M * T0 / D;
  const std::complex<double> iwc(0.0, w * c);
  return D * (M + iwc) / (M + iwc + D - D_prime);
}

// Its frequency times the creep time, and the dynamic stiffness's slope with the mean load.
struct Cycle {
  double wt, slope;
};
void PrintTo(const Cycle& c, std::ostream* out) {
  *out << "w tau " << c.wt << ", slope " << c.slope;
}

class ViscoElasticCycle : public ::testing::TestWithParam<Cycle> {};

TEST_P(ViscoElasticCycle, TensionFollowsTheComplexStiffness) {
  const double wt = GetParam().wt;
  const double slope = GetParam().slope;
  const double w = wt / kCreepTime;
  const double period = 2.0 * std::numbers::pi / w;
  PrescribedMotion heave;
  // 0.1 m on 988 m: a strain of 1e-4 about 8.2e-3, where the rope is linear within 1e-5.
  heave.components[PrescribedMotion::kHeave] = {{0.1, period}};
  SolverSettings tight;
  tight.rtol = 1e-8;
  tight.atol_position = 1e-8;
  tight.atol_velocity = 1e-8;
  LineSimulation sim(VerticalRope(slope), tight, heave);
  // The start dies out with the relaxation time c / (EA_d + K) < the creep time.
  const double settle = std::ceil(10.0 * kCreepTime / period) * period;
  sim.AdvanceTo(settle);
  // Least squares over four periods: x(t) = x0 + xs sin(w t) + xc cos(w t).
  constexpr int kSamples = 400;
  Eigen::MatrixXd basis(kSamples, 3);
  Eigen::VectorXd strain(kSamples), tension(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double t = settle + 4.0 * period * (i + 1) / kSamples;
    sim.AdvanceTo(t);
    basis.row(i) << 1.0, std::sin(w * t), std::cos(w * t);
    strain(i) = (1000.0 - sim.Fairleads()[0].position.z()) / kLength - 1.0;
    tension(i) = Tension(sim);
  }
  const Eigen::Vector3d e = basis.colPivHouseholderQr().solve(strain);
  const Eigen::Vector3d T = basis.colPivHouseholderQr().solve(tension);
  const std::complex<double> measured =
      std::complex<double>(T(1), T(2)) / std::complex<double>(e(1), e(2));
  const std::complex<double> expected = ComplexStiffness(w, slope);
  EXPECT_LT(std::abs(measured - expected), 1e-4 * std::abs(expected))
      << "w tau " << wt << ", slope " << slope << ": " << measured << " against " << expected;
  RecordProperty("storage_modulus_N", std::to_string(measured.real()));
  RecordProperty("loss_angle_deg", std::to_string(std::arg(measured) * 180.0 / std::numbers::pi));
}

// Slow cycles see the quasi-static stiffness, fast ones the dynamic; the creep time
// between them, with the largest loss. A slope of 100 (about three times polyester's)
// raises the dynamic stiffness at this rope's mean load by 27 %.
INSTANTIATE_TEST_SUITE_P(Frequencies, ViscoElasticCycle,
                         ::testing::Values(Cycle{0.05, 0.0}, Cycle{1.0, 0.0}, Cycle{20.0, 0.0},
                                           Cycle{0.05, 100.0}, Cycle{1.0, 100.0},
                                           Cycle{20.0, 100.0}),
                         [](const auto& info) {
                           const double wt = info.param.wt;
                           return std::string(wt < 0.5   ? "Slow"
                                              : wt < 5.0 ? "AtTheCreepTime"
                                                         : "Fast") +
                                  (info.param.slope > 0.0 ? "StiffeningWithLoad" : "");
                         });

// With the stiffness rising with the load the rope still rests at its quasi-static
// stiffness, and stays there.
TEST(ViscoElasticRope, StiffeningWithLoadItStillRestsAtItsQuasiStaticStiffness) {
  LineSimulation sim(VerticalRope(100.0), SolverSettings{}, PrescribedMotion{});
  const double strain = 988.0 / kLength - 1.0;
  EXPECT_NEAR(Tension(sim), kStatic * strain, 1e-9 * kStatic * strain);
  sim.AdvanceTo(50.0);
  EXPECT_NEAR(Tension(sim), kStatic * strain, 1e-6 * kStatic * strain);
}

}  // namespace
}  // namespace moorsim::mooring_fem
