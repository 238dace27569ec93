#include "detectors/mle.h"

#include <algorithm>

#include "detectors/registry.h"

namespace moorsim::detectors {

Mle::Mle(const MleOptions& options) : options_(options) {
  internal::Require(options.forgetting_factor > 0.0 && options.forgetting_factor <= 1.0, "mle",
                    "forgetting_factor in (0, 1]");
  internal::Require(options.hold >= 0.0, "mle", "hold >= 0");
  internal::Require(options.margin >= 0.0, "mle", "margin >= 0");
}

void Mle::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "mle", "at least one hypothesis");
  verdict_.score.assign(static_cast<std::size_t>(hypotheses), 0.0);
  verdict_.hypothesis = 0;
  verdict_.alarm = false;
  leader_ = 0;
  leader_since_ = 0.0;
  started_ = false;
}

Verdict Mle::Update(const Evidence& evidence) { return Step(evidence); }

const Verdict& Mle::Step(const Evidence& evidence) {
  internal::CheckEvidence("mle", evidence, static_cast<int>(verdict_.score.size()));
  std::vector<double>& nll = verdict_.score;
  const double lambda = options_.forgetting_factor;
  for (std::size_t k = 0; k < nll.size(); ++k) {
    nll[k] = lambda * nll[k] - evidence.hypotheses[k].log_likelihood;
  }
  const auto best = static_cast<int>(std::min_element(nll.begin(), nll.end()) - nll.begin());
  if (!started_ || best != leader_) {
    leader_ = best;
    leader_since_ = evidence.t;
    started_ = true;
  }
  verdict_.hypothesis = best;
  verdict_.alarm = best != 0 && evidence.t - leader_since_ >= options_.hold &&
                   nll[0] - nll[static_cast<std::size_t>(best)] > options_.margin;
  return verdict_;
}

}  // namespace moorsim::detectors
