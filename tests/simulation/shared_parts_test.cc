// The process-wide cache of read-only run parts (simulation/shared_parts.h): one build
// per key, the same object for every caller, also when threads ask at once; the detectors'
// parts of a set-up are built once for all its run seeds.
#include "simulation/shared_parts.h"
#include "scenarios/plant_builder.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "scenarios/load.h"
#include "simulation/simulation.h"

namespace moorsim::simulation {
namespace {

TEST(SharedPart, BuildsOncePerKeyAndTypeAndSharesTheObject) {
  int builds = 0;
  const auto build = [&builds] {
    ++builds;
    return std::vector<double>{1.0, 2.0};
  };
  const auto a = SharedPart<std::vector<double>>("shared_parts_test one", build);
  const auto b = SharedPart<std::vector<double>>("shared_parts_test one", build);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(builds, 1);
  const auto c = SharedPart<std::vector<double>>("shared_parts_test two", build);
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(builds, 2);
  // The same key for another type is another entry.
  const auto d =
      SharedPart<std::vector<int>>("shared_parts_test one", [] { return std::vector<int>{3}; });
  EXPECT_EQ(d->front(), 3);
}

TEST(SharedPart, ThreadsAskingAtOnceAllGetTheFirstStored) {
  std::atomic<int> builds{0};
  std::vector<const std::vector<int>*> seen(8, nullptr);
  std::vector<std::thread> threads;
  for (int i = 0; i < 8; ++i) {
    threads.emplace_back([&, i] {
      seen[static_cast<std::size_t>(i)] =
          SharedPart<std::vector<int>>("shared_parts_test threads", [&] {
            ++builds;
            return std::vector<int>(1000, 7);
          }).get();
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_GE(builds.load(), 1);
  for (const auto* p : seen) EXPECT_EQ(p, seen.front());
}

// The moored equilibrium is the calm-water one, so the hypothesis bank, the GLR signatures and
// the passive observers' training (from detection.training_seed) depend on the set-up, not
// on the run seed: a second seed with waves adds no entry, another set-up does.
TEST(SharedPartSlow, RunsOfOneSetUpShareTheDetectorsPartsWhateverTheirSeed) {
  const std::string library = MOORSIM_SOURCE_DIR "/scenarios/library/";
  const std::vector<std::string> passive = {"detection.observer=passive", "simulation.duration=500",
                                            "detectors=[{type: dht}, {type: mle}, {type: glr}]"};
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(library + "thesis_line6_current.yaml", passive);
  ASSERT_TRUE(scenario.environment.waves.enabled);
  const Simulation first(scenarios::ToPlantModel(scenario), 101);
  const std::size_t entries = SharedPartCount();
  const Simulation second(scenarios::ToPlantModel(scenario), 102);
  EXPECT_EQ(SharedPartCount(), entries);
  // The calm-water equilibrium, to the last bit, whatever the waves do at t = 0.
  EXPECT_EQ(first.initial_pose(), second.initial_pose());

  std::vector<std::string> other = passive;
  other.insert(other.end(), {"detection.measurement_variance=0.006"});
  const Simulation third(scenarios::ToPlantModel(
                             scenarios::LoadScenario(library + "thesis_line6_current.yaml", other)),
                         101);
  EXPECT_GT(SharedPartCount(), entries);
}

}  // namespace
}  // namespace moorsim::simulation
