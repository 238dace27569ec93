// The detectors' quasi-static model of lines meeting at free points (point_network.h), on
// the library's bridled seed mooring: the tabulated end tensions against the catenary, the
// network's load and Jacobian against finite differences and against the finite-element
// model at rest, and the hypotheses that change the network.
#include "mooring_fem/point_network.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "detectors/hypothesis_bank.h"
#include "mooring_fem/mooring_system.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::detectors {
namespace {

std::string Sci(double x) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << x;
  return out.str();
}

mooring_fem::MooringParameters BridledMooring() {
  return scenarios::ToMooringParameters(
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml").mooring);
}

mooring_fem::CompositeLine LineOf(const mooring_fem::MooringParameters& spec, int id) {
  const mooring_fem::LineProperties p =
      mooring_fem::MakeLineProperties(spec, spec.lines[static_cast<std::size_t>(id - 1)]);
  mooring_fem::CompositeLine line = mooring_fem::CatenaryLineOf(p);
  line.lower_on_seabed = p.lower_point < 0;
  return line;
}

class PointNetworkTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    spec_ = new mooring_fem::MooringParameters(BridledMooring());
    bank_ = new HypothesisBank(*spec_);
  }
  static void TearDownTestSuite() {
    delete bank_;
    delete spec_;
  }
  static mooring_fem::MooringParameters* spec_;
  static HypothesisBank* bank_;
};
mooring_fem::MooringParameters* PointNetworkTest::spec_ = nullptr;
HypothesisBank* PointNetworkTest::bank_ = nullptr;

// The bicubic table of the anchor line (on the seabed, up to the apex) and of a leg
// (hanging free from the apex to the turret) against the catenary itself at 200 points
// each, inside the ranges the apex moves over: the tensions within 1e-5 of the line's
// tension there, their derivatives within 1e-3 of the largest derivative.
TEST_F(PointNetworkTest, TablesAgreeWithTheCatenary) {
  struct Case {
    int id;
    mooring_fem::LineEndTable::Range range;
  };
  std::mt19937 random(7);
  for (const Case& c :
       {Case{1, {2000.0, 2040.0, 0.42, 0.46}}, Case{9, {159.0, 162.0, 0.9, 1.25}}}) {
    const mooring_fem::CompositeLine line = LineOf(*spec_, c.id);
    const mooring_fem::LineEndTable table(line, c.range, 2.0);
    std::uniform_real_distribution<double> chord(c.range.chord_min, c.range.chord_max);
    std::uniform_real_distribution<double> angle(c.range.angle_min, c.range.angle_max);
    double worst_value = 0.0, worst_slope = 0.0;
    for (int k = 0; k < 200; ++k) {
      const double a = angle(random), r = chord(random);
      const double s = r * std::cos(a), h = r * std::sin(a);
      mooring_fem::LineEnds exact;
      try {
        exact = mooring_fem::SolveLineEnds(line, s, h);
      } catch (const Error&) {
        continue;  // a taut leg beyond its strain limit: the table's smooth extension
      }
      const mooring_fem::LineEnds t = table.At(s, h);
      const double tension = std::hypot(exact.horizontal, exact.vertical);
      worst_value = std::max({worst_value, std::abs(t.horizontal - exact.horizontal) / tension,
                              std::abs(t.vertical - exact.vertical) / tension,
                              std::abs(t.lower_vertical - exact.lower_vertical) / tension});
      const double slope = std::max(exact.d_horizontal.lpNorm<Eigen::Infinity>(),
                                    exact.d_vertical.lpNorm<Eigen::Infinity>());
      worst_slope = std::max(
          {worst_slope, (t.d_horizontal - exact.d_horizontal).lpNorm<Eigen::Infinity>() / slope,
           (t.d_vertical - exact.d_vertical).lpNorm<Eigen::Infinity>() / slope});
    }
    RecordProperty("line_" + std::to_string(c.id) + "_nodes", table.num_nodes());
    EXPECT_LT(worst_value, 1e-5) << "line " << c.id;
    EXPECT_LT(worst_slope, 1e-3) << "line " << c.id;
    RecordProperty("line_" + std::to_string(c.id) + "_value_error", Sci(worst_value));
    RecordProperty("line_" + std::to_string(c.id) + "_slope_error", Sci(worst_slope));
  }
}

