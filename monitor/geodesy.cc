#include "monitor/geodesy.h"

#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"

namespace moorsim::monitor {
namespace {

void CheckPosition(double latitude, double longitude, double height) {
  if (!(latitude >= -90.0 && latitude <= 90.0)) {
    throw InputError("latitude " + FormatNumber(latitude) + " deg is not in [-90, 90]");
  }
  if (!(longitude >= -180.0 && longitude < 360.0)) {
    throw InputError("longitude " + FormatNumber(longitude) + " deg is not in [-180, 360)");
  }
  if (!std::isfinite(height)) throw InputError("height " + FormatNumber(height) + " m");
}

}  // namespace

GeodeticFrame::GeodeticFrame(double latitude, double longitude, double height) {
  CheckPosition(latitude, longitude, height);
  frame_ = std::make_unique<GeographicLib::LocalCartesian>(latitude, longitude, height);
}

GeodeticFrame::~GeodeticFrame() = default;
GeodeticFrame::GeodeticFrame(GeodeticFrame&&) noexcept = default;
GeodeticFrame& GeodeticFrame::operator=(GeodeticFrame&&) noexcept = default;

Vec3 GeodeticFrame::NorthEastDown(double latitude, double longitude, double height) const {
  CheckPosition(latitude, longitude, height);
  double east = 0.0, north = 0.0, up = 0.0;
  frame_->Forward(latitude, longitude, height, east, north, up);
  return Vec3(north, east, -up);
}

Vec3 GeodeticFrame::LatitudeLongitudeHeight(const Vec3& ned) const {
  double latitude = 0.0, longitude = 0.0, height = 0.0;
  frame_->Reverse(ned.y(), ned.x(), -ned.z(), latitude, longitude, height);
  return Vec3(latitude, longitude, height);
}

}  // namespace moorsim::monitor
