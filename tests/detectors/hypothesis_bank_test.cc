// Tests of the hypothesis-model bank (detectors/hypothesis_bank.h): the catenary look-up
// table against the solver it tabulates, the seed case's numbers
// (docs/design.md section 9), the mooring load against SolveLineCatenary in
// Earth coordinates, the analytic Jacobian against central differences, and the bank's
// bookkeeping.
#include "detectors/hypothesis_bank.h"
#include "core/angles.h"
#include "tests/detectors/observer_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/mooring_system.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::detectors {
namespace {

mooring_fem::CompositeLine CatenaryOf(const mooring_fem::MooringParameters& spec, int index) {
  return mooring_fem::CatenaryLineOf(mooring_fem::MakeLineProperties(spec, spec.lines[index]));
}

/// Net load [Fx, Fy, Mz] of the given lines (0-based) by SolveLineCatenary in Earth
/// coordinates: an independent path to the same physics (no table, no 2-D geometry).
Vec3 DirectLoad(const mooring_fem::MooringParameters& spec, const std::vector<int>& lines,
                const Vec3& eta) {
  const double c = std::cos(eta.z());
  const double s = std::sin(eta.z());
  Vec3 load = Vec3::Zero();
  for (int i : lines) {
    const Vec3& fb = spec.lines[i].fairlead_body;
    const Vec3 r(c * fb.x() - s * fb.y(), s * fb.x() + c * fb.y(), 0.0);
    const Vec3 fairlead(eta.x() + r.x(), eta.y() + r.y(), fb.z());
    const auto cat = mooring_fem::SolveLineCatenary(CatenaryOf(spec, i).sections.front(),
                                                    spec.lines[i].anchor, fairlead);
    const Vec3 f = cat.fairlead_force;
    load += Vec3(f.x(), f.y(), r.x() * f.y() - r.y() * f.x());
  }
  return load;
}

class HypothesisBankTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    spec_ = new mooring_fem::MooringParameters(testing::SeedMooring());
    bank_ = new HypothesisBank(*spec_);
  }
  static void TearDownTestSuite() {
    delete bank_;
    delete spec_;
  }
  static mooring_fem::MooringParameters* spec_;
  static HypothesisBank* bank_;
};
mooring_fem::MooringParameters* HypothesisBankTest::spec_ = nullptr;
HypothesisBank* HypothesisBankTest::bank_ = nullptr;

// Interpolation error at off-grid spans, mid-interval (where cubic Hermite errs most) and
// at fractions 0.3 / 0.85, over the whole +-150 m range plus the turret radius, for a
// cardinal and a diagonal line. Measured with the 1 m grid: smooth intervals ~3e-11 of H
// (1e-8 of dH/dspan); the worst is the interval holding the touchdown -> lift-off
// transition near span 2022 m, 3.1e-7 of H and 1.4e-4 of dH/dspan, because H'' is not
// smooth there. Bounds: 1e-6 of H and V, 5e-4 of the slope (the interpolant's derivative,
// which is what the Jacobians use).
TEST_F(HypothesisBankTest, TableMatchesCatenaryOffGrid) {
  for (int index : {0, 5}) {
    const LineForceTable& table = bank_->table(index);
    const auto line = CatenaryOf(*spec_, index).sections.front();
    double worst_h = 0.0, worst_dh = 0.0, worst_v = 0.0;
    for (int i = 0; i + 1 < table.num_nodes(); ++i) {
      for (double fraction : {0.3, 0.5, 0.85}) {
        const double span = table.span_min() + (i + fraction) * table.span_step();
        const auto exact = mooring_fem::SolveCatenary(line, span, table.height());
        const double step = 1e-3;
        const double slope =
            (mooring_fem::SolveCatenary(line, span + step, table.height()).horizontal_tension -
             mooring_fem::SolveCatenary(line, span - step, table.height()).horizontal_tension) /
            (2.0 * step);
        double dh = 0.0;
        const double h = table.HorizontalTension(span, &dh);
        worst_h = std::max(worst_h, std::abs(h / exact.horizontal_tension - 1.0));
        worst_dh = std::max(worst_dh, std::abs(dh / slope - 1.0));
        worst_v =
            std::max(worst_v, std::abs(table.VerticalTension(span) / exact.vertical_tension - 1.0));
      }
    }
    EXPECT_LT(worst_h, 1e-6) << "line " << index + 1;
    EXPECT_LT(worst_dh, 5e-4) << "line " << index + 1;
    EXPECT_LT(worst_v, 1e-6) << "line " << index + 1;
    // The range covers +-150 m of offset at any heading.
    EXPECT_LE(table.span_min(), table.nominal_span() - 150.0 - 20.0 + 1e-9);
    EXPECT_GE(table.span_max(), table.nominal_span() + 150.0 + 20.0 - 1e-9);
  }
}

