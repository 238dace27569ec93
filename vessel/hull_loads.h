// Environmental loads on the hull that depend on the vessel's own motion: viscous current
// drag on the submerged hull, wind drag on the hull and superstructure above water, and
// the NPD (Froya) wind gust spectrum with a random-phase realisation of the wind speed.
//
// Conventions (docs/design.md section 2): SI units, angles in radians. Earth frame NED (x north,
// y east, z down); body frame x forward, y starboard, z down, origin midship on the
// waterline and the centreline. eta = [x y z phi theta psi], nu = [u v w p q r] (Fossen
// 2011, "Handbook of Marine Craft Hydrodynamics and Motion Control", ch. 2). Loads are
// returned as body-frame generalised forces tau = [X Y Z K M N] [N, N m]; the current and
// wind models act in the horizontal plane only (Z = K = M = 0).
//
// Both current and wind are resolved into body axes by the heading alone, R_z(psi)^T
// (Fossen 2011 ch. 8): roll and pitch of an FPSO are a few degrees, and the load
// coefficients are themselves defined for the upright vessel.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/random.h"
#include "core/types.h"
#include "vessel/rigid_body.h"

namespace moorsim::vessel {

// ---------------------------------------------------------------------------------------
// Current

/// Main particulars and flow constants of the hull for the current load.
struct HullGeometry {
  double length = 0.0;            ///< L [m], length between perpendiculars, > 0
  double beam = 0.0;              ///< B [m], > 0
  double draught = 0.0;           ///< T [m], > 0
  double displaced_volume = 0.0;  ///< nabla [m^3]; needed only to estimate wetted_surface
  /// S [m^2]; 0 = estimate by Denny-Mumford from L, T and nabla (see
  /// DennyMumfordWettedSurface).
  double wetted_surface = 0.0;
  /// Two-dimensional cross-flow drag coefficient C_d2D [-] of a hull section; 0 = read
  /// from Hoerner's curve at B / (2 T) (see HoernerCrossFlowDragCoefficient).
  double cross_flow_drag_coefficient = 0.0;
  /// Form factor k [-] of the viscous resistance (1 + k) C_F (ITTC-78), > -1.
  double form_factor = 0.0;
  double water_density = 1025.0;  ///< rho [kg/m^3], > 0
  /// nu [m^2/s], > 0. Default: sea water at 15 deg C, salinity 35 g/kg (ITTC 7.5-02-01-03,
  /// "Fresh Water and Seawater Properties", 2011: 1.1883e-6).
  double kinematic_viscosity = 1.19e-6;
};

/// The seed FPSO (docs/design.md section 9: Lpp 200 m, B 44 m, T 12 m, nabla 97 961 m^3, so
/// C_B = 0.928): wetted surface and C_d2D left to their estimates (12 243 m^2 and 0.661),
/// k = 0.505 from WatanabeFormFactor. A scenario's `vessel.hull` defaults to these values
/// (scenarios/README.md).
HullGeometry SeedFpsoHull();

/// Watanabe's form-factor regression k = -0.095 + 25.6 C_B / ((L/B)^2 sqrt(B/T)) [-], with
/// C_B = nabla / (L B T) (as quoted by Molland, Turnock & Hudson, "Ship Resistance and
/// Propulsion", 2011, ch. 4): 0.505 for the seed FPSO. Throws moorsim::InputError if an
/// argument is not positive and finite.
double WatanabeFormFactor(double length, double beam, double draught, double displaced_volume);

/// Denny-Mumford wetted-surface estimate S = 1.7 L T + nabla / T [m^2] for a full
/// displacement hull (SNAME, "Principles of Naval Architecture" vol. II, 1988, ch. V).
/// Throws moorsim::InputError if an argument is not positive and finite.
double DennyMumfordWettedSurface(double length, double draught, double displaced_volume);

/// Hoerner's two-dimensional cross-flow drag coefficient of a ship-like section against
/// its half-beam to draught ratio B / (2 T) (Hoerner, "Fluid-Dynamic Drag", 1965, as
/// digitised by Leite, Aranha, Umeda & de Conti, Applied Ocean Research 20, 1998, and used
/// for cross-flow drag in Fossen 2011 ch. 6): about 2 for a deep thin plate, falling to about 0.56
/// for a flat, wide section. Linear interpolation between the digitised points, held at
/// the end values outside their range [0.011, 4.0]. The seed FPSO's B / (2 T) = 1.83 gives
/// 0.661. Throws moorsim::InputError if the ratio is not positive and finite.
double HoernerCrossFlowDragCoefficient(double half_beam_over_draught);

/// ITTC-57 model-ship correlation line C_F = 0.075 / (log10 Re - 2)^2 [-] (ITTC 1957;
/// Fossen 2011 ch. 6, surge resistance). Below Re = 1e5 the line is held at its value there: the
/// formula is a turbulent-flow fit and has a pole at Re = 100 (the hold only matters for
/// relative speeds below 1e-9 m/s on the seed hull).
double IttcFrictionCoefficient(double reynolds_number);

/// Viscous current load on the hull from the hull's velocity relative to the water
/// (Fossen 2011 ch. 6, surge resistance and cross-flow drag; ch. 8, current):
///
///   nu_r = nu - [u_c v_c 0 0 0 0],  [u_c v_c] = R_z(psi)^T [V_north V_east]
///   X = -1/2 rho S (1 + k) C_F(Re) |u_r| u_r,   Re = |u_r| L / nu_kin
///   Y = -1/2 rho T C_d2D  integral_{-L/2}^{L/2} |v_r + x r| (v_r + x r) dx
///   N = -1/2 rho T C_d2D  integral_{-L/2}^{L/2} x |v_r + x r| (v_r + x r) dx
///
/// Surge is the frictional resistance with a form factor; sway and yaw are cross-flow drag
/// by strip theory, integrated by the midpoint rule on kStrips equal strips (the rule is
/// exact for r = 0 and 0.5 % low for pure yaw, whose integrand is x^3). The current is
/// irrotational, so r_r = r. These loads are quadratic in the *relative* velocity and
/// replace any quadratic damping in absolute velocity of the vessel model (set
/// VesselParameters::quadratic_damping to zero when using them). The mooring lines carry
/// their own current drag.
///
/// Not included: the residual (pressure) drag of the blunt bow and stern in surge, the
/// Munk moment and lift at small drift angles, and shallow-water amplification. OCIMF-
/// style head-current coefficients of loaded tankers in deep water are of order 0.02 to
/// 0.04 on 1/2 rho V^2 L T, i.e. 25 to 50 kN at 1 m/s on the seed hull; this friction
/// model gives 18.3 kN, below that range, so surge current drag is on the low side.
///
/// Load and Jacobian allocate nothing and throw nothing; a non-finite state gives a
/// non-finite load, for the integrator's RHS adapter to report.
class CurrentLoad {
 public:
  static constexpr int kStrips = 20;