// A free lower end hangs: the lower V is the upper V less the line's weight in water.
TEST_F(PointNetworkTest, AHangingLegCarriesItsWeight) {
  const mooring_fem::CompositeLine leg = LineOf(*spec_, 9);
  const mooring_fem::LineEnds e = mooring_fem::SolveLineEnds(leg, 90.0, 130.0);
  const double weight = leg.sections.front().weight_per_length * leg.sections.front().length;
  EXPECT_NEAR(e.vertical - e.lower_vertical, weight, 1e-9 * weight);
}

// A line of no weight in water is straight: slack while its ends are closer than its
// length, then stretched, T = (c - L) EA / L along the chord.
TEST(PointNetworkLines, ANeutralLineIsSlackThenElastic) {
  mooring_fem::CompositeLine line;
  line.sections = {{32.0, 0.0, 1e9}};
  line.lower_on_seabed = false;
  const mooring_fem::LineEnds slack = mooring_fem::SolveLineEnds(line, 10.0, -28.0);
  EXPECT_EQ(slack.horizontal, 0.0);
  EXPECT_EQ(slack.vertical, 0.0);
  const double chord = 32.01, span = 0.6 * chord, height = -0.8 * chord;
  const mooring_fem::LineEnds taut = mooring_fem::SolveLineEnds(line, span, height);
  const double tension = 0.01 * 1e9 / 32.0;
  EXPECT_NEAR(taut.horizontal, 0.6 * tension, 1e-9 * tension);
  EXPECT_NEAR(taut.vertical, -0.8 * tension, 1e-9 * tension);  // pulls the upper end up
  EXPECT_NEAR(taut.d_horizontal.x(), 0.6 * 0.6 * 1e9 / 32.0 + 0.8 * 0.8 * tension / chord,
              1e-5 * 1e9 / 32.0);
}

// The neutral line's derivatives are closed forms: central differences of a millimetre
// (which stay on the taut side of the kink) agree within 1e-6 of the axial stiffness per
// metre of line.
TEST(PointNetworkLines, ANeutralLinesDerivativesAreExact) {
  mooring_fem::CompositeLine line;
  line.sections = {{32.0, 0.0, 1e9}};
  line.lower_on_seabed = false;
  const double span = 6.0, height = -31.9;  // chord 32.459 m: taut
  const mooring_fem::LineEnds e = mooring_fem::SolveLineEnds(line, span, height);
  const double h = 1e-3, scale = 1e9 / 32.0;
  const auto at = [&](double s, double z) { return mooring_fem::SolveLineEnds(line, s, z); };
  const mooring_fem::LineEnds s1 = at(span - h, height), s2 = at(span + h, height);
  const mooring_fem::LineEnds z1 = at(span, height - h), z2 = at(span, height + h);
  EXPECT_NEAR(e.d_horizontal.x(), (s2.horizontal - s1.horizontal) / (2 * h), 1e-6 * scale);
  EXPECT_NEAR(e.d_horizontal.y(), (z2.horizontal - z1.horizontal) / (2 * h), 1e-6 * scale);
  EXPECT_NEAR(e.d_vertical.x(), (s2.vertical - s1.vertical) / (2 * h), 1e-6 * scale);
  EXPECT_NEAR(e.d_vertical.y(), (z2.vertical - z1.vertical) / (2 * h), 1e-6 * scale);
  EXPECT_EQ(e.d_lower_vertical, e.d_vertical);
}

// A mass on a stiff neutral line, hung from a point above it and started 18 degrees to
// the side with the line taut, swings to rest straight below, the line stretched by its
// weight: W L / EA. Each Newton step across the taut line leaves the circle its length
// allows by metres (tens of MN of axial force); the solve must still reach rest.
TEST(PointNetworkLines, APendulumSwingsToRestBelowItsHangingPoint) {
  mooring_fem::NetworkLine pendant;
  pendant.id = 1;
  pendant.lower = {mooring_fem::NetworkEnd::Kind::kAnchor, 0};
  pendant.upper = {mooring_fem::NetworkEnd::Kind::kPoint, 0};
  pendant.line.sections = {{32.0, 0.0, 1e9}};
  pendant.line.lower_on_seabed = false;
  const double weight = 98.1, angle = 18.0 * std::numbers::pi / 180.0;
  Eigen::Matrix3Xd start(3, 1);
  start.col(0) = Vec3(32.0 * std::sin(angle), 1.0, 32.0 * std::cos(angle));
  const mooring_fem::PointNetwork network({pendant}, {weight}, {Vec3(0.0, 1.0, 0.0)}, 0, start);
  const auto rest = network.Solve(Eigen::Matrix3Xd(3, 0), false);
  ASSERT_TRUE(rest.converged) << "residual " << rest.residual << " N";
  // The solve stops within 1e-9 EA (1 N) of balance: what is left is the sideways pull
  // W x / L and the axial force's error.
  EXPECT_LE(rest.residual, 1.0);
  EXPECT_LE(std::abs(rest.points(0, 0)) * weight / 32.0, rest.residual * (1.0 + 1e-9));
  EXPECT_NEAR(rest.points(1, 0), 1.0, 1e-12);
  EXPECT_NEAR(rest.points(2, 0), 32.0 + weight * 32.0 / 1e9, 1e-6);
  EXPECT_NEAR(rest.upper_tension[0], weight, rest.residual + 1e-6);
}

