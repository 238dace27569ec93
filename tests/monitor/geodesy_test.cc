// The scenario's frame on the Earth (monitor/geodesy.h) against closed forms on the WGS84
// ellipsoid written here: a point 100 m along the meridian or the parallel is at the arc
// lengths the radii of curvature give, with the tangent plane's drop and the parallel's
// curvature to second order (within 10 um); a position goes to metres and back to the same
// latitude and longitude; bad coordinates are InputErrors.
#include "monitor/geodesy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace moorsim::monitor {
namespace {

constexpr double kA = 6378137.0;            // WGS84 semi-major axis [m]
constexpr double kF = 1.0 / 298.257223563;  // flattening
constexpr double kE2 = kF * (2.0 - kF);     // first eccentricity squared
constexpr double kDeg = std::numbers::pi / 180.0;

// The ellipsoid's radii of curvature at latitude phi [rad]: meridian M, prime vertical N.
double Meridian(double phi) {
  const double s = std::sin(phi);
  return kA * (1.0 - kE2) / std::pow(1.0 - kE2 * s * s, 1.5);
}
double PrimeVertical(double phi) {
  return kA / std::sqrt(1.0 - kE2 * std::sin(phi) * std::sin(phi));
}

TEST(GeodeticFrame, ArcsAlongTheMeridianAndTheParallelAreWhereTheRadiiPutThem) {
  const double lat0 = 60.4611, lon0 = 5.3227;  // a North Sea field
  const GeodeticFrame frame(lat0, lon0);
  const Vec3 origin = frame.NorthEastDown(lat0, lon0);
  EXPECT_NEAR(origin.norm(), 0.0, 1e-9);

  // 100 m north along the meridian: the arc M dphi (M's change over it is 7 um), below
  // the tangent plane by s^2 / (2 M).
  const double phi0 = lat0 * kDeg;
  const double s = 100.0;
  const Vec3 north = frame.NorthEastDown(lat0 + s / Meridian(phi0) / kDeg, lon0);
  EXPECT_NEAR(north.x(), s, 1e-5);
  EXPECT_NEAR(north.y(), 0.0, 1e-9);
  EXPECT_NEAR(north.z(), s * s / (2.0 * Meridian(phi0)), 1e-5);

  // 100 m east along the parallel (radius p = N cos phi): the chord's east part p sin(dl),
  // its north part p (1 - cos dl) sin phi (the parallel curves toward the pole).
  const double p = PrimeVertical(phi0) * std::cos(phi0);
  const double dl = s / p;
  const Vec3 east = frame.NorthEastDown(lat0, lon0 + dl / kDeg);
  EXPECT_NEAR(east.y(), p * std::sin(dl), 1e-5);
  EXPECT_NEAR(east.x(), p * (1.0 - std::cos(dl)) * std::sin(phi0), 1e-5);
  EXPECT_GT(east.x(), 1e-3);  // 1.4 mm: a flat-earth formula would put it at 0
}

TEST(GeodeticFrame, MetresGoBackToTheSameLatitudeAndLongitude) {
  const GeodeticFrame frame(-22.9, -40.2);  // the Campos basin
  for (const Vec3& ned : {Vec3(35.0, -12.5, 0.0), Vec3(-4000.0, 2500.0, 1.0), Vec3(0, 0, 0)}) {
    const Vec3 llh = frame.LatitudeLongitudeHeight(ned);
    const Vec3 back = frame.NorthEastDown(llh.x(), llh.y(), llh.z());
    EXPECT_NEAR((back - ned).norm(), 0.0, 1e-8) << ned.transpose();
  }
}

TEST(GeodeticFrame, CoordinatesOutOfRangeAreInputErrors) {
  EXPECT_THROW(GeodeticFrame(91.0, 0.0), InputError);
  EXPECT_THROW(GeodeticFrame(std::nan(""), 0.0), InputError);
  EXPECT_THROW(GeodeticFrame(0.0, 360.0), InputError);
  const GeodeticFrame frame(10.0, 20.0);
  EXPECT_THROW(frame.NorthEastDown(10.0, std::nan("")), InputError);
  EXPECT_THROW(frame.NorthEastDown(-90.5, 20.0), InputError);
  EXPECT_NO_THROW(frame.NorthEastDown(10.0, 20.0 + 1e-6));
}

}  // namespace
}  // namespace moorsim::monitor
