#include "mooring_fem/environment.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/format.h"

namespace moorsim::mooring_fem {

CurrentField::CurrentField(const CurrentProfile& profile)
    : direction_(std::cos(profile.direction), std::sin(profile.direction), 0.0),
      depth_(profile.depth),
      speed_(profile.speed),
      table_(profile.table) {}

namespace {

// Index i of the profile interval [depth[i], depth[i+1]] holding z; -1 or n-1 outside.
int Interval(const std::vector<double>& depth, double z) {
  if (z < depth.front()) return -1;
  const auto it = std::upper_bound(depth.begin(), depth.end(), z);
  return static_cast<int>(it - depth.begin()) - 1;
}

// Where a coordinate falls on one axis of a table: the value there is (1 - w) v[lower] +
// w v[upper], and dw is dw/dcoordinate.
struct AxisPlace {
  int lower = 0, upper = 0;
  double w = 0.0, dw = 0.0;
};

// Held constant beyond the ends.
AxisPlace PlaceOn(const std::vector<double>& axis, double c) {
  const int i = Interval(axis, c);
  const int n = static_cast<int>(axis.size());
  if (i < 0) return {0, 0, 0.0, 0.0};
  if (i >= n - 1) return {n - 1, n - 1, 0.0, 0.0};
  const double h = axis[i + 1] - axis[i];
  return {i, i + 1, (c - axis[i]) / h, 1.0 / h};
}

// Repeating with `period` after the first time: from the last time back to the first over
// the gap to the period's end.
AxisPlace PlaceInTime(const std::vector<double>& times, double period, double t) {
  if (period <= 0.0 || times.size() == 1) return PlaceOn(times, t);
  const double t0 = times.front();
  double tau = std::fmod(t - t0, period);
  if (tau < 0.0) tau += period;
  tau += t0;
  const int n = static_cast<int>(times.size());
  if (tau < times.back()) return PlaceOn(times, tau);
  const double h = t0 + period - times.back();
  return {n - 1, 0, (tau - times.back()) / h, 1.0 / h};
}

}  // namespace

Vec3 CurrentField::ProfileVelocity(double z) const {
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

Mat3 CurrentField::GradientAt(double t, const Vec3& r) const {
  Mat3 gradient = Mat3::Zero();
  if (table_ != nullptr) {
    TableVelocity(t, r, &gradient);
    return gradient;
  }
  if (depth_.empty()) return gradient;
  const int n = static_cast<int>(depth_.size());
  const int i = Interval(depth_, r.z());
  if (i < 0 || i >= n - 1) return gradient;
  gradient.col(2) = (speed_[i + 1] - speed_[i]) / (depth_[i + 1] - depth_[i]) * direction_;
  return gradient;
}

Vec3 CurrentField::TableVelocity(double t, const Vec3& r, Mat3* gradient) const {
  const CurrentTable& g = *table_;
  const AxisPlace place[4] = {PlaceOn(g.x, r.x()), PlaceOn(g.y, r.y()), PlaceOn(g.z, r.z()),
                              PlaceInTime(g.t, g.period, t)};
  const int ny = static_cast<int>(g.y.size()), nz = static_cast<int>(g.z.size()),
            nt = static_cast<int>(g.t.size());
  Vec3 velocity = Vec3::Zero();
  // The 16 corners around the point, each weighted by the product of its axes' weights;
  // the gradient's column d takes dw in place of w on axis d.
  for (int corner = 0; corner < 16; ++corner) {
    int index[4];
    double factor[4], d_factor[4];
    for (int a = 0; a < 4; ++a) {
      const bool up = (corner >> a) & 1;
      index[a] = up ? place[a].upper : place[a].lower;
      factor[a] = up ? place[a].w : 1.0 - place[a].w;
      d_factor[a] = up ? place[a].dw : -place[a].dw;
    }
    const double weight = factor[0] * factor[1] * factor[2] * factor[3];
    const Vec3& v = g.velocity[((index[0] * ny + index[1]) * nz + index[2]) * nt + index[3]];
    velocity += weight * v;
    if (gradient != nullptr) {
      for (int d = 0; d < 3; ++d) {
        double w = d_factor[d] * factor[3];
        for (int a = 0; a < 3; ++a) {
          if (a != d) w *= factor[a];
        }
        gradient->col(d) += w * v;
      }
    }
  }
  return velocity;
}

std::string CurrentSpeedProblem(const Vec3& velocity) {
  if (velocity.norm() <= kMaxCurrentSpeed) return "";
  return "a current of " + FormatNumber(velocity.norm()) +
         " m/s must be <= " + FormatNumber(kMaxCurrentSpeed) +
         " m/s (the strongest tidal races run at about 10 m/s)";
}

void CheckCurrentTable(const CurrentTable& table) {
  const std::string where = table.source.empty() ? "current table" : table.source;
  const std::pair<const std::vector<double>*, const char*> axes[] = {
      {&table.x, "x"}, {&table.y, "y"}, {&table.z, "depth"}, {&table.t, "time"}};
  std::size_t points = 1;
  for (const auto& [axis, name] : axes) {
    if (axis->empty()) throw InputError(where + ": the " + std::string(name) + " axis is empty");
    for (std::size_t i = 0; i < axis->size(); ++i) {
      if (!std::isfinite((*axis)[i]) || (i > 0 && !((*axis)[i] > (*axis)[i - 1]))) {
        throw InputError(where + ": the " + std::string(name) +
                         " axis must hold finite values, strictly increasing");
      }
    }
    points *= axis->size();
  }
  if (table.velocity.size() != points) {
    throw InputError(where + ": " + std::to_string(table.velocity.size()) +
                     " velocities for a grid of " + std::to_string(points) + " points");
  }
  for (const Vec3& v : table.velocity) {
    if (!v.allFinite()) throw InputError(where + ": a velocity is not finite");
    if (const std::string problem = CurrentSpeedProblem(v); !problem.empty()) {
      throw InputError(where + ": " + problem);
    }
  }
  if (!(table.period >= 0.0) || !std::isfinite(table.period) ||
      (table.period > 0.0 && !(table.period > table.t.back() - table.t.front()))) {
    throw InputError(where + ": the period must be longer than the times it repeats (" +
                     FormatNumber(table.t.back() - table.t.front()) + " s)");
  }
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