// The load and its Jacobian at poses about the origin: the analytic Jacobian (the apex
// following the vessel) against central differences of the load, within 1e-4 of the
// largest entry.
TEST_F(PointNetworkTest, TheLoadJacobianMatchesFiniteDifferences) {
  for (int h : {0, bank_->Find(std::vector<int>{9}), bank_->Find(std::vector<int>{4})}) {
    const QuasiStaticMooring& mooring = bank_->mooring(h);
    ASSERT_TRUE(mooring.has_networks()) << bank_->Label(h);
    for (const Vec3& eta :
         {Vec3(0.0, 0.0, 0.0), Vec3(25.0, -10.0, 0.05), Vec3(-40.0, 30.0, -0.1)}) {
      Mat3 J;
      mooring.Load(eta, &J);
      Mat3 fd;
      const Vec3 step(1e-2, 1e-2, 1e-5);
      for (int k = 0; k < 3; ++k) {
        Vec3 plus = eta, minus = eta;
        plus(k) += step(k);
        minus(k) -= step(k);
        fd.col(k) = (mooring.Load(plus) - mooring.Load(minus)) / (2.0 * step(k));
      }
      const double scale = std::max(J.topLeftCorner<2, 2>().cwiseAbs().maxCoeff(), 1.0);
      for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) {
          // Rows and columns in their own units: N/m, N/rad, N m/m, N m/rad scaled by the
          // 20 m turret radius.
          const double units = (r == 2 ? 20.0 : 1.0) * (k == 2 ? 20.0 : 1.0);
          EXPECT_NEAR(J(r, k), fd(r, k), 1e-4 * scale * units)
              << bank_->Label(h) << " eta " << eta.transpose() << " (" << r << ", " << k << ")";
        }
      }
    }
  }
}

// With the anchor line gone the apex hangs from the turret alone: no network is left, and
// the load is the other seven lines'. With a leg gone the apex hangs on the other leg.
TEST_F(PointNetworkTest, HypothesesChangeTheNetwork) {
  EXPECT_EQ(bank_->size(), 11);
  EXPECT_TRUE(bank_->has_networks());
  EXPECT_FALSE(bank_->mooring(bank_->Find(std::vector<int>{1})).has_networks());
  const QuasiStaticMooring& leg_gone = bank_->mooring(bank_->Find(std::vector<int>{10}));
  ASSERT_EQ(leg_gone.networks().size(), 1u);
  EXPECT_EQ(leg_gone.networks().front().network->lines().size(), 2u);
  EXPECT_THROW(bank_->table(0), Error);  // line 1 is in the network
  EXPECT_NO_THROW(bank_->table(1));
}

