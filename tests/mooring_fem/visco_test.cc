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

MooringParameters VerticalRope() {
  MooringParameters spec;
  spec.water.depth = 1000.0;
  LineType rope = testing::PolyesterType();
  rope.name = "rope";
  rope.axial_stiffness = kStatic;
  rope.visco_elastic = ViscoElastic{kDynamic, kCreepTime};
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

class ViscoElasticCycle : public ::testing::TestWithParam<double> {};

TEST_P(ViscoElasticCycle, TensionFollowsTheComplexStiffness) {
  const double wt = GetParam();  // w times the creep time
  const double w = wt / kCreepTime;
  const double period = 2.0 * std::numbers::pi / w;
  PrescribedMotion heave;
  heave.components[PrescribedMotion::kHeave] = {{1.0, period}};
  SolverSettings tight;
  tight.rtol = 1e-8;
  tight.atol_position = 1e-8;
  tight.atol_velocity = 1e-8;
  LineSimulation sim(VerticalRope(), tight, heave);
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
  const double K = kStatic * kDynamic / (kDynamic - kStatic);
  const std::complex<double> iwc(0.0, w * K * kCreepTime);
  const std::complex<double> expected = kDynamic * (K + iwc) / (kDynamic + K + iwc);
  EXPECT_LT(std::abs(measured - expected), 1e-4 * std::abs(expected))
      << "w tau " << wt << ": " << measured << " against " << expected;
  RecordProperty("storage_modulus_N", std::to_string(measured.real()));
  RecordProperty("loss_angle_deg", std::to_string(std::arg(measured) * 180.0 / std::numbers::pi));
}

// Slow cycles see the quasi-static stiffness, fast ones the dynamic; the creep time
// between them, with the largest loss.
INSTANTIATE_TEST_SUITE_P(Frequencies, ViscoElasticCycle, ::testing::Values(0.05, 1.0, 20.0),
                         [](const auto& info) {
                           return info.param < 0.5   ? std::string("Slow")
                                  : info.param < 5.0 ? std::string("AtTheCreepTime")
                                                     : std::string("Fast");
                         });

}  // namespace
}  // namespace moorsim::mooring_fem