  /// Throws moorsim::InputError naming the field and value if a particular is not
  /// positive and finite (displaced_volume only when wetted_surface is 0), a coefficient
  /// is negative, or k <= -1.
  explicit CurrentLoad(const HullGeometry& geometry);

  /// tau_current [N, N m] in body axes. current_velocity_ned: water velocity at the
  /// surface in NED [m/s]; its vertical component is ignored.
  Vec6 Load(const Vec6& eta, const Vec6& nu, const Vec3& current_velocity_ned) const;

  /// Analytic Jacobians d tau / d eta (nonzero only in the psi column, through
  /// R_z(psi)^T v_c) and d tau / d nu (columns u, v, r). Either pointer may be null to
  /// skip that block.
  void Jacobian(const Vec6& eta, const Vec6& nu, const Vec3& current_velocity_ned, Mat6* J_load_eta,
                Mat6* J_load_nu) const;

  const HullGeometry& geometry() const { return geometry_; }
  /// S [m^2] in use (given or estimated).
  double wetted_surface() const { return wetted_surface_; }
  /// C_d2D [-] in use (given or from Hoerner's curve).
  double cross_flow_drag_coefficient() const { return cross_flow_drag_coefficient_; }

 private:
  struct Relative {
    double u_c, v_c;  // current in body axes [m/s]
    double u_r, v_r;  // hull velocity relative to the water, body axes [m/s]
    double r;         // yaw rate [rad/s]
  };
  Relative RelativeVelocity(const Vec6& eta, const Vec6& nu, const Vec3& current_ned) const;

