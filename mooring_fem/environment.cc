#include "mooring_fem/environment.h"

#include <algorithm>
#include <cmath>

namespace moorsim::mooring_fem {

CurrentField::CurrentField(const CurrentProfile& profile)
    : direction_(std::cos(profile.direction), std::sin(profile.direction), 0.0),
      depth_(profile.depth),
      speed_(profile.speed) {}

namespace {

// Index i of the profile interval [depth[i], depth[i+1]] holding z; -1 or n-1 outside.
int Interval(const std::vector<double>& depth, double z) {
  if (z < depth.front()) return -1;
  const auto it = std::upper_bound(depth.begin(), depth.end(), z);
  return static_cast<int>(it - depth.begin()) - 1;
}

}  // namespace

Vec3 CurrentField::VelocityAt(double z) const {
  if (depth_.empty()) return Vec3::Zero();
  const int n = static_cast<int>(depth_.size());
  const int i = Interval(depth_, z);
  double speed;
  if (i < 0) {
    speed = speed_.front();
  } else if (i >= n - 1) {
    speed = speed_.back();
  } else {
    const double f = (z - depth_[i]) / (depth_[i + 1] - depth_[i]);
    speed = speed_[i] + f * (speed_[i + 1] - speed_[i]);
  }
  return speed * direction_;
}

Vec3 CurrentField::GradientAt(double z) const {
  if (depth_.empty()) return Vec3::Zero();
  const int n = static_cast<int>(depth_.size());
  const int i = Interval(depth_, z);
  if (i < 0 || i >= n - 1) return Vec3::Zero();
  return (speed_[i + 1] - speed_[i]) / (depth_[i + 1] - depth_[i]) * direction_;
}

SeabedFrame SeabedContact::SlopedFrame(const Vec3& r, SeabedFrameDerivatives* derivatives) const {
  const SeabedPoint p = surface.At(r.x(), r.y());
  const Vec3 G(-p.dx, -p.dy, 1.0);  // grad (z - h)
  const double norm = G.norm();
  const double g = r.z() - p.depth;
  SeabedFrame f{G / norm, g / norm};
  if (derivatives == nullptr) return f;
  // dG/dr = -C with C the padded Hessian of h: only h_xy is nonzero (seabed.h).
  const Vec3 Cn(p.dxy * f.normal.y(), p.dxy * f.normal.x(), 0.0);
  derivatives->d_penetration = f.normal + (g / (norm * norm)) * Cn;
  Mat3 C = Mat3::Zero();
  C(0, 1) = C(1, 0) = p.dxy;
  derivatives->d_normal = -(Mat3::Identity() - f.normal * f.normal.transpose()) * C / norm;
  return f;
}

void SeabedContact::Penetration(double delta, double* q, double* dq) const {
  const double eps = regularisation;
  if (delta <= 0.0) {
    *q = 0.0;
    *dq = 0.0;
  } else if (delta < eps) {
    *q = 0.5 * delta * delta / eps;
    *dq = delta / eps;
  } else {
    *q = delta - 0.5 * eps;
    *dq = 1.0;
  }
}

void SeabedContact::DamperWeight(double delta, double* s, double* ds) const {
  const double eps = regularisation;
  if (delta <= 0.0) {
    *s = 0.0;
    *ds = 0.0;
  } else if (delta < eps) {
    const double x = delta / eps;
    *s = x * x * (3.0 - 2.0 * x);
    *ds = 6.0 * x * (1.0 - x) / eps;
  } else {
    *s = 1.0;
    *ds = 0.0;
  }
}

double SeabedContact::PenetrationEnergy(double delta) const {
  const double eps = regularisation;
  if (delta <= 0.0) return 0.0;
  if (delta < eps) return delta * delta * delta / (6.0 * eps);
  return eps * eps / 6.0 + 0.5 * (delta * delta - eps * eps) - 0.5 * eps * (delta - eps);
}

}  // namespace moorsim::mooring_fem