// Outside the table: continuous linear extrapolation with the end slope, clamped at 0.
TEST_F(HypothesisBankTest, TableExtrapolatesLinearlyOutsideItsRange) {
  const LineForceTable& table = bank_->table(0);
  double slope_end = 0.0;
  const double h_end = table.HorizontalTension(table.span_max(), &slope_end);
  double slope = 0.0;
  EXPECT_NEAR(table.HorizontalTension(table.span_max() + 10.0, &slope), h_end + 10.0 * slope_end,
              1e-6 * h_end);
  EXPECT_DOUBLE_EQ(slope, slope_end);
  EXPECT_FALSE(table.Covers(table.span_max() + 10.0));
  EXPECT_EQ(table.HorizontalTension(table.span_min() - 1e5, &slope), 0.0);
  EXPECT_EQ(slope, 0.0);
}

// Seed case (docs/design.md section 9): H = 3.497 MN and V = 4.948 MN per line at the origin
// (span 1930 m, fairlead depth 12 m). The diagonal anchors, at (1378.9, 1378.9), are
// 1950.06 m out, so their lines' own nominal span is 6 cm longer and their H 1.5 kN higher.
TEST_F(HypothesisBankTest, SeedTensionAtTheOrigin) {
  for (int i = 0; i < bank_->num_lines(); ++i) {
    const LineForceTable& table = bank_->table(i);
    EXPECT_NEAR(table.fairlead_depth(), 12.0, 1e-12);
    EXPECT_NEAR(table.nominal_span(), i < 4 ? 1930.0 : 1930.059, 1e-3);
    EXPECT_NEAR(table.HorizontalTension(1930.0), 3.497e6, 0.5e3);
    EXPECT_NEAR(table.VerticalTension(1930.0), 4.948e6, 0.5e3);
  }
  // The eight pulls cancel at the origin.
  EXPECT_LT(bank_->mooring(0).Load(Vec3::Zero()).head<2>().norm(), 1e3);
}

// Seed case (docs/design.md section 9): surge stiffness about 81 kN/m near the origin
// (81.57 kN/m by `moorsim static` at +-1 m, vessel/controller.h), the same in sway;
// yaw 5.657e8 N m/rad.
TEST_F(HypothesisBankTest, SeedStiffnessAtTheOrigin) {
  const Mat3& G = bank_->stiffness(0);
  EXPECT_NEAR(G(0, 0), 81.57e3, 0.2e3);
  EXPECT_NEAR(G(1, 1), 81.57e3, 0.2e3);
  EXPECT_NEAR(G(2, 2), 5.657e8, 0.01e8);
  // Symmetric: the load is the gradient of the lines' potential energy in (x, y, psi).
  EXPECT_LT((G - G.transpose()).cwiseAbs().maxCoeff(), 1e-6 * G(0, 0));
}

