// Regression (golden) files of two coupled library scenarios: vessel pose, fairlead
// tensions, delivered thrust, every detector's decision, alarm and scores, and the CVODE
// counters, at fixed times, against values recorded from an earlier verified build. They
// guard against unintended changes of the numbers; the physics is verified by the other
// tests. A missing golden file is a failure.
//
// Tolerances (stated per channel below) are far above the round-off differences between
// equivalent builds (the release and the sanitizer builds compile with different
// optimisation and both must pass) and far below what a change of model or settings moves:
// a 10 % change of a drag coefficient moves tensions by tens of kN.
//
// After an intended change, rewrite them with tools/dev/update_golden.sh and say why in the
// commit; the script (and this test) refuse to rewrite under CI=true.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"

namespace moorsim::simulation {
namespace {

using nlohmann::json;

struct GoldenCase {
  std::string name;      // tests/data/golden/<name>.json
  std::string scenario;  // a library scenario
  double duration;       // [s]
  double interval;       // sample spacing [s]
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

template <class V>
std::vector<double> Values(const V& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

json Simulate(const GoldenCase& c) {
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/" + c.scenario, {});
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  json samples = json::array();
  const auto count = static_cast<int>(std::lround(c.duration / c.interval));
  for (int k = 0; k <= count; ++k) {
    sim.AdvanceTo(k * c.interval);
    const Sample s = sim.Record();
    json j;
    j["time"] = s.time;
    j["pose"] = Values(s.pose_true);
    j["tension"] = s.fairlead_tension;
    j["thrust"] = Values(s.thrust_delivered);
    json detectors = json::array();
    for (const detectors::Verdict& v : s.detectors) {
      detectors.push_back({{"decision", v.hypothesis}, {"alarm", v.alarm}, {"score", v.score}});
    }
    j["detectors"] = detectors;
    samples.push_back(j);
  }
  const IntegratorStats stats = sim.stats();
  json out;
  out["scenario"] = c.scenario;
  out["seed"] = scenario.simulation.seed;
  out["samples"] = samples;
  out["integrator"] = {{"steps", stats.steps},
                       {"rhs_evaluations", stats.rhs_evals},
                       {"jacobian_evaluations", stats.jacobian_evals}};
  std::vector<std::string> labels;
  for (const DetectorRecord& d : sim.detector_records()) labels.push_back(d.label);
  out["detector_labels"] = labels;
  return out;
}

std::string GoldenPath(const GoldenCase& c) {
  return MOORSIM_SOURCE_DIR "/tests/data/golden/" + c.name + ".json";
}

/// Compares a list of numbers within |a - b| <= atol + rtol |b|.
void ExpectNear(const json& now, const json& golden, double atol, double rtol,
                const std::string& what) {
  ASSERT_EQ(now.size(), golden.size()) << what;
  for (std::size_t i = 0; i < now.size(); ++i) {
    const double a = now[i].get<double>(), b = golden[i].get<double>();
    EXPECT_LE(std::abs(a - b), atol + rtol * std::abs(b))
        << what << "[" << i << "]: " << a << " vs golden " << b;
  }
}

class CoupledGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(CoupledGolden, MatchesTheRecordedRun) {
  const GoldenCase& c = GetParam();
  const json now = Simulate(c);
  if (std::getenv("MOORSIM_UPDATE_GOLDEN") != nullptr) {
    const char* ci = std::getenv("CI");
    ASSERT_FALSE(ci != nullptr && std::string(ci) == "true")
        << "golden files are never rewritten under CI=true";
    std::ofstream out(GoldenPath(c));
    out << now.dump(1) << "\n";
    ASSERT_TRUE(out.good()) << "cannot write " << GoldenPath(c);
    GTEST_SKIP() << "golden file rewritten: " << GoldenPath(c);
  }
  std::ifstream in(GoldenPath(c));
  ASSERT_TRUE(in) << "missing golden file " << GoldenPath(c);
  const json golden = json::parse(in);
  ASSERT_EQ(now["detector_labels"], golden["detector_labels"]);
  const json& a = now["samples"];
  const json& b = golden["samples"];
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::string at = "t = " + std::to_string(b[k]["time"].get<double>()) + " s ";
    ASSERT_EQ(a[k]["time"], b[k]["time"]);
    // Pose: 5 mm and 5e-5 rad (heading 0.003 deg); tensions 2 kN of ~5 MN; thrust 5 kN.
    const json& pa = a[k]["pose"];
    const json& pb = b[k]["pose"];
    ExpectNear(json(std::vector<double>(pa.begin(), pa.begin() + 3)),
               json(std::vector<double>(pb.begin(), pb.begin() + 3)), 5e-3, 0.0, at + "position");
    ExpectNear(json(std::vector<double>(pa.begin() + 3, pa.end())),
               json(std::vector<double>(pb.begin() + 3, pb.end())), 5e-5, 0.0, at + "angles");
    ExpectNear(a[k]["tension"], b[k]["tension"], 2e3, 0.0, at + "tension");
    ExpectNear(a[k]["thrust"], b[k]["thrust"], 5e3, 0.0, at + "thrust");
    ASSERT_EQ(a[k]["detectors"].size(), b[k]["detectors"].size());
    for (std::size_t d = 0; d < a[k]["detectors"].size(); ++d) {
      const json& da = a[k]["detectors"][d];
      const json& db = b[k]["detectors"][d];
      const std::string label = at + golden["detector_labels"][d].get<std::string>();
      // Decisions and alarms exactly; scores (probabilities, nats, statistics) to 1e-3
      // relative plus 1e-3 absolute.
      EXPECT_EQ(da["decision"], db["decision"]) << label;
      EXPECT_EQ(da["alarm"], db["alarm"]) << label;
      ExpectNear(da["score"], db["score"], 1e-3, 1e-3, label + " score");
    }
  }
  // The integrator's work within 5 %: a change of settings or Jacobian shows here first.
  for (const char* counter : {"steps", "rhs_evaluations", "jacobian_evaluations"}) {
    const double n = now["integrator"][counter].get<double>();
    const double g = golden["integrator"][counter].get<double>();
    EXPECT_NEAR(n, g, 0.05 * g) << counter;
  }
}

std::string CaseName(const ::testing::TestParamInfo<GoldenCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Library, CoupledGolden,
                         ::testing::Values(GoldenCase{"seed_tapm_coupled", "seed_tapm.yaml", 300.0,
                                                      10.0}),
                         CaseName);
// The longer run: labelled slow by the prefix.
INSTANTIATE_TEST_SUITE_P(LibrarySlow, CoupledGolden,
                         ::testing::Values(GoldenCase{"thesis_line6_current",
                                                      "thesis_line6_current.yaml", 1000.0, 25.0}),
                         CaseName);

}  // namespace
}  // namespace moorsim::simulation
