#include "vessel/hull_loads.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "vessel/checks.h"

namespace moorsim::vessel {
namespace {

// The ITTC-57 line is held below this Reynolds number (see IttcFrictionCoefficient).
constexpr double kMinFrictionReynolds = 1e5;

// A user table's first and last angle may be off 0 and pi by this much (a table written in
// degrees and converted, or pi typed to a few digits); the ends are then taken as 0 and pi.
constexpr double kTableEndTolerance = 1e-6;

// NPD spectrum shape exponent n (ISO 19901-1).
constexpr double kNpdShapeExponent = 0.468;

// Points of Hoerner's cross-flow drag curve, {B / (2 T), C_d2D}, as digitised by Leite et
// al. (1998); rounded to four digits. The steep fall near B / (2 T) = 0.5 is the change
// from a deep section (flow separating at the keel as from a plate) to a rounded one.
struct CurvePoint {
  double ratio;
  double drag;
};
constexpr std::array<CurvePoint, 20> kHoernerCurve{{
    {0.01086, 1.966}, {0.1766, 1.966}, {0.3530, 1.898}, {0.4519, 1.787},  {0.4728, 1.584},
    {0.4929, 1.279},  {0.4933, 1.211}, {0.5585, 1.084}, {0.6464, 0.9986}, {0.8336, 0.8796},
    {0.9880, 0.8284}, {1.308, 0.7599}, {1.639, 0.6914}, {1.860, 0.6571},  {2.313, 0.6307},
    {2.600, 0.5962},  {3.009, 0.5868}, {3.451, 0.5859}, {3.738, 0.5599},  {4.003, 0.5593},
}};

// Blendermann (1994), "tanker, loaded".
constexpr double kTankerLateralDrag = 0.70;        // C_Dt
constexpr double kTankerLongitudinalBow = 0.90;    // C_DlAF, wind from ahead
constexpr double kTankerLongitudinalStern = 0.55;  // C_DlAF, wind from astern
constexpr double kTankerCrossForce = 0.40;         // delta
// Blendermann's slope of the centre of effort against the wind angle [1/rad].
constexpr double kCentreOfEffortSlope = 0.18;

using internal::ThrowBadValue;

void RequirePositive(std::string_view field, double value, std::string_view unit) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    ThrowBadValue(field, value, unit, "must be > 0 and finite");
  }
}

void RequireNonNegative(std::string_view field, double value, std::string_view unit,
                        std::string_view meaning_of_zero) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    ThrowBadValue(field, value, unit,
                  "must be >= 0 and finite (" + std::string(meaning_of_zero) + ")");
  }
}

/// "[i]", the index suffix of a table field. (Built by appending: GCC 12 warns falsely,
/// -Wrestrict, on `"[" + std::to_string(i)`.)
std::string Index(std::size_t i) {
  std::string index = "[";
  index += std::to_string(i);
  index += ']';
  return index;
}

/// ITTC-57 C_F and its logarithmic derivative dC_F / d(ln Re) (0 where the line is held).
struct Friction {
  double coefficient;
  double log_slope;
};

Friction IttcFriction(double reynolds_number) {
  if (!(reynolds_number > kMinFrictionReynolds)) {
    const double denominator = std::log10(kMinFrictionReynolds) - 2.0;
    return {0.075 / (denominator * denominator), 0.0};
  }
  const double denominator = std::log10(reynolds_number) - 2.0;
  const double coefficient = 0.075 / (denominator * denominator);
  // d/d(ln Re) of 0.075 (log10 Re - 2)^-2 = -2 C_F / ((log10 Re - 2) ln 10).
  return {coefficient, -2.0 * coefficient / (denominator * std::numbers::ln10)};
}

/// Linear interpolation in a table with strictly increasing abscissae, held at the ends.
/// Allocation-free.
double Interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto upper = std::upper_bound(x.begin(), x.end(), at);
  const auto j = static_cast<std::size_t>(std::distance(x.begin(), upper));  // x[j-1] <= at
  const double fraction = (at - x[j - 1]) / (x[j] - x[j - 1]);
  return y[j - 1] + fraction * (y[j] - y[j - 1]);
}

