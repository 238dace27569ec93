#include "detectors/glr.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "core/angles.h"
#include "core/error.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

namespace {

[[noreturn]] void ThrowBadSample(double t, std::string_view what) {
  std::ostringstream message;
  message << "glr: " << what << " at t = " << t << " s";
  throw SolverError(message.str());
}

}  // namespace

double ChiSquareSurvival(int dof, double x) {
  internal::Require(dof >= 1 && dof <= 3, "ChiSquareSurvival", "dof in {1, 2, 3}");
  if (!(x > 0.0)) return 1.0;
  switch (dof) {
    case 1:
      return std::erfc(std::sqrt(0.5 * x));
    case 2:
      return std::exp(-0.5 * x);
    default:
      return std::erfc(std::sqrt(0.5 * x)) + std::sqrt(2.0 * x / kPi) * std::exp(-0.5 * x);
  }
}

double GlrDefaultThreshold(double false_alarm_probability, int window) {
  internal::Require(false_alarm_probability > 0.0 && false_alarm_probability < 1.0,
                    "GlrDefaultThreshold", "false_alarm_probability in (0, 1)");
  internal::Require(window >= 1, "GlrDefaultThreshold", "window >= 1");
  const double tail = false_alarm_probability / window;
  // The survival function falls monotonically from 1 at 0; below 1e-300 at x = 1400.
  double low = 0.0;
  double high = 1400.0;
  while (high - low > 1e-12 * high) {
    const double mid = 0.5 * (low + high);
    if (ChiSquareSurvival(3, mid) > tail) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return 0.5 * (low + high);
}

std::optional<std::array<bool, 3>> CarriedChannels(const HypothesisEvidence& evidence) {
  if (evidence.dimension == 3) return std::array<bool, 3>{true, true, true};
  if (evidence.dimension < 0 || evidence.dimension > 3) return std::nullopt;
  std::array<bool, 3> carried{};
  int count = 0;
  for (int c = 0; c < 3; ++c) {
    carried[c] = evidence.innovation[c] != 0.0;
    count += carried[c] ? 1 : 0;
  }
  if (count != evidence.dimension) return std::nullopt;
  return carried;
}

std::optional<Vec3> WhitenInnovation(const Mat3& covariance, const Vec3& v,
                                     const std::array<bool, 3>& carried) {
  // Cholesky of the carried block, written out for at most 3 x 3 (no allocation).
  std::array<int, 3> index{};
  int d = 0;
  for (int c = 0; c < 3; ++c) {
    if (carried[c]) index[d++] = c;
  }
  double l[3][3] = {};
  for (int a = 0; a < d; ++a) {
    for (int b = 0; b <= a; ++b) {
      double sum = covariance(index[a], index[b]);
      for (int m = 0; m < b; ++m) sum -= l[a][m] * l[b][m];
      if (a == b) {
        if (!(sum > 0.0) || !std::isfinite(sum)) return std::nullopt;
        l[a][a] = std::sqrt(sum);
      } else {
        l[a][b] = sum / l[b][b];
      }
    }
  }
  Vec3 w = Vec3::Zero();
  double solved[3] = {};
  for (int a = 0; a < d; ++a) {  // forward substitution L solved = v(carried)
    double sum = v[index[a]];
    for (int m = 0; m < a; ++m) sum -= l[a][m] * solved[m];
    solved[a] = sum / l[a][a];
    w[index[a]] = solved[a];
  }
  if (!w.allFinite()) return std::nullopt;
  return w;
}

Glr::Glr(const GlrOptions& options) : options_(options) {
  internal::Require(options.window >= 2, "glr", "window >= 2");
  internal::Require(options.hold >= 0.0, "glr", "hold >= 0");
  internal::Require(options.false_alarm_probability > 0.0 && options.false_alarm_probability < 1.0,
                    "glr", "false_alarm_probability in (0, 1)");
  internal::Require(!options.threshold || *options.threshold > 0.0, "glr", "threshold > 0");
  threshold_ = options.threshold
                   ? *options.threshold
                   : GlrDefaultThreshold(options.false_alarm_probability, options.window);
}

void Glr::SetSignatures(std::vector<Vec3> signatures) {
  internal::Require(hypotheses_ == 0 || signatures.empty() ||
                        static_cast<int>(signatures.size()) == hypotheses_ - 1,
                    "glr", "one signature per failure hypothesis (N - 1 of them)");
  signatures_ = std::move(signatures);
}

void Glr::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "glr", "at least one hypothesis");
  internal::Require(signatures_.empty() || static_cast<int>(signatures_.size()) == hypotheses - 1,
                    "glr", "one signature per failure hypothesis (N - 1 of them)");
  hypotheses_ = hypotheses;
  whitened_.setZero(3, options_.window);
  carried_.setZero(3, options_.window);
  log_likelihood_.setZero(hypotheses, options_.window);
  newest_ = -1;
  filled_ = 0;
  change_samples_ = 0;
  verdict_.score.assign(static_cast<std::size_t>(hypotheses), 0.0);
  verdict_.hypothesis = 0;
  verdict_.alarm = false;
  exceeding_ = false;
  exceeding_since_ = 0.0;
}

