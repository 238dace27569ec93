// Latencies of a live service, summarised with bounded memory.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace moorsim::simulation {

/// Wall times [ms] of a live service's steps (`moorsim detect`: each sample in the observers
/// and detectors; the monitor: from a line's arrival to what it made announced): mean and
/// max over every one, the 99th percentile over the last kRecent (a day at 1 Hz), so that a
/// service that runs for months keeps bounded memory.
class Latency {
 public:
  static constexpr std::size_t kRecent = 86400;
  void Add(double ms) {
    if (recent_.size() < kRecent) {
      recent_.push_back(ms);
    } else {
      recent_[count_ % kRecent] = ms;
    }
    ++count_;
    sum_ += ms;
    max_ = std::max(max_, ms);
    last_ = ms;
  }
  double last() const { return last_; }
  double mean() const { return count_ > 0 ? sum_ / static_cast<double>(count_) : 0.0; }
  nlohmann::json Summary() const {
    if (count_ == 0) return {{"samples", 0}};
    std::vector<double> sorted = recent_;
    const std::size_t p99 =
        std::min(sorted.size() - 1, static_cast<std::size_t>(0.99 * sorted.size()));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(p99),
                     sorted.end());
    return {{"samples", count_},
            {"mean_ms", mean()},
            {"p99_ms", sorted[p99]},
            {"p99_over_samples", sorted.size()},
            {"max_ms", max_}};
  }

 private:
  std::vector<double> recent_;
  std::size_t count_ = 0;
  double sum_ = 0.0, max_ = 0.0, last_ = 0.0;
};

}  // namespace moorsim::simulation