// The thesis cases hold heading -135 deg with the locked turret's fairleads turned to
// match; linearised there, their stiffness is the seed case's at heading 0.
TEST(HypothesisBankReferencePoseTest, ThesisStiffnessAtItsHeading) {
  const mooring_fem::MooringParameters thesis = scenarios::ToMooringParameters(
      scenarios::LoadScenario(std::string(MOORSIM_SOURCE_DIR) +
                              "/scenarios/library/thesis_no_failure.yaml")
          .mooring);
  HypothesisBankOptions options;
  options.reference_pose = Vec3(0.0, 0.0, -0.75 * kPi);
  const HypothesisBank bank(thesis, options);
  const Mat3& G = bank.stiffness(0);
  EXPECT_NEAR(G(0, 0), 81.57e3, 0.2e3);
  EXPECT_NEAR(G(1, 1), 81.57e3, 0.2e3);
  EXPECT_NEAR(G(2, 2), 5.657e8, 0.01e8);
  // At its own neutral heading the intact mooring exerts no yaw moment.
  EXPECT_NEAR(bank.mooring(0).Load(options.reference_pose).z(), 0.0, 1e3);
  EXPECT_GT(std::abs(bank.mooring(0).Load(Vec3::Zero()).z()), 1e8);
}

// Seed case (docs/design.md section 9): with line 6 gone the net force at the origin is
// 3.50 MN toward (+x, -y), away from line 6 (anchor at (-1378.9, 1378.9)).
TEST_F(HypothesisBankTest, SeedLineSixFailureForce) {
  const int h = bank_->Find(std::vector<int>{6});
  ASSERT_EQ(h, 6);
  const Vec3 load = bank_->mooring(h).Load(Vec3::Zero());
  EXPECT_NEAR(load.head<2>().norm(), 3.50e6, 0.005e6);
  EXPECT_NEAR(std::atan2(load.y(), load.x()), -kPi / 4.0, 1e-6);
  EXPECT_NEAR(load.z(), 0.0, 1.0);  // through the turret centre at heading 0
}

// The table-based load against SolveLineCatenary at displaced poses, intact and with lines
// failed. The bound is the table's 2e-6 of one line's 3.5-6 MN pull.
TEST_F(HypothesisBankTest, LoadMatchesDirectCatenary) {
  const std::vector<Vec3> poses = {Vec3(0.0, 0.0, 0.0), Vec3(12.0, -7.0, 0.05),
                                   Vec3(-60.0, 35.0, -0.4), Vec3(100.0, 90.0, 2.5)};
  for (int h : {0, 3, 6}) {
    std::vector<int> intact;
    for (int i = 0; i < 8; ++i) {
      if (h == 0 || i != h - 1) intact.push_back(i);
    }
    for (const Vec3& eta : poses) {
      const Vec3 expected = DirectLoad(*spec_, intact, eta);
      const Vec3 got = bank_->mooring(h).Load(eta);
      EXPECT_NEAR(got.x(), expected.x(), 100.0) << "h " << h << " eta " << eta.transpose();
      EXPECT_NEAR(got.y(), expected.y(), 100.0) << "h " << h << " eta " << eta.transpose();
      EXPECT_NEAR(got.z(), expected.z(), 2000.0) << "h " << h << " eta " << eta.transpose();
    }
  }
}

// Analytic Jacobians against central differences (steps 1 mm, 1e-6 rad: truncation
// ~H''' step^2 and rounding ~1e-16 |F| / step both far below 1e-6 of the entries' scale).
TEST_F(HypothesisBankTest, JacobianMatchesCentralDifferences) {
  const std::vector<Vec3> poses = {Vec3(0.0, 0.0, 0.0), Vec3(30.0, -20.0, 0.3),
                                   Vec3(-90.0, 60.0, -2.0), Vec3(5.0, 140.0, 3.1)};
  const Vec3 steps(1e-3, 1e-3, 1e-6);
  for (int h : {0, 2, 6}) {
    const QuasiStaticMooring& mooring = bank_->mooring(h);
    for (const Vec3& eta : poses) {
      for (bool body : {false, true}) {
        Mat3 J;
        if (body) {
          mooring.LoadBody(eta, &J);
        } else {
          mooring.Load(eta, &J);
        }
        for (int k = 0; k < 3; ++k) {
          Vec3 plus = eta, minus = eta;
          plus(k) += steps(k);
          minus(k) -= steps(k);
          const Vec3 diff = body ? (mooring.LoadBody(plus) - mooring.LoadBody(minus))
                                 : (mooring.Load(plus) - mooring.Load(minus));
          const Vec3 fd = diff / (2.0 * steps(k));
          // Scales: force rows ~1e5 N/m (x, y) or 1e7 N/rad (psi); moment row x 20 m.
          const double scale = (k < 2 ? 1e5 : 1e7);
          for (int r = 0; r < 3; ++r) {
            const double row_scale = r < 2 ? scale : 20.0 * scale;
            EXPECT_NEAR(J(r, k), fd(r), 1e-6 * row_scale)
                << "h " << h << " body " << body << " eta " << eta.transpose() << " J(" << r << ","
                << k << ")";
          }
        }
      }
    }
  }
}

