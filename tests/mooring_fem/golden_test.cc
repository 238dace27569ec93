// Regression (golden) test: fairlead tensions of the seed mooring (20 segments) under the
// issue's surge at fixed times, and the integrator's step count, against values recorded
// from an earlier verified build. It guards against unintended changes to the numbers;
// the physics is verified by the other tests. A missing golden file is a failure.
//
// After an intended change, regenerate with tools/dev/update_golden.sh and say why in the
// commit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

const std::string kGolden =
    std::string(MOORSIM_SOURCE_DIR) + "/tests/data/golden/seed_surge_20_segments.csv";

struct Record {
  std::vector<std::vector<double>> rows;  // time, line 1..8 tension [N]
  long steps = 0;
};

Record Simulate() {
  const testing::SeedCase s = testing::SeedScenario(20);
  LineSimulation sim(s.mooring, s.solver, testing::IssueSurge());
  Record r;
  for (int i = 1; i <= 12; ++i) {
    sim.AdvanceTo(10.0 * i);
    std::vector<double> row{sim.time()};
    for (const Vec3& f : sim.FairleadForces()) row.push_back(f.norm());
    r.rows.push_back(row);
  }
  r.steps = sim.stats().steps;
  return r;
}

TEST(Golden, SeedSurgeTensionsAndStepCount) {
  const Record now = Simulate();
  if (std::getenv("MOORSIM_UPDATE_GOLDEN") != nullptr) {
    const char* ci = std::getenv("CI");
    ASSERT_FALSE(ci != nullptr && std::string(ci) == "true")
        << "golden files are never rewritten under CI=true";
    std::ofstream out(kGolden);
    out.precision(12);
    out << "# moorsim golden: seed_tapm.yaml, 20 segments, surge 5 m / 100 s + 2 m / 10 s\n";
    out << "steps," << now.steps << "\n";
    for (const auto& row : now.rows) {
      for (std::size_t k = 0; k < row.size(); ++k) out << (k ? "," : "") << row[k];
      out << "\n";
    }
    GTEST_SKIP() << "golden file rewritten: " << kGolden;
  }
  std::ifstream in(kGolden);
  ASSERT_TRUE(in) << "missing golden file " << kGolden;
  Record golden;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("steps,", 0) == 0) {
      golden.steps = std::stol(line.substr(6));
      continue;
    }
    std::stringstream fields(line);
    std::vector<double> row;
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    golden.rows.push_back(row);
  }
  ASSERT_EQ(golden.rows.size(), now.rows.size());
  for (std::size_t i = 0; i < now.rows.size(); ++i) {
    ASSERT_EQ(golden.rows[i].size(), now.rows[i].size());
    EXPECT_DOUBLE_EQ(now.rows[i][0], golden.rows[i][0]);
    for (std::size_t k = 1; k < now.rows[i].size(); ++k) {
      // 100 N on 6 MN: far above round-off differences between equivalent builds, far below
      // any change of model or integrator settings (those move tensions by kN).
      EXPECT_NEAR(now.rows[i][k], golden.rows[i][k], 100.0)
          << "t = " << now.rows[i][0] << " s, line " << k;
    }
  }
  // The integrator's work: a change of settings or Jacobian shows here first.
  EXPECT_NEAR(static_cast<double>(now.steps), static_cast<double>(golden.steps),
              0.05 * golden.steps);
}

}  // namespace
}  // namespace moorsim::mooring_fem