void ValidateTable(const WindCoefficientTable& table) {
  const std::size_t rows = table.angle.size();
  if (rows < 2) {
    ThrowBadValue("wind.coefficients.angle size", static_cast<double>(rows), "",
                  "must be >= 2 (rows from 0 to pi)");
  }
  const auto check_size = [&](std::string_view field, const std::vector<double>& column) {
    if (column.size() != rows) {
      ThrowBadValue(field, static_cast<double>(column.size()), "",
                    "rows must equal the " + std::to_string(rows) + " angles");
    }
  };
  check_size("wind.coefficients.surge size", table.surge);
  check_size("wind.coefficients.sway size", table.sway);
  check_size("wind.coefficients.yaw size", table.yaw);
  for (std::size_t i = 0; i < rows; ++i) {
    const std::string row = Index(i);
    if (!std::isfinite(table.angle[i])) {
      ThrowBadValue("wind.coefficients.angle" + row, table.angle[i], "rad", "must be finite");
    }
    if (i > 0 && !(table.angle[i] > table.angle[i - 1])) {
      ThrowBadValue("wind.coefficients.angle" + row, table.angle[i], "rad",
                    "must be > the previous angle " + FormatNumber(table.angle[i - 1]) +
                        " rad (strictly increasing)");
    }
    if (!std::isfinite(table.surge[i])) {
      ThrowBadValue("wind.coefficients.surge" + row, table.surge[i], "", "must be finite");
    }
    if (!std::isfinite(table.sway[i])) {
      ThrowBadValue("wind.coefficients.sway" + row, table.sway[i], "", "must be finite");
    }
    if (!std::isfinite(table.yaw[i])) {
      ThrowBadValue("wind.coefficients.yaw" + row, table.yaw[i], "", "must be finite");
    }
  }
  const std::string last = Index(rows - 1);
  if (std::abs(table.angle.front()) > kTableEndTolerance) {
    ThrowBadValue("wind.coefficients.angle[0]", table.angle.front(), "rad",
                  "must be 0 (the table covers 0 to pi)");
  }
  if (std::abs(table.angle.back() - kPi) > kTableEndTolerance) {
    ThrowBadValue("wind.coefficients.angle" + last, table.angle.back(), "rad",
                  "must be pi (the table covers 0 to pi)");
  }
  const std::string mirror =
      "must be 0 at a head or stern wind (port winds use the mirror image, so a nonzero "
      "value would jump as the wind crosses the bow or stern)";
  if (table.sway.front() != 0.0) {
    ThrowBadValue("wind.coefficients.sway[0]", table.sway.front(), "", mirror);
  }
  if (table.sway.back() != 0.0) {
    ThrowBadValue("wind.coefficients.sway" + last, table.sway.back(), "", mirror);
  }
  if (table.yaw.front() != 0.0) {
    ThrowBadValue("wind.coefficients.yaw[0]", table.yaw.front(), "", mirror);
  }
  if (table.yaw.back() != 0.0) {
    ThrowBadValue("wind.coefficients.yaw" + last, table.yaw.back(), "", mirror);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Current

HullGeometry SeedFpsoHull() {
  HullGeometry hull;
  hull.length = 200.0;
  hull.beam = 44.0;
  hull.draught = 12.0;
  hull.displaced_volume = 97961.0;
  hull.form_factor =
      WatanabeFormFactor(hull.length, hull.beam, hull.draught, hull.displaced_volume);
  return hull;
}

double WatanabeFormFactor(double length, double beam, double draught, double displaced_volume) {
  RequirePositive("hull.length", length, "m");
  RequirePositive("hull.beam", beam, "m");
  RequirePositive("hull.draught", draught, "m");
  RequirePositive("hull.displaced_volume", displaced_volume, "m^3");
  const double block_coefficient = displaced_volume / (length * beam * draught);
  const double length_over_beam = length / beam;
  return -0.095 + 25.6 * block_coefficient /
                      (length_over_beam * length_over_beam * std::sqrt(beam / draught));
}

double DennyMumfordWettedSurface(double length, double draught, double displaced_volume) {
  RequirePositive("hull.length", length, "m");
  RequirePositive("hull.draught", draught, "m");
  RequirePositive("hull.displaced_volume", displaced_volume, "m^3");
  return 1.7 * length * draught + displaced_volume / draught;
}

double HoernerCrossFlowDragCoefficient(double half_beam_over_draught) {
  RequirePositive("hull B / (2 T)", half_beam_over_draught, "");
  const double ratio = half_beam_over_draught;
  if (ratio <= kHoernerCurve.front().ratio) return kHoernerCurve.front().drag;
  if (ratio >= kHoernerCurve.back().ratio) return kHoernerCurve.back().drag;
  const auto upper =
      std::upper_bound(kHoernerCurve.begin(), kHoernerCurve.end(), ratio,
                       [](double value, const CurvePoint& point) { return value < point.ratio; });
  const CurvePoint& right = *upper;
  const CurvePoint& left = *(upper - 1);
  const double fraction = (ratio - left.ratio) / (right.ratio - left.ratio);
  return left.drag + fraction * (right.drag - left.drag);
}

double IttcFrictionCoefficient(double reynolds_number) {
  return IttcFriction(reynolds_number).coefficient;
}

CurrentLoad::CurrentLoad(const HullGeometry& geometry) : geometry_(geometry) {
  RequirePositive("hull.length", geometry.length, "m");
  RequirePositive("hull.beam", geometry.beam, "m");
  RequirePositive("hull.draught", geometry.draught, "m");
  RequireNonNegative("hull.wetted_surface", geometry.wetted_surface, "m^2",
                     "0 = Denny-Mumford estimate");
  RequireNonNegative("hull.cross_flow_drag_coefficient", geometry.cross_flow_drag_coefficient, "",
                     "0 = Hoerner's curve");
  if (!(geometry.form_factor > -1.0) || !std::isfinite(geometry.form_factor)) {
    ThrowBadValue("hull.form_factor", geometry.form_factor, "",
                  "must be > -1 and finite (k of the viscous resistance (1 + k) C_F)");
  }
  RequirePositive("hull.water_density", geometry.water_density, "kg/m^3");
  RequirePositive("hull.kinematic_viscosity", geometry.kinematic_viscosity, "m^2/s");

  wetted_surface_ = geometry.wetted_surface;
  if (wetted_surface_ == 0.0) {
    if (!(geometry.displaced_volume > 0.0) || !std::isfinite(geometry.displaced_volume)) {
      ThrowBadValue("hull.displaced_volume", geometry.displaced_volume, "m^3",
                    "must be > 0 and finite to estimate hull.wetted_surface (given as 0)");
    }
    wetted_surface_ =
        DennyMumfordWettedSurface(geometry.length, geometry.draught, geometry.displaced_volume);
  }
  cross_flow_drag_coefficient_ = geometry.cross_flow_drag_coefficient;
  if (cross_flow_drag_coefficient_ == 0.0) {
    cross_flow_drag_coefficient_ =
        HoernerCrossFlowDragCoefficient(geometry.beam / (2.0 * geometry.draught));
  }
  surge_factor_ = 0.5 * geometry.water_density * wetted_surface_ * (1.0 + geometry.form_factor);
  cross_flow_factor_ =
      0.5 * geometry.water_density * geometry.draught * cross_flow_drag_coefficient_;
  strip_width_ = geometry.length / kStrips;
  for (int i = 0; i < kStrips; ++i) {
    strip_x_[i] = -0.5 * geometry.length + (i + 0.5) * strip_width_;
  }
}

CurrentLoad::Relative CurrentLoad::RelativeVelocity(const Vec6& eta, const Vec6& nu,
                                                    const Vec3& current_ned) const {
  const double c = std::cos(eta[5]);
  const double s = std::sin(eta[5]);
  Relative rel;
  rel.u_c = c * current_ned[0] + s * current_ned[1];
  rel.v_c = -s * current_ned[0] + c * current_ned[1];
  rel.u_r = nu[0] - rel.u_c;
  rel.v_r = nu[1] - rel.v_c;
  rel.r = nu[5];
  return rel;
}

Vec6 CurrentLoad::Load(const Vec6& eta, const Vec6& nu, const Vec3& current_velocity_ned) const {
  const Relative rel = RelativeVelocity(eta, nu, current_velocity_ned);
  const double reynolds = std::abs(rel.u_r) * geometry_.length / geometry_.kinematic_viscosity;
  const Friction friction = IttcFriction(reynolds);

  double sway = 0.0;
  double yaw = 0.0;
  for (int i = 0; i < kStrips; ++i) {
    const double w = rel.v_r + strip_x_[i] * rel.r;  // local cross-flow velocity
    const double drag = std::abs(w) * w;
    sway += drag;
    yaw += strip_x_[i] * drag;
  }
  Vec6 tau = Vec6::Zero();
  tau[0] = -surge_factor_ * friction.coefficient * std::abs(rel.u_r) * rel.u_r;
  tau[1] = -cross_flow_factor_ * strip_width_ * sway;
  tau[5] = -cross_flow_factor_ * strip_width_ * yaw;
  return tau;
}

void CurrentLoad::Jacobian(const Vec6& eta, const Vec6& nu, const Vec3& current_velocity_ned,
                           Mat6* J_load_eta, Mat6* J_load_nu) const {
  const Relative rel = RelativeVelocity(eta, nu, current_velocity_ned);
  const double reynolds = std::abs(rel.u_r) * geometry_.length / geometry_.kinematic_viscosity;
  const Friction friction = IttcFriction(reynolds);

  // X = -f C_F(Re) |u_r| u_r with d(ln Re)/d(u_r) = 1 / u_r:
  // dX/du_r = -f |u_r| (2 C_F + dC_F/d(ln Re)).
  const double J_surge_ur =
      -surge_factor_ * std::abs(rel.u_r) * (2.0 * friction.coefficient + friction.log_slope);
  // d(|w| w)/dw = 2 |w| for each strip, w = v_r + x r.
  double sum_w = 0.0;
  double sum_xw = 0.0;
  double sum_xxw = 0.0;
  for (int i = 0; i < kStrips; ++i) {
    const double x = strip_x_[i];
    const double abs_w = std::abs(rel.v_r + x * rel.r);
    sum_w += abs_w;
    sum_xw += x * abs_w;
    sum_xxw += x * x * abs_w;
  }
  const double scale = -2.0 * cross_flow_factor_ * strip_width_;
  const double J_sway_vr = scale * sum_w;
  const double J_sway_r = scale * sum_xw;
  const double J_yaw_vr = scale * sum_xw;
  const double J_yaw_r = scale * sum_xxw;

  if (J_load_nu != nullptr) {
    J_load_nu->setZero();
    (*J_load_nu)(0, 0) = J_surge_ur;
    (*J_load_nu)(1, 1) = J_sway_vr;
    (*J_load_nu)(1, 5) = J_sway_r;
    (*J_load_nu)(5, 1) = J_yaw_vr;
    (*J_load_nu)(5, 5) = J_yaw_r;
  }
  if (J_load_eta != nullptr) {
    // u_c = cos(psi) V_n + sin(psi) V_e, v_c = -sin(psi) V_n + cos(psi) V_e, so
    // du_c/dpsi = v_c and dv_c/dpsi = -u_c; u_r and v_r move the opposite way.
    J_load_eta->setZero();
    (*J_load_eta)(0, 5) = -J_surge_ur * rel.v_c;
    (*J_load_eta)(1, 5) = J_sway_vr * rel.u_c;
    (*J_load_eta)(5, 5) = J_yaw_vr * rel.u_c;
  }
}

// ---------------------------------------------------------------------------------------
// Wind

WindCoefficientTable LoadedTankerWindCoefficients(double frontal_area, double lateral_area,
                                                  double centroid_forward_over_length,
                                                  int samples) {
  RequirePositive("wind.frontal_area", frontal_area, "m^2");
  RequirePositive("wind.lateral_area", lateral_area, "m^2");
  if (!std::isfinite(centroid_forward_over_length)) {
    ThrowBadValue("wind centroid_forward_over_length", centroid_forward_over_length, "",
                  "must be finite");
  }
  if (samples < 2) {
    ThrowBadValue("wind coefficient samples", samples, "", "must be >= 2");
  }
  WindCoefficientTable table;
  table.angle.resize(samples);
  table.surge.resize(samples);
  table.sway.resize(samples);
  table.yaw.resize(samples);
  for (int i = 0; i < samples; ++i) {
    // The last angle is exactly pi, and sin(0) = 0 exactly; sin(pi) in floating point is
    // 1.2e-16, so the ends of C_Y and C_N are set to their exact zeros.
    const double gamma = i == samples - 1 ? kPi : kPi * i / (samples - 1);
    const double longitudinal =
        gamma <= 0.5 * kPi ? kTankerLongitudinalBow : kTankerLongitudinalStern;
    const double longitudinal_on_lateral = longitudinal * frontal_area / lateral_area;
    const double sin_2gamma = std::sin(2.0 * gamma);
    const double denominator = 1.0 - 0.5 * kTankerCrossForce *
                                         (1.0 - longitudinal_on_lateral / kTankerLateralDrag) *
                                         sin_2gamma * sin_2gamma;
    const bool end = i == 0 || i == samples - 1;
    table.angle[i] = gamma;
    table.surge[i] = -longitudinal * std::cos(gamma) / denominator;
    table.sway[i] = end ? 0.0 : -kTankerLateralDrag * std::sin(gamma) / denominator;
    table.yaw[i] =
        (centroid_forward_over_length - kCentreOfEffortSlope * (gamma - 0.5 * kPi)) * table.sway[i];
  }
  return table;
}

WindParameters SeedFpsoWind() {
  WindParameters wind;
  wind.air_density = 1.226;
  wind.frontal_area = 1200.0;
  wind.lateral_area = 4500.0;
  wind.length = 200.0;
  wind.coefficients = LoadedTankerWindCoefficients(wind.frontal_area, wind.lateral_area, 0.0);
  return wind;
}

WindLoad::WindLoad(const WindParameters& parameters) : parameters_(parameters) {
  RequirePositive("wind.air_density", parameters.air_density, "kg/m^3");
  RequirePositive("wind.frontal_area", parameters.frontal_area, "m^2");
  RequirePositive("wind.lateral_area", parameters.lateral_area, "m^2");
  RequirePositive("wind.length", parameters.length, "m");
  ValidateTable(parameters.coefficients);
}

Vec3 WindLoad::Coefficients(double gamma) const {
  const double wrapped = WrapAngle(gamma);
  const double side = wrapped < 0.0 ? -1.0 : 1.0;  // -1: wind from port
  const double magnitude = std::abs(wrapped);
  const WindCoefficientTable& table = parameters_.coefficients;
  return Vec3(Interpolate(table.angle, table.surge, magnitude),
              side * Interpolate(table.angle, table.sway, magnitude),
              side * Interpolate(table.angle, table.yaw, magnitude));
}

Vec6 WindLoad::Load(const Vec6& eta, const Vec6& nu, double wind_speed,
                    double direction_from) const {
  // The air moves toward direction_from + pi.
  const double wind_north = -wind_speed * std::cos(direction_from);
  const double wind_east = -wind_speed * std::sin(direction_from);
  const double c = std::cos(eta[5]);
  const double s = std::sin(eta[5]);
  const double air_u = c * wind_north + s * wind_east - nu[0];
  const double air_v = -s * wind_north + c * wind_east - nu[1];
  // The relative wind comes from the direction opposite to the air's relative velocity.
  const double gamma = std::atan2(-air_v, -air_u);
  const Vec3 coefficient = Coefficients(gamma);
  const double dynamic_pressure = 0.5 * parameters_.air_density * (air_u * air_u + air_v * air_v);
  Vec6 tau = Vec6::Zero();
  tau[0] = dynamic_pressure * coefficient[0] * parameters_.frontal_area;
  tau[1] = dynamic_pressure * coefficient[1] * parameters_.lateral_area;
  tau[5] = dynamic_pressure * coefficient[2] * parameters_.lateral_area * parameters_.length;
  return tau;
}

// ---------------------------------------------------------------------------------------
// Gusts

NpdWindSpectrum::NpdWindSpectrum(double mean_speed, double height)
    : mean_speed_(mean_speed), height_(height) {
  RequirePositive("wind.gust.mean_speed", mean_speed, "m/s");
  RequirePositive("wind.gust.height", height, "m");
}

double NpdWindSpectrum::Density(double frequency) const {
  if (!(frequency > 0.0)) return 0.0;
  const double speed_ratio = mean_speed_ / 10.0;
  const double height_ratio = height_ / 10.0;
  const double x =
      172.0 * frequency * std::pow(height_ratio, 2.0 / 3.0) * std::pow(speed_ratio, -0.75);
  const double n = kNpdShapeExponent;
  return 320.0 * speed_ratio * speed_ratio * std::pow(height_ratio, 0.45) /
         std::pow(1.0 + std::pow(x, n), 5.0 / (3.0 * n));
}

double NpdWindSpectrum::MeanSpeedAtHeight() const {
  const double c = 0.0573 * std::sqrt(1.0 + 0.148 * mean_speed_);
  return mean_speed_ * (1.0 + c * std::log(height_ / 10.0));
}

WindGust::WindGust(const WindGustOptions& options, RandomStream& stream)
    : spectrum_(options.mean_speed, options.height) {
  if (options.components < 1) {
    ThrowBadValue("wind.gust.components", options.components, "", "must be >= 1");
  }
  RequirePositive("wind.gust.frequency_min", options.frequency_min, "Hz");
  if (!(options.frequency_max > options.frequency_min) || !std::isfinite(options.frequency_max)) {
    ThrowBadValue("wind.gust.frequency_max", options.frequency_max, "Hz",
                  "must be finite and > wind.gust.frequency_min = " +
                      FormatNumber(options.frequency_min) + " Hz");
  }
  mean_speed_ = spectrum_.MeanSpeedAtHeight();
  frequency_min_ = options.frequency_min;
  frequency_max_ = options.frequency_max;

  const int n = options.components;
  const double log_min = std::log(frequency_min_);
  const double log_bin = (std::log(frequency_max_) - log_min) / n;
  components_.resize(n);
  angular_frequency_.resize(n);
  amplitude_.resize(n);
  phase_.resize(n);
  for (int k = 0; k < n; ++k) {
    // Two draws per component, in this order (see the class comment).
    const double frequency_draw = stream.Uniform();
    const double phase_draw = stream.Uniform();
    GustComponent& c = components_[k];
    c.frequency = std::exp(log_min + (k + frequency_draw) * log_bin);
    c.amplitude = std::sqrt(2.0 * spectrum_.Density(c.frequency) * c.frequency * log_bin);
    c.phase = kTwoPi * phase_draw;
    angular_frequency_[k] = kTwoPi * c.frequency;
    amplitude_[k] = c.amplitude;
    phase_[k] = c.phase;
  }
}

double WindGust::Speed(double t) const {
  double speed = mean_speed_;
  for (Eigen::Index k = 0; k < amplitude_.size(); ++k) {
    speed += amplitude_[k] * std::cos(angular_frequency_[k] * t + phase_[k]);
  }
  return speed;
}

double WindGust::RealisedVariance() const { return 0.5 * amplitude_.square().sum(); }

}  // namespace moorsim::vessel