// A turret on its bearing: the fairleads hold their absolute direction about the turret
// centre while the hull turns; the hull feels the net force at the centre. Against
// SolveLineCatenary with the fairleads placed by hand, the analytic Jacobian against central
// differences, and with the centre at the reference point no yaw stiffness at all.
Vec3 DirectTurretLoad(const mooring_fem::MooringParameters& spec, const Vec3& eta,
                      const TurretModel& turret) {
  const double c = std::cos(eta.z()), s = std::sin(eta.z());
  const double ct = std::cos(turret.heading), st = std::sin(turret.heading);
  const Eigen::Vector2d& k = turret.centre;
  const Vec3 centre(eta.x() + c * k.x() - s * k.y(), eta.y() + s * k.x() + c * k.y(), 0.0);
  Vec3 load = Vec3::Zero();
  for (std::size_t i = 0; i < spec.lines.size(); ++i) {
    const Vec3& fb = spec.lines[i].fairlead_body;
    const Eigen::Vector2d arm = fb.head<2>() - k;
    const Vec3 fairlead(centre.x() + ct * arm.x() - st * arm.y(),
                        centre.y() + st * arm.x() + ct * arm.y(), fb.z());
    const Vec3 f =
        mooring_fem::SolveLineCatenary(CatenaryOf(spec, static_cast<int>(i)).sections.front(),
                                       spec.lines[i].anchor, fairlead)
            .fairlead_force;
    const Vec3 lever = centre - Vec3(eta.x(), eta.y(), 0.0);
    load += Vec3(f.x(), f.y(), lever.x() * f.y() - lever.y() * f.x());
  }
  return load;
}

TEST_F(HypothesisBankTest, TurningTurretLoadJacobianAndNoYawStiffnessAtTheCentre) {
  HypothesisBankOptions options;
  options.turret = TurretModel{Eigen::Vector2d(30.0, 2.0), 0.2};
  const HypothesisBank bank(*spec_, options);
  const QuasiStaticMooring& mooring = bank.mooring(0);
  for (const Vec3& eta : {Vec3(0.0, 0.0, 0.2), Vec3(12.0, -7.0, 0.5), Vec3(-40.0, 25.0, -0.4)}) {
    const Vec3 expected = DirectTurretLoad(*spec_, eta, *options.turret);
    const Vec3 got = mooring.Load(eta);
    EXPECT_NEAR(got.x(), expected.x(), 100.0) << eta.transpose();
    EXPECT_NEAR(got.y(), expected.y(), 100.0) << eta.transpose();
    EXPECT_NEAR(got.z(), expected.z(), 2000.0) << eta.transpose();
    Mat3 J;
    mooring.Load(eta, &J);
    const Vec3 steps(1e-3, 1e-3, 1e-6);
    for (int k = 0; k < 3; ++k) {
      Vec3 plus = eta, minus = eta;
      plus(k) += steps(k);
      minus(k) -= steps(k);
      const Vec3 fd = (mooring.Load(plus) - mooring.Load(minus)) / (2.0 * steps(k));
      const double scale = (k < 2 ? 1e5 : 1e7);
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(J(r, k), fd(r), 1e-6 * (r < 2 ? scale : 30.0 * scale))
            << eta.transpose() << " J(" << r << "," << k << ")";
      }
    }
  }
  // The centre at the reference point: the hull can turn without moving a line.
  HypothesisBankOptions centred;
  centred.turret = TurretModel{Eigen::Vector2d::Zero(), 0.0};
  const HypothesisBank free_bank(*spec_, centred);
  const Vec3 at_rest = free_bank.mooring(0).Load(Vec3::Zero());
  for (const double psi : {0.3, -1.0, 2.5}) {
    const Vec3 turned = free_bank.mooring(0).Load(Vec3(0.0, 0.0, psi));
    EXPECT_NEAR((turned - at_rest).head<2>().norm(), 0.0, 1e-6);
    EXPECT_EQ(turned.z(), 0.0);
  }
  EXPECT_EQ(free_bank.stiffness(0)(2, 2), 0.0);
  // The locked bank's yaw stiffness is the seed's 5.7e8 N m/rad.
  EXPECT_GT(bank_->stiffness(0)(2, 2), 5e8);
}