  HullGeometry geometry_;
  double wetted_surface_ = 0.0;
  double cross_flow_drag_coefficient_ = 0.0;
  double surge_factor_ = 0.0;              // 1/2 rho S (1 + k) [kg/m]
  double cross_flow_factor_ = 0.0;         // 1/2 rho T C_d2D [kg/m^2]
  double strip_width_ = 0.0;               // L / kStrips [m]
  std::array<double, kStrips> strip_x_{};  // strip midpoints [m], forward of midship
};

// ---------------------------------------------------------------------------------------
// Wind

/// Wind load coefficients against the relative wind angle gamma in [0, pi]: the direction
/// the relative wind comes FROM, measured from the bow toward starboard (0 = head wind,
/// pi/2 = from starboard, pi = from astern). Body-axis signs: C_X > 0 pushes forward,
/// C_Y > 0 to starboard, C_N > 0 turns the bow to starboard. So a head wind has C_X < 0
/// and a wind from starboard C_Y < 0. Winds from port (gamma in (-pi, 0)) use the mirror
/// image of a port-starboard symmetric vessel: C_X(-gamma) = C_X(gamma),
/// C_Y(-gamma) = -C_Y(gamma), C_N(-gamma) = -C_N(gamma). Linear interpolation between
/// rows.
struct WindCoefficientTable {
  std::vector<double> angle;  ///< gamma [rad], strictly increasing from 0 to pi
  std::vector<double> surge;  ///< C_X [-], on the frontal area A_F
  std::vector<double> sway;   ///< C_Y [-], on the lateral area A_L; 0 at 0 and pi
  std::vector<double> yaw;    ///< C_N [-], on A_L L; 0 at 0 and pi
};

/// Blendermann's (1994) parametric wind coefficients with his "tanker, loaded" parameters
/// (W. Blendermann, "Parameter identification of wind loads on ships", J. Wind Eng. Ind.
/// Aerodyn. 51, 1994, 339-351; tabulated in Fossen 2021, 2nd ed., section 10.1.2): C_Dt = 0.70,
/// C_DlAF = 0.90 (wind from ahead) and 0.55 (from astern), cross-force parameter
/// delta = 0.40. With C_Dl = C_DlAF A_F / A_L and
/// d(gamma) = 1 - delta/2 (1 - C_Dl / C_Dt) sin^2(2 gamma):
///
///   C_X = -C_DlAF cos(gamma) / d,   C_Y = -C_Dt sin(gamma) / d,
///   C_N = (s_L / L - 0.18 (gamma - pi/2)) C_Y
///
/// (C_Y and C_N carry a minus sign relative to Blendermann because gamma here is positive
/// for wind from starboard.) The centre of effort moves linearly from 0.28 L forward of
/// the lateral-area centroid in a head wind to 0.28 L aft of it in a stern wind. With
/// delta = 0 this is Fossen's simplified model C_X = -c_x cos gamma, C_Y = -c_y sin gamma.
/// Why this model: it is published for the vessel type (a loaded tanker), needs only the
/// areas and the centroid, and is smooth; Isherwood's (1972) regression also needs the
/// lateral outline's perimeter, superstructure area and mast count, unknown for the seed.
/// Sampled at `samples` equally spaced angles (>= 2) over [0, pi].
/// centroid_forward_over_length: s_L / L, the lateral-area centroid forward of midship
/// over the length. Throws moorsim::InputError for non-positive areas or samples < 2.
WindCoefficientTable LoadedTankerWindCoefficients(double frontal_area, double lateral_area,
                                                  double centroid_forward_over_length = 0.0,
                                                  int samples = 37);

struct WindParameters {
  double air_density = 1.226;  ///< rho_a [kg/m^3], > 0 (ISA sea level, 15 deg C)
  double frontal_area = 0.0;   ///< A_F [m^2], projected above water, seen from ahead, > 0
  double lateral_area = 0.0;   ///< A_L [m^2], projected above water, seen from the side, > 0
  double length = 0.0;         ///< L [m], reference length of the yaw moment, > 0
  WindCoefficientTable coefficients;
};

/// The seed FPSO above water (the project's choice; the papers give no topsides): A_F =
/// 1200 m^2 (44 m beam x ~9 m freeboard of hull, plus ~800 m^2 of accommodation, flare
/// and process modules seen end-on), A_L = 4500 m^2 (200 m x 9 m of hull plus topsides
/// ~15 m high over ~180 m, counted ~90 % solid), L = 200 m, rho_a = 1.226 kg/m^3, and
/// LoadedTankerWindCoefficients with the centroid at midship (37 rows, 5 deg apart). A
/// scenario's `vessel.windage` defaults to these values (scenarios/README.md).
WindParameters SeedFpsoWind();

/// Wind load on the hull and superstructure from the relative wind (Fossen 2011 ch. 8,
/// wind forces; Blendermann 1994):
///
///   v_w = -U [cos beta, sin beta] (NED, beta = direction the wind comes FROM, compass)
///   [a_u a_v] = R_z(psi)^T v_w - [u v]       (air velocity relative to the hull)
///   V_rw^2 = a_u^2 + a_v^2,   gamma = atan2(-a_v, -a_u)
///   X = 1/2 rho_a V_rw^2 C_X(gamma) A_F
///   Y = 1/2 rho_a V_rw^2 C_Y(gamma) A_L
///   N = 1/2 rho_a V_rw^2 C_N(gamma) A_L L
///
/// The yaw rate's contribution to the relative wind is neglected (the superstructure's
/// lever arm times r is far below the wind speed). Load allocates nothing and throws
/// nothing.
class WindLoad {
 public:
  /// Throws moorsim::InputError naming the field and value for a non-positive density,
  /// area or length, or an invalid table (sizes differ, fewer than 2 rows, angles not
  /// strictly increasing from 0 to pi within 1e-6 rad, a non-finite value, C_Y or C_N not
  /// 0 at 0 and pi; the mirror image would make them jump as the wind crosses the bow).
  explicit WindLoad(const WindParameters& parameters);

