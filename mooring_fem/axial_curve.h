// A line's axial tension as a function of its strain, from a measured tension-strain table
// (a polyester or nylon rope's, whose stiffness grows with its load): the monotone cubic
// Hermite interpolant of the points (Fritsch & Carlson 1980) through (0, 0) and the table,
// so the tension and its slope are continuous (the implicit integrator's Newton iteration
// sees no kink) and the tension never falls as the strain grows. Beyond the last point the
// tension goes on with the last point's slope.
#pragma once

#include <vector>

namespace moorsim::mooring_fem {

struct StrainTension {
  double strain = 0.0;   ///< [-]
  double tension = 0.0;  ///< [N]
};

class AxialCurve {
 public:
  /// `points`: strains and tensions both strictly increasing from above zero (the origin is
  /// added). Throws moorsim::InputError otherwise, naming the point (1-based).
  explicit AxialCurve(const std::vector<StrainTension>& points);

  /// T(e) [N] for a strain e >= 0, and dT/de [N] if `slope` is given.
  double Tension(double strain, double* slope = nullptr) const;
  /// The strain at tension T >= 0 (the inverse of Tension).
  double Strain(double tension) const;
  /// The elastic energy per unit unstretched length, the integral of T from 0 to e [N].
  double Energy(double strain) const;
  /// The largest slope dT/de [N]: the stiffness of the curve's stiffest part.
  double MaxSlope() const;

 private:
  std::vector<double> e_, t_, m_;  // knots and Hermite slopes
};

}  // namespace moorsim::mooring_fem