TEST_F(HypothesisBankTest, SizesAndLabels) {
  EXPECT_EQ(bank_->num_lines(), 8);
  EXPECT_EQ(bank_->size(), 9);
  EXPECT_FALSE(bank_->has_pairs());
  EXPECT_EQ(bank_->Label(0), "intact");
  EXPECT_EQ(bank_->Label(6), "line 6");
  EXPECT_TRUE(bank_->failed_lines(0).empty());
  for (int k = 1; k <= 8; ++k) {
    ASSERT_EQ(bank_->failed_lines(k).size(), 1u);
    EXPECT_EQ(bank_->failed_lines(k)[0], k);
    EXPECT_EQ(bank_->mooring(k).num_lines(), 7);
  }

  HypothesisBankOptions options;
  options.include_pairs = true;
  const HypothesisBank pairs(*spec_, options);
  EXPECT_EQ(pairs.size(), 37);  // 1 + 8 + 28
  EXPECT_TRUE(pairs.has_pairs());
  EXPECT_EQ(pairs.Label(9), "lines 1+2");
  const int h25 = pairs.Find(std::vector<int>{5, 2});
  ASSERT_GT(h25, 8);
  EXPECT_EQ(pairs.Label(h25), "lines 2+5");
  EXPECT_EQ(pairs.Label(36), "lines 7+8");
  EXPECT_EQ(pairs.mooring(h25).num_lines(), 6);
  EXPECT_EQ(pairs.Find(std::vector<int>{9}), -1);
  // Tables are shared, not rebuilt per hypothesis.
  EXPECT_EQ(&pairs.mooring(h25).line(0), &pairs.mooring(0).line(0));
}

// Hypothesis k's load is the intact load minus line k's own; a pair removes both.
TEST_F(HypothesisBankTest, FailedLoadIsIntactMinusTheLine) {
  HypothesisBankOptions options;
  options.include_pairs = true;
  const HypothesisBank bank(*spec_, options);
  const Vec3 eta(23.0, -41.0, 0.2);
  const Vec3 intact = bank.mooring(0).Load(eta);
  for (int k = 1; k <= 8; ++k) {
    const Vec3 line_k = bank.mooring(0).LineLoad(k - 1, eta);
    EXPECT_LT((bank.mooring(k).Load(eta) - (intact - line_k)).norm(), 1e-6 * intact.norm() + 1e-3)
        << "line " << k;
  }
  const int h = bank.Find(std::vector<int>{2, 5});
  const Vec3 expected =
      intact - bank.mooring(0).LineLoad(1, eta) - bank.mooring(0).LineLoad(4, eta);
  EXPECT_LT((bank.mooring(h).Load(eta) - expected).norm(), 1e-3);
}