int Glr::Slot(int back) const {
  const int slot = newest_ - back;
  return slot < 0 ? slot + options_.window : slot;
}

double Glr::MeanChangeStatistic(int samples) const {
  internal::Require(samples >= 1 && samples <= filled_, "glr",
                    "MeanChangeStatistic: 1 <= samples <= filled()");
  Vec3 sum = Vec3::Zero();
  Vec3 count = Vec3::Zero();
  for (int back = 0; back < samples; ++back) {
    sum += whitened_.col(Slot(back));
    count += carried_.col(Slot(back));
  }
  double g = 0.0;
  for (int c = 0; c < 3; ++c) {
    if (count[c] > 0.0) g += sum[c] * sum[c] / count[c];
  }
  return g;
}

Verdict Glr::Update(const Evidence& evidence) { return Step(evidence); }

const Verdict& Glr::Step(const Evidence& evidence) {
  internal::CheckEvidence("glr", evidence, hypotheses_);
  const HypothesisEvidence& intact = evidence.nominal ? *evidence.nominal : evidence.hypotheses[0];
  if (!intact.innovation.allFinite()) ThrowBadSample(evidence.t, "non-finite intact innovation");
  if (!intact.covariance.allFinite()) ThrowBadSample(evidence.t, "non-finite intact covariance");

  // Push the sample into the ring.
  newest_ = newest_ + 1 == options_.window ? 0 : newest_ + 1;
  filled_ = std::min(filled_ + 1, options_.window);
  const std::optional<std::array<bool, 3>> carried = CarriedChannels(intact);
  Vec3 w = Vec3::Zero();
  Vec3 carried_mask = Vec3::Zero();
  if (carried) {
    const std::optional<Vec3> whitened =
        WhitenInnovation(intact.covariance, intact.innovation, *carried);
    if (!whitened) ThrowBadSample(evidence.t, "intact covariance not positive definite");
    w = *whitened;
    for (int c = 0; c < 3; ++c) carried_mask[c] = (*carried)[c] ? 1.0 : 0.0;
  }
  whitened_.col(newest_) = w;
  carried_.col(newest_) = carried_mask;
  for (int k = 0; k < hypotheses_; ++k) {
    log_likelihood_(k, newest_) = evidence.hypotheses[k].log_likelihood;
  }

  // One backward sweep over the change times j = k, k-1, ..., k-filled+1.
  std::vector<double>& score = verdict_.score;
  std::fill(score.begin(), score.end(), 0.0);
  const bool use_signatures = !signatures_.empty();
  Vec3 sum = Vec3::Zero();
  Vec3 count = Vec3::Zero();
  double g = 0.0;
  change_samples_ = 0;
  for (int back = 0; back < filled_; ++back) {
    sum += whitened_.col(Slot(back));
    count += carried_.col(Slot(back));
    double g_j = 0.0;
    for (int c = 0; c < 3; ++c) {
      if (count[c] > 0.0) g_j += sum[c] * sum[c] / count[c];
    }
    if (g_j > g) {
      g = g_j;
      change_samples_ = back + 1;
    }
    if (!use_signatures) continue;
    for (int k = 1; k < hypotheses_; ++k) {
      const Vec3& s = signatures_[static_cast<std::size_t>(k - 1)];
      const double projection = s.dot(sum);
      if (projection <= 0.0) continue;  // the amplitude nu is one-sided
      const double information = count.dot(s.cwiseProduct(s));
      if (information <= 0.0) continue;
      score[static_cast<std::size_t>(k)] =
          std::max(score[static_cast<std::size_t>(k)], projection * projection / information);
    }
  }
  score[0] = g;
  if (!use_signatures && hypotheses_ > 1) {
    // Fallback isolation: 2 x windowed log-likelihood ratio against the intact hypothesis.
    double intact_sum = 0.0;
    for (int back = 0; back < filled_; ++back) intact_sum += log_likelihood_(0, Slot(back));
    for (int k = 1; k < hypotheses_; ++k) {
      double sum_k = 0.0;
      for (int back = 0; back < filled_; ++back) sum_k += log_likelihood_(k, Slot(back));
      score[static_cast<std::size_t>(k)] = 2.0 * (sum_k - intact_sum);
    }
  }

  const bool exceeded = g > threshold_;
  if (!exceeded) {
    exceeding_ = false;
  } else if (!exceeding_) {
    exceeding_ = true;
    exceeding_since_ = evidence.t;
  }
  verdict_.alarm = exceeded && evidence.t - exceeding_since_ >= options_.hold;
  verdict_.hypothesis = 0;
  if (exceeded && hypotheses_ > 1) {
    verdict_.hypothesis =
        static_cast<int>(std::max_element(score.begin() + 1, score.end()) - score.begin());
  }
  return verdict_;
}

}  // namespace moorsim::detectors
