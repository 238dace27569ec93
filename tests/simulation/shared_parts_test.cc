// The process-wide cache of read-only run parts (tools/simulation/shared_parts.h): one build
// per key, the same object for every caller, also when threads ask at once.
#include "tools/simulation/shared_parts.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

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

}  // namespace
}  // namespace moorsim::simulation