// Moored heave lowers every fairlead: a deeper fairlead on the same span pulls less.
TEST_F(HypothesisBankTest, MooredHeaveMovesTheFairleads) {
  HypothesisBankOptions options;
  options.moored_heave = 0.5;
  const HypothesisBank heaved(*spec_, options);
  EXPECT_NEAR(heaved.table(0).fairlead_depth(), 12.5, 1e-12);
  const auto exact =
      mooring_fem::SolveCatenary(CatenaryOf(*spec_, 0).sections.front(), 1930.0, 1000.0 - 12.5);
  EXPECT_NEAR(heaved.table(0).HorizontalTension(1930.0), exact.horizontal_tension, 10.0);
}

TEST_F(HypothesisBankTest, MooringDampingIsAFractionOfCritical) {
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const Mat3 D = bank_->MooringDamping(0, model.mass, Vec3(0.1, 0.1, 0.2));
  const Mat3& G = bank_->stiffness(0);
  EXPECT_NEAR(D(0, 0), 0.2 * std::sqrt(G(0, 0) * model.mass(0, 0)), 1e-9 * D(0, 0));
  EXPECT_NEAR(D(2, 2), 0.4 * std::sqrt(G(2, 2) * model.mass(2, 2)), 1e-9 * D(2, 2));
  EXPECT_EQ(D(0, 1), 0.0);
  EXPECT_THROW(MooringDampingMatrix(G, model.mass, Vec3(0.1, -1.0, 0.1)), InputError);
}

TEST(LowFrequencyModelTest, SeedNumbers) {
  const LowFrequencyModel model = SeedLowFrequencyModel();
  EXPECT_DOUBLE_EQ(model.mass(0, 0), 1.0041e8 + 7.9427e6);
  EXPECT_DOUBLE_EQ(model.mass(1, 1), 1.0041e8 + 6.4432e7);
  EXPECT_DOUBLE_EQ(model.mass(2, 2), 1.0041e8 * 54.0 * 54.0 + 1.4513e11);
  EXPECT_DOUBLE_EQ(model.damping(0, 0), model.mass(0, 0) / 50.0);
  EXPECT_DOUBLE_EQ(model.damping(1, 1), model.mass(1, 1) / 100.0);
  EXPECT_DOUBLE_EQ(model.damping(2, 2), model.mass(2, 2) / 20.0);
  EXPECT_EQ(model.mass(0, 1), 0.0);
}

TEST(HypothesisBankInputTest, BadParametersNameTheField) {
  mooring_fem::MooringParameters spec = testing::SeedMooring();
  HypothesisBankOptions options;
  options.table.span_step = 0.0;
  try {
    HypothesisBank bank(spec, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("span_step = 0"), std::string::npos) << e.what();
  }
  options = {};
  options.moored_heave = std::nan("");
  EXPECT_THROW(HypothesisBank(spec, options), InputError);

  mooring_fem::MooringParameters empty = spec;
  empty.lines.clear();
  EXPECT_THROW(HypothesisBank{empty}, InputError);

  // A fairlead below its anchor.
  const auto line = CatenaryOf(spec, 0);
  try {
    LineForceTable table(3, line, Vec3(1950.0, 0.0, 1000.0), Vec3(20.0, 0.0, 12.0), 1200.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mooring.lines[3]"), std::string::npos) << e.what();
  }
}

// A table asked to reach farther than the line can stretch stops short of the limit.
TEST(HypothesisBankInputTest, TableStopsWhereTheLineCannotReach) {
  mooring_fem::MooringParameters spec = testing::SeedMooring();
  const auto line = CatenaryOf(spec, 0);
  LineForceTableOptions options;
  options.span_margin = 600.0;
  const LineForceTable table(1, line, Vec3(1950.0, 0.0, 1000.0), Vec3(20.0, 0.0, 12.0), 12.0,
                             options);
  EXPECT_LT(table.span_max(), 1930.0 + 620.0);
  EXPECT_NO_THROW(
      mooring_fem::SolveCatenary(line.sections.front(), table.span_max(), table.height()));
  EXPECT_GT(table.HorizontalTension(table.span_max()), 1e7);
}

}  // namespace
}  // namespace moorsim::detectors