// The tabulated network against the same network solved straight from the catenaries
// (no table), with the vessel offset and turned: the apex within 1 mm, the load within
// 1e-5 of the anchor line's tension.
TEST_F(PointNetworkTest, TheTabulatedNetworkMatchesTheDirectSolve) {
  for (int h : {0, bank_->Find(std::vector<int>{9})}) {
    const AttachedNetwork& attached = bank_->mooring(h).networks().front();
    const mooring_fem::PointNetwork& tabulated = *attached.network;
    const mooring_fem::PointNetwork direct = tabulated.WithTables(
        std::vector<std::shared_ptr<const mooring_fem::LineEndTable>>(tabulated.lines().size()),
        tabulated.rest());
    for (const Vec3& eta : {Vec3(0.0, 0.0, 0.0), Vec3(60.0, 20.0, 0.08), Vec3(-70.0, -40.0, 0.0)}) {
      Eigen::Matrix3Xd fairleads(3, tabulated.num_fairleads());
      for (int f = 0; f < tabulated.num_fairleads(); ++f) {
        const Vec3& b = attached.fairlead_body[static_cast<std::size_t>(f)];
        const double c = std::cos(eta.z()), s = std::sin(eta.z());
        fairleads.col(f) = Vec3(eta.x() + c * b.x() - s * b.y(), eta.y() + s * b.x() + c * b.y(),
                                attached.fairlead_depth[static_cast<std::size_t>(f)]);
      }
      const mooring_fem::PointNetwork::Equilibrium a = tabulated.Solve(fairleads, false);
      const mooring_fem::PointNetwork::Equilibrium b = direct.Solve(fairleads, false);
      ASSERT_TRUE(a.converged && b.converged) << bank_->Label(h);
      EXPECT_LT((a.points - b.points).lpNorm<Eigen::Infinity>(), 1e-3) << bank_->Label(h);
      const double tension = *std::max_element(b.upper_tension.begin(), b.upper_tension.end());
      EXPECT_LT((a.fairlead_forces - b.fairlead_forces).lpNorm<Eigen::Infinity>(), 1e-5 * tension)
          << bank_->Label(h) << " eta " << eta.transpose();
    }
  }
}

// The network at rest against the finite-element model settled at rest (lines cut three
// times finer than the library's): the apex within 5 cm, the legs' pull on the vessel
// within 0.1 % of it.
TEST_F(PointNetworkTest, TheNetworkAtRestMatchesTheFiniteElementModel) {
  mooring_fem::MooringParameters fine = *spec_;
  for (mooring_fem::LineParameters& line : fine.lines) {
    for (mooring_fem::LineSection& section : line.sections) section.segments *= 3;
  }
  mooring_fem::MooringSystem fem(fine);
  std::vector<Vec3> positions;
  std::vector<PointKinematics> fairleads;
  for (int i = 0; i < fem.num_lines(); ++i) {
    PointKinematics f;
    f.position = fem.line(i).fairlead_body;
    fairleads.push_back(f);
    positions.push_back(f.position);
  }
  std::vector<double> x(fem.StateSize());
  fem.CatenaryState(positions, x.data());
  fem.SettleStatic(positions, x.data());
  const Vec3 apex = fem.PointPosition(x.data(), 0);
  const auto loads = fem.LineLoads(x.data(), fairleads);
  const Eigen::Vector2d legs = (loads[8].fairlead_force + loads[9].fairlead_force).head<2>();

  const AttachedNetwork& attached = bank_->mooring(0).networks().front();
  Eigen::Matrix3Xd at(3, 2);
  for (int f = 0; f < 2; ++f) {
    at.col(f) = attached.fairlead_body[static_cast<std::size_t>(f)];
    at(2, f) = attached.fairlead_depth[static_cast<std::size_t>(f)];
  }
  const mooring_fem::PointNetwork::Equilibrium eq = attached.network->Solve(at, false);
  ASSERT_TRUE(eq.converged);
  EXPECT_LT((eq.points.col(0) - apex).norm(), 0.05)
      << eq.points.col(0).transpose() << " vs " << apex.transpose();
  const Eigen::Vector2d pull = eq.fairlead_forces.topRows<2>().rowwise().sum();
  EXPECT_LT((pull - legs).norm(), 1e-3 * legs.norm())
      << pull.transpose() << " vs " << legs.transpose();
  RecordProperty("apex_error_m", Sci((eq.points.col(0) - apex).norm()));
  RecordProperty("pull_error", Sci((pull - legs).norm() / legs.norm()));
}

// An apex on legs too long to hold it off the seabed: one message naming the points (that
// it sinks to the seabed, where the solve gets there, or that it finds no rest).
TEST(PointNetworkInput, APointThatSinksToTheSeabedIsOneMessage) {
  mooring_fem::MooringParameters spec = BridledMooring();
  // Legs of 1100 m: the apex would hang below the seabed.
  for (int leg : {8, 9}) spec.lines[static_cast<std::size_t>(leg)].sections.front().length = 1100.0;
  try {
    HypothesisBank bank(spec);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("mooring.points[1]: sinks to the seabed") == 0 ||
                what.find("mooring.points: the detectors' quasi-static model finds no rest for "
                          "the free points of lines 1 9 10") == 0)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace moorsim::detectors
