#include "mooring_fem/axial_curve.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace moorsim::mooring_fem {

AxialCurve::AxialCurve(const std::vector<StrainTension>& points) {
  if (points.empty()) throw InputError("tension_strain: give at least one point");
  e_.push_back(0.0);
  t_.push_back(0.0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const StrainTension& p = points[k];
    if (!(std::isfinite(p.strain) && std::isfinite(p.tension) && p.strain > e_.back() &&
          p.tension > t_.back())) {
      throw InputError("tension_strain[" + std::to_string(k + 1) +
                       "]: strain and tension must both increase from the point before (the "
                       "first from 0, 0)");
    }
    e_.push_back(p.strain);
    t_.push_back(p.tension);
  }
  // Fritsch-Carlson: secant slopes d_k, knot slopes their harmonic-type mean where the
  // neighbours agree (they always do here: the data increase), one-sided at the ends, then
  // limited so that the interpolant stays monotone.
  const std::size_t n = e_.size();
  std::vector<double> d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) d[k] = (t_[k + 1] - t_[k]) / (e_[k + 1] - e_[k]);
  m_.assign(n, 0.0);
  m_.front() = d.front();
  m_.back() = d.back();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h0 = e_[k] - e_[k - 1], h1 = e_[k + 1] - e_[k];
    const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
    m_[k] = (w0 + w1) / (w0 / d[k - 1] + w1 / d[k]);  // weighted harmonic mean
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double a = m_[k] / d[k], b = m_[k + 1] / d[k];
    const double r = a * a + b * b;
    if (r > 9.0) {
      const double tau = 3.0 / std::sqrt(r);
      m_[k] = tau * a * d[k];
      m_[k + 1] = tau * b * d[k];
    }
  }
}

double AxialCurve::Tension(double strain, double* slope) const {
  if (strain >= e_.back()) {
    if (slope) *slope = m_.back();
    return t_.back() + m_.back() * (strain - e_.back());
  }
  strain = std::max(strain, 0.0);
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(e_.begin(), e_.end(), strain) - e_.begin() - 1);
  const double h = e_[k + 1] - e_[k];
  const double s = (strain - e_[k]) / h;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  if (slope) {
    const double d00 = (6 * s2 - 6 * s) / h, d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h,
                 d11 = 3 * s2 - 2 * s;
    *slope = d00 * t_[k] + d10 * m_[k] + d01 * t_[k + 1] + d11 * m_[k + 1];
  }
  return h00 * t_[k] + h10 * h * m_[k] + h01 * t_[k + 1] + h11 * h * m_[k + 1];
}

double AxialCurve::Strain(double tension) const {
  if (tension <= 0.0) return 0.0;
  if (tension >= t_.back()) return e_.back() + (tension - t_.back()) / m_.back();
  // Bisection on the knot interval, then Newton (safeguarded) on the monotone cubic.
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), tension) - t_.begin() - 1);
  double lo = e_[k], hi = e_[k + 1];
  double e = lo + (hi - lo) * (tension - t_[k]) / (t_[k + 1] - t_[k]);
  for (int i = 0; i < 100; ++i) {
    double slope = 0.0;
    const double f = Tension(e, &slope) - tension;
    if (f > 0.0) {
      hi = e;
    } else {
      lo = e;
    }
    if (std::abs(f) <= 1e-14 * tension || hi - lo <= 1e-16 * hi) break;
    const double next = slope > 0.0 ? e - f / slope : 0.5 * (lo + hi);
    e = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return e;
}

double AxialCurve::Energy(double strain) const {
  // Simpson's rule is exact for the cubic on each interval.
  const auto piece = [this](double a, double b) {
    return (b - a) / 6.0 * (Tension(a) + 4.0 * Tension(0.5 * (a + b)) + Tension(b));
  };
  double energy = 0.0;
  for (std::size_t k = 0; k + 1 < e_.size() && e_[k] < strain; ++k) {
    energy += piece(e_[k], std::min(strain, e_[k + 1]));
  }
  if (strain > e_.back()) {
    const double over = strain - e_.back();
    energy += t_.back() * over + 0.5 * m_.back() * over * over;
  }
  return energy;
}

double AxialCurve::MaxSlope() const {
  // The cubic's slope is largest at a knot or where its derivative peaks inside an
  // interval: sample each interval finely enough for a stiffness scale.
  double largest = 0.0;
  for (std::size_t k = 0; k + 1 < e_.size(); ++k) {
    for (int i = 0; i <= 16; ++i) {
      double slope = 0.0;
      Tension(e_[k] + (e_[k + 1] - e_[k]) * i / 16.0, &slope);
      largest = std::max(largest, slope);
    }
  }
  return std::max(largest, m_.back());
}

}  // namespace moorsim::mooring_fem
