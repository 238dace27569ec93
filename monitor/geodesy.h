// The scenario's north-east frame on the Earth: a GNSS position in latitude and longitude
// (WGS84) as metres north, east and down of the frame's geodetic origin on its tangent
// plane, and back. Exact, through Earth-centred coordinates (GeographicLib's
// LocalCartesian), not a flat-earth formula: at 60 deg latitude a point 1 km east lies
// 0.14 m north of the origin's parallel on the tangent plane, and the difference grows
// with the square of the distance. Heights are above the ellipsoid.
#pragma once

#include <memory>

#include "core/types.h"

namespace GeographicLib {
class LocalCartesian;
}

namespace moorsim::monitor {

class GeodeticFrame {
 public:
  /// The frame with its origin at `latitude`, `longitude` [deg] (north, east positive).
  /// Throws InputError for a latitude outside [-90, 90], a longitude outside [-180, 360)
  /// or values that are not finite.
  GeodeticFrame(double latitude, double longitude, double height = 0.0);
  ~GeodeticFrame();
  GeodeticFrame(GeodeticFrame&&) noexcept;
  GeodeticFrame& operator=(GeodeticFrame&&) noexcept;

  /// Where `latitude`, `longitude` [deg] at `height` [m] lies: metres north and east of the
  /// origin, on the origin's tangent plane. InputError as for the constructor.
  Vec3 NorthEastDown(double latitude, double longitude, double height = 0.0) const;
  /// The latitude, longitude [deg] and height [m] of a point north, east and down of the
  /// origin.
  Vec3 LatitudeLongitudeHeight(const Vec3& north_east_down) const;

 private:
  std::unique_ptr<GeographicLib::LocalCartesian> frame_;
};

}  // namespace moorsim::monitor