  /// tau_wind [N, N m] in body axes for the wind speed U at 10 m [m/s] (>= 0; a negative
  /// speed is the same wind from the opposite direction) coming from `direction_from`
  /// [rad, compass: 0 = from north, pi/2 = from east].
  Vec6 Load(const Vec6& eta, const Vec6& nu, double wind_speed, double direction_from) const;

  /// The coefficients [C_X C_Y C_N] at a relative wind angle gamma [rad] (any real value,
  /// wrapped to (-pi, pi] and mirrored as described at WindCoefficientTable).
  Vec3 Coefficients(double gamma) const;

  const WindParameters& parameters() const { return parameters_; }

 private:
  WindParameters parameters_;
};

// ---------------------------------------------------------------------------------------
// Gusts

/// The NPD (Froya) wind spectrum of ISO 19901-1 and API RP 2A-WSD (also DNV-RP-C205,
/// 2010, section 2.3), for the 1-hour mean wind speed U0 at 10 m:
///
///   S(f) = 320 (U0/10)^2 (z/10)^0.45 / (1 + x^n)^(5 / (3 n))   [m^2/s^2 per Hz]
///   x = 172 f (z/10)^(2/3) (U0/10)^(-0.75),   n = 0.468
///
/// with the NPD mean profile U(z) = U0 (1 + C ln(z/10)), C = 0.0573 sqrt(1 + 0.148 U0)
/// (U0 in m/s). Fitted to wind over the North Sea at 10 m <= z <= 100 m (not enforced).
/// The spectrum's variance over 1/3600..0.5 Hz is (0.121 U0)^2 at U0 = 20 m/s, close to
/// the standard's turbulence intensity 0.06 (1 + 0.043 U0) = 0.112.
class NpdWindSpectrum {
 public:
  /// Throws moorsim::InputError if U0 or z is not positive and finite.
  explicit NpdWindSpectrum(double mean_speed, double height = 10.0);
  /// S(f) [m^2/s^2 per Hz] at frequency f [Hz]; 0 for f <= 0.
  double Density(double frequency) const;
  /// U0 [m/s], the 1-hour mean at 10 m.
  double mean_speed() const { return mean_speed_; }
  double height() const { return height_; }
  /// U(z) [m/s], the 1-hour mean at the spectrum's height.
  double MeanSpeedAtHeight() const;

