#include "detectors/dht.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

namespace internal {

void ApplyProbabilityFloor(double floor, std::vector<double>& probability,
                           std::vector<char>& floored) {
  const std::size_t n = probability.size();
  std::fill(floored.begin(), floored.end(), 0);
  // Each pass floors at least one more entry or stops, so n + 1 passes always suffice.
  for (std::size_t pass = 0; pass <= n; ++pass) {
    std::size_t floored_count = 0;
    double free_mass = 0.0;  // the mass of the entries above the floor
    for (std::size_t k = 0; k < n; ++k) {
      if (!floored[k] && probability[k] < floor) floored[k] = 1;
      if (floored[k]) {
        ++floored_count;
      } else {
        free_mass += probability[k];
      }
    }
    if (floored_count == 0) return;
    // free_mass > 0: with n floor < 1 the largest entry never reaches the floor.
    const double scale = (1.0 - static_cast<double>(floored_count) * floor) / free_mass;
    bool more = false;
    for (std::size_t k = 0; k < n; ++k) {
      if (floored[k]) {
        probability[k] = floor;
      } else {
        probability[k] *= scale;
        more = more || probability[k] < floor;
      }
    }
    if (!more) return;
  }
}

}  // namespace internal

Dht::Dht(const DhtOptions& options) : options_(options) {
  internal::Require(options.floor > 0.0 && options.floor < 1.0, "dht", "floor in (0, 1)");
  internal::Require(options.threshold > 0.0 && options.threshold < 1.0, "dht",
                    "threshold in (0, 1)");
  internal::Require(options.hold >= 0.0, "dht", "hold >= 0");
  internal::Require(
      !options.prior_intact || (*options.prior_intact > 0.0 && *options.prior_intact < 1.0), "dht",
      "prior_intact in (0, 1)");
}

void Dht::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "dht", "at least one hypothesis");
  if (static_cast<double>(hypotheses) * options_.floor >= 1.0) {
    std::ostringstream message;
    message << "dht: floor " << options_.floor << " is too large for " << hypotheses
            << " hypotheses (floor times hypotheses must be < 1)";
    throw InputError(message.str());
  }
  const auto n = static_cast<std::size_t>(hypotheses);
  verdict_.score.assign(n, 1.0 / static_cast<double>(hypotheses));
  if (options_.prior_intact && hypotheses > 1) {
    verdict_.score[0] = *options_.prior_intact;
    std::fill(verdict_.score.begin() + 1, verdict_.score.end(),
              (1.0 - *options_.prior_intact) / static_cast<double>(hypotheses - 1));
  }
  if (hypotheses == 1) verdict_.score[0] = 1.0;
  log_weight_.assign(n, 0.0);
  floored_.assign(n, 0);
  internal::ApplyProbabilityFloor(options_.floor, verdict_.score, floored_);
  verdict_.hypothesis = static_cast<int>(
      std::max_element(verdict_.score.begin(), verdict_.score.end()) - verdict_.score.begin());
  verdict_.alarm = false;
  held_hypothesis_ = 0;
  held_since_ = 0.0;
}

Verdict Dht::Update(const Evidence& evidence) { return Step(evidence); }

const Verdict& Dht::Step(const Evidence& evidence) {
  internal::CheckEvidence("dht", evidence, static_cast<int>(verdict_.score.size()));
  std::vector<double>& posterior = verdict_.score;
  const std::size_t n = posterior.size();

  // Hassani et al. 2018, eq. 47 in log space: a_k = log h_k + log p(y | H_k), then log-sum-exp.
  double a_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    log_weight_[k] = std::log(posterior[k]) + evidence.hypotheses[k].log_likelihood;
    a_max = std::max(a_max, log_weight_[k]);
  }
  double total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    posterior[k] = std::exp(log_weight_[k] - a_max);  // the largest is exactly 1
    total += posterior[k];
  }
  for (double& h : posterior) h /= total;
  internal::ApplyProbabilityFloor(options_.floor, posterior, floored_);

  const auto best =
      static_cast<int>(std::max_element(posterior.begin(), posterior.end()) - posterior.begin());
  verdict_.hypothesis = best;
  const bool candidate =
      best != 0 && posterior[static_cast<std::size_t>(best)] >= options_.threshold;
  if (!candidate) {
    held_hypothesis_ = 0;
  } else if (held_hypothesis_ != best) {
    held_hypothesis_ = best;
    held_since_ = evidence.t;
  }
  verdict_.alarm = candidate && evidence.t - held_since_ >= options_.hold;
  return verdict_;
}

}  // namespace moorsim::detectors