 private:
  double mean_speed_ = 0.0;
  double height_ = 10.0;
};

struct WindGustOptions {
  /// U0 [m/s], 1-hour mean wind speed at 10 m, > 0. No default: an unset wind is an
  /// input error, not a calm.
  double mean_speed = 0.0;
  double height = 10.0;  ///< z [m] at which the speed is realised, > 0
  /// N, number of components, >= 1. With log-spaced bins and the realised variance a
  /// stratified estimate of the spectrum's, the realised variance of 2000 realisations at
  /// N = 100 strays at most 0.24 % (standard deviation 0.06 %) from the integral.
  int components = 100;
  /// Frequency range [Hz]. Below 1/3600 Hz the variation belongs to the 1-hour mean
  /// itself. Above 0.5 Hz the eddies are shorter than U0 / f = 40 m at U0 = 20 m/s, small
  /// against the 200 m hull, so they are not coherent over the exposed area and largely
  /// average out (and the vessel's low-frequency motion does not respond to them). The
  /// NPD spectrum's variance outside the range is 17 % of its total at U0 = 20 m/s: 3 %
  /// below 1/3600 Hz and 14 % above 0.5 Hz (the f^-5/3 tail).
  double frequency_min = 1.0 / 3600.0;
  double frequency_max = 0.5;
};

/// One component of a gust realisation: a cos(2 pi f t + phi).
struct GustComponent {
  double frequency = 0.0;  ///< f [Hz]
  double amplitude = 0.0;  ///< a [m/s]
  double phase = 0.0;      ///< phi [rad], in [0, 2 pi)
};

/// A random-phase realisation of the NPD spectrum (the same single-summation model as
/// WaveRealisation; Faltinsen 1990 ch. 2 for waves, DNV-RP-C205 section 2.3 for wind):
///
///   U(t) = U(z) + sum_k a_k cos(2 pi f_k t + phi_k),  a_k = sqrt(2 S(f_k) f_k d_lnf)
///
/// over N bins equally spaced in ln f (the spectrum spans 3.3 decades; equal linear bins
/// would put most of the energy into the first bin), with f_k uniform in ln f within its
/// bin and phi_k uniform on [0, 2 pi). Since f_k is uniform in ln f, S(f_k) f_k d_lnf is an
/// unbiased estimate of the bin's variance, and the random frequencies keep the record
/// from repeating. Each component takes exactly two uniforms from the stream, in this
/// order: frequency offset, phase. The caller derives the stream from the run seed and
/// the name "wind.gust".
class WindGust {
 public:
  /// Throws moorsim::InputError naming the field and value for U0 <= 0, z <= 0, N < 1, a
  /// non-positive or inverted frequency range, or a non-finite value.
  WindGust(const WindGustOptions& options, RandomStream& stream);

  /// Wind speed U(t) [m/s] at time t [s]. Allocation-free; N cosines. Not clipped at 0
  /// (the gust's standard deviation is ~12 % of U0, so U < 0 is an 8-sigma event).
  double Speed(double t) const;

  const std::vector<GustComponent>& components() const { return components_; }
  /// sum a_k^2 / 2 [m^2/s^2], the realisation's variance about the mean.
  double RealisedVariance() const;
  /// U(z) [m/s], the mean of Speed.
  double mean_speed() const { return mean_speed_; }
  const NpdWindSpectrum& spectrum() const { return spectrum_; }
  double frequency_min() const { return frequency_min_; }
  double frequency_max() const { return frequency_max_; }

 private:
  NpdWindSpectrum spectrum_;
  double mean_speed_ = 0.0;
  double frequency_min_ = 0.0;
  double frequency_max_ = 0.0;
  std::vector<GustComponent> components_;
  // Structure-of-arrays copies for the sum: 2 pi f_k, a_k, phi_k.
  Eigen::ArrayXd angular_frequency_;
  Eigen::ArrayXd amplitude_;
  Eigen::ArrayXd phase_;
};

}  // namespace moorsim::vessel
