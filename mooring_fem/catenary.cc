// Elastic catenary with a frictionless horizontal seabed.
//
// Equations: H. M. Irvine, "Cable Structures" (MIT Press, 1981), sec. 2.2 (elastic
// catenary, eqs. 2.21-2.22 for a free span) and its touchdown variant as used in
// J. Jonkman's FAST v7 catenary routine (inherited by MoorDyn, MoorPy and MAP++). With
// H the horizontal and V the vertical tension at the fairlead, L, w, EA the unstretched
// length, submerged weight per unstretched length and axial stiffness:
//
//   touchdown (grounded unstretched length Lb = L - V/w >= 0):
//     span   = Lb + (H/w) asinh(V/H) + H L / EA
//     height = (H/w) (sqrt(1 + (V/H)^2) - 1) + V^2 / (2 EA w)
//   fully suspended (anchor vertical force Va = V - w L > 0):
//     span   = (H/w) [asinh(V/H) - asinh(Va/H)] + H L / EA
//     height = (H/w) [sqrt(1 + (V/H)^2) - sqrt(1 + (Va/H)^2)] + (V L - w L^2/2) / EA
//
// Both are one formula: a free-hanging piece of unstretched length Ls = (V - Va)/w whose
// lower end carries Va (0 at touchdown), preceded by Lb grounded metres under tension H.
// The map (H, V) -> (span, height) is C1 across Va = 0 and its Jacobian is the symmetric
// positive-definite flexibility matrix of the line, so a damped Newton iteration on the
// unified form crosses the regime boundary smoothly.
//
// The free-span terms are evaluated in cancellation-free form, using
//   sqrt(H^2+V^2) - sqrt(H^2+Va^2) = (V - Va)(V + Va) / (T + Ta),
//   asinh(a) - asinh(b) = asinh((a^2 - b^2) / (a sqrt(1+b^2) + b sqrt(1+a^2))),
// so nearly vertical (H -> 0) and nearly horizontal (V << H) lines keep full precision
// and H = 0 needs no special case.
#include "mooring_fem/catenary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/error.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kMaxStrain = kMaxCatenaryStrain;
/// Convergence: residuals of span and height below this fraction of the problem size.
constexpr double kRelativeTolerance = 1e-12;
constexpr int kMaxNewtonIterations = 100;

std::string Describe(const CatenaryLineProperties& line, double span, double height) {
  std::ostringstream out;
  out.precision(10);
  out << "catenary (L = " << line.length << " m, w = " << line.weight_per_length
      << " N/m, EA = " << line.axial_stiffness << " N, span = " << span << " m, height = " << height
      << " m)";
  return out.str();
}

void CheckLine(const CatenaryLineProperties& line) {
  const bool ok = std::isfinite(line.length) && line.length > 0.0 &&
                  std::isfinite(line.weight_per_length) && line.weight_per_length > 0.0 &&
                  std::isfinite(line.axial_stiffness) && line.axial_stiffness > 0.0;
  if (!ok) {
    std::ostringstream out;
    out << "catenary: line properties must be finite and positive (L = " << line.length
        << " m, w = " << line.weight_per_length << " N/m, EA = " << line.axial_stiffness << " N)";
    throw Error(out.str());
  }
}

/// Offset (dx, dz) across a free-hanging piece of unstretched length `sigma` whose lower
/// end carries vertical force `va` >= 0, with horizontal tension `h` >= 0 (Irvine 1981,
/// eqs. 2.21-2.22 written from the lower end, in cancellation-free form).
Eigen::Vector2d HangingOffset(double h, double va, double sigma, double w, double ea) {
  if (sigma <= 0.0) return Eigen::Vector2d::Zero();
  const double vs = va + w * sigma;  // vertical force at the upper end
  const double ta = std::hypot(h, va);
  const double ts = std::hypot(h, vs);
  // (T_s - T_a)/w = sigma (V_s + V_a)/(T_s + T_a); elastic part (Va sigma + w sigma^2/2)/EA.
  const double dz = sigma * (vs + va) / (ts + ta) + sigma * (va + 0.5 * w * sigma) / ea;
  double dx = h * sigma / ea;
  if (h > 0.0) {
    // (h/w) [asinh(vs/h) - asinh(va/h)]; the argument is finite unless h underflows, and
    // then h * asinh(.) -> 0 (a vertical piece).
    const double arg = w * sigma * (vs + va) / (vs * ta + va * ts);
    if (std::isfinite(arg)) dx += (h / w) * std::asinh(arg);
  }
  return {dx, dz};
}

/// Fairlead position and flexibility for trial fairlead tensions (h > 0, v > 0).
struct EndpointState {
  Eigen::Vector2d position;  // (span, height) the trial tensions produce [m]
  Eigen::Matrix2d jacobian;  // d(span, height)/d(H, V) [m/N], symmetric positive definite
};

EndpointState EvaluateEndpoint(const CatenaryLineProperties& line, double h, double v) {
  const double len = line.length;
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  const bool lifted = v > w * len;
  const double va = lifted ? v - w * len : 0.0;  // vertical force at the lower end of the free span
  const double suspended = lifted ? len : v / w;  // unstretched free-hanging length
  const double grounded = len - suspended;

  EndpointState state;
  const Eigen::Vector2d offset = HangingOffset(h, va, suspended, w, ea);
  state.position.x() = grounded * (1.0 + h / ea) + offset.x();
  state.position.y() = offset.y();

  // Derivatives of the formulas in the file comment, in the same cancellation-free form:
  //   V/T - Va/Ta = H^2 (V^2 - Va^2) / ((V Ta + Va T) T Ta),
  //   H/T - H/Ta  = -H (V^2 - Va^2) / ((T + Ta) T Ta).
  const double t = std::hypot(h, v);
  const double ta = std::hypot(h, va);
  const double v2_minus_va2 = w * suspended * (v + va);
  const double sine_difference = h * h * v2_minus_va2 / ((v * ta + va * t) * t * ta);
  const double cosine_difference = -h * v2_minus_va2 / ((t + ta) * t * ta);
  const double asinh_difference = std::asinh(w * suspended * (v + va) / (v * ta + va * t));
  state.jacobian(0, 0) = (asinh_difference - sine_difference) / w + len / ea;
  state.jacobian(0, 1) = cosine_difference / w;
  state.jacobian(1, 0) = cosine_difference / w;
  state.jacobian(1, 1) = sine_difference / w + suspended / ea;
  return state;
}

/// Unstretched length of a vertical hanging line whose top is `height` above its lowest
/// point (where the vertical force vanishes): height = Ls + w Ls^2 / (2 EA).
double VerticalHangingLength(const CatenaryLineProperties& line, double height) {
  const double k = 2.0 * line.weight_per_length * height / line.axial_stiffness;
  return 2.0 * height / (std::sqrt(1.0 + k) + 1.0);
}

/// Fills the derived fields of a solution from (H, V).
CatenarySolution MakeSolution(const CatenaryLineProperties& line, double h, double v) {
  const double weight = line.weight_per_length * line.length;
  CatenarySolution solution;
  solution.horizontal_tension = h;
  solution.vertical_tension = v;
  solution.fairlead_tension = std::hypot(h, v);
  solution.anchor_horizontal = h;
  solution.anchor_lifted = v > weight;
  solution.anchor_vertical = solution.anchor_lifted ? v - weight : 0.0;
  solution.grounded_length =
      solution.anchor_lifted ? 0.0 : std::max(0.0, line.length - v / line.weight_per_length);
  return solution;
}

/// Initial guess from the inextensible touchdown catenary: with a = H/w, the suspended
/// length is sqrt(h^2 + 2 a h) and span = L - sqrt(h^2 + 2 a h) + a acosh(1 + h/a),
/// increasing in a up to the lift-off value a = (L^2 - h^2)/(2h); bisection in log a.
Eigen::Vector2d TouchdownGuess(const CatenaryLineProperties& line, double span, double height) {
  const double len = line.length;
  const double w = line.weight_per_length;
  if (len <= height) return {w * height, w * height};  // only an elastic line can reach
  const auto span_at = [&](double a) {
    return len - std::sqrt(height * height + 2.0 * a * height) + a * std::acosh(1.0 + height / a);
  };
  double hi = (len * len - height * height) / (2.0 * height);
  double lo = 1e-12 * hi;
  if (span >= span_at(hi)) {
    lo = hi;
  } else if (span <= span_at(lo)) {
    hi = lo;
  }
  for (int i = 0; i < 80 && hi > lo * (1.0 + 1e-6); ++i) {
    const double mid = std::sqrt(lo * hi);
    (span_at(mid) < span ? lo : hi) = mid;
  }
  const double a = std::sqrt(lo * hi);
  return {w * a, w * std::sqrt(height * height + 2.0 * a * height)};
}

/// Initial guess for a fully suspended line: the inextensible catenary through both ends,
/// sinh(lambda)/lambda = sqrt(L^2 - h^2)/span with lambda = span/(2a), and
/// V = (w/2)(L + h coth(lambda)) (Irvine 1981 sec. 1.3); a straight stretched line if the
/// chord is not shorter than L.
Eigen::Vector2d SuspendedGuess(const CatenaryLineProperties& line, double span, double height) {
  const double len = line.length;
  const double w = line.weight_per_length;
  const double chord = std::hypot(span, height);
  if (chord >= len * (1.0 - 1e-9)) {
    const double tension = line.axial_stiffness * std::max(chord / len - 1.0, 1e-6);
    return {tension * span / chord, tension * height / chord + 0.5 * w * len};
  }
  const double ratio = std::sqrt(len * len - height * height) / span;  // > 1
  double lo = 0.0;
  double hi = 1.0;
  while (std::sinh(hi) / hi < ratio && hi < 700.0) hi *= 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::sinh(mid) / mid < ratio ? lo : hi) = mid;
  }
  const double lambda = std::max(0.5 * (lo + hi), 1e-12);
  const double a = span / (2.0 * lambda);
  return {w * a, 0.5 * w * (len + height / std::tanh(lambda))};
}

/// The initial guess of Jonkman's FAST v7 catenary routine (also MoorDyn's), kept as a
/// second starting point.
Eigen::Vector2d JonkmanGuess(const CatenaryLineProperties& line, double span, double height) {
  const double len = line.length;
  const double w = line.weight_per_length;
  double lambda = 0.2;
  if (std::hypot(span, height) < len) {
    lambda = std::sqrt(3.0 * ((len * len - height * height) / (span * span) - 1.0));
  }
  lambda = std::max(lambda, 1e-6);
  return {std::max(0.5 * w * span / lambda, 1e-6 * w * len),
          0.5 * w * (height / std::tanh(lambda) + len)};
}

/// Robust but slow starting point: along the curve height(H, V) = height, V(H) is unique
/// (height rises with V) and span rises strictly with H (the flexibility matrix is
/// positive definite), so nested bisections bracket the solution to `relative` in H.
Eigen::Vector2d BisectionGuess(const CatenaryLineProperties& line, double span, double height,
                               double relative) {
  const double w = line.weight_per_length;
  const auto v_for = [&](double h) {
    double lo = 0.0;
    double hi = w * line.length + w * height;
    while (EvaluateEndpoint(line, h, hi).position.y() < height && hi < 1e300) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (EvaluateEndpoint(line, h, mid).position.y() < height ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  double lo = 1e-12 * w * line.length;
  double hi = w * line.length;
  while (EvaluateEndpoint(line, hi, v_for(hi)).position.x() < span && hi < 1e300) hi *= 2.0;
  for (int i = 0; i < 200 && hi > lo * (1.0 + relative); ++i) {
    const double mid = std::sqrt(lo * hi);
    (EvaluateEndpoint(line, mid, v_for(mid)).position.x() < span ? lo : hi) = mid;
  }
  const double h = std::sqrt(lo * hi);
  return {h, v_for(h)};
}

/// Damped Newton iteration on the unified endpoint equations from the guess in `tensions`
/// (H, V). Returns true and sets `tensions` on convergence; `residual_out` is the last
/// max-norm residual [m].
bool NewtonSolve(const CatenaryLineProperties& line, double span, double height,
                 Eigen::Vector2d& tensions, double& residual_out) {
  const Eigen::Vector2d target(span, height);
  const double tolerance = kRelativeTolerance * std::max({span, height, line.length});
  Eigen::Vector2d x = tensions;
  EndpointState state = EvaluateEndpoint(line, x(0), x(1));
  Eigen::Vector2d residual = state.position - target;
  bool polished = false;
  for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
    residual_out = residual.cwiseAbs().maxCoeff();
    if (!std::isfinite(residual_out)) return false;
    if (residual_out <= tolerance && polished) {
      tensions = x;
      return true;
    }
    const Eigen::Matrix2d& j = state.jacobian;
    const double det = j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0);
    if (!(det > 0.0) || !std::isfinite(det)) return false;
    const Eigen::Vector2d step(-(j(1, 1) * residual(0) - j(0, 1) * residual(1)) / det,
                               -(-j(1, 0) * residual(0) + j(0, 0) * residual(1)) / det);
    // Step limiting: H and V stay positive (at most a 90 % cut per iteration).
    double alpha = 1.0;
    for (int k = 0; k < 2; ++k) {
      if (step(k) < 0.0) alpha = std::min(alpha, 0.9 * x(k) / -step(k));
    }
    // Backtracking line search on the residual norm (the Newton step is a descent
    // direction for it). Once near the root, rounding may stall the decrease: accept a
    // full step whose residual grows by no more than a few convergence tolerances.
    const double norm = residual.norm();
    bool accepted = false;
    for (int k = 0; k < 60; ++k, alpha *= 0.5) {
      const Eigen::Vector2d trial = x + alpha * step;
      if (!(trial(0) > 0.0) || !(trial(1) > 0.0)) continue;
      EndpointState trial_state = EvaluateEndpoint(line, trial(0), trial(1));
      const Eigen::Vector2d trial_residual = trial_state.position - target;
      const double trial_norm = trial_residual.norm();
      if (trial_norm <= (1.0 - 1e-4 * alpha) * norm ||
          (alpha == 1.0 && trial_norm <= norm + 16.0 * tolerance)) {
        x = trial;
        state = trial_state;
        residual = trial_residual;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (residual_out > tolerance) return false;
      polished = true;  // rounding floor reached; keep the converged point
      continue;
    }
    // Converged already: this was the extra step that takes the residual from the
    // tolerance down to the rounding floor (quadratic convergence makes it nearly free).
    if (residual_out <= tolerance) polished = true;
  }
  residual_out = residual.cwiseAbs().maxCoeff();
  if (residual_out <= tolerance) {
    tensions = x;
    return true;
  }
  return false;
}

/// Position in the line's vertical plane; `slack_span` is where the hanging part stands
/// when H = 0 and part of the line is grounded (only the caller knows the span then).
Eigen::Vector2d PointInPlane(const CatenaryLineProperties& line, const CatenarySolution& solution,
                             double s, double slack_span) {
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  const double h = solution.horizontal_tension;
  if (solution.anchor_lifted) {
    return HangingOffset(h, solution.anchor_vertical, s, w, ea);
  }
  const double grounded = solution.grounded_length;
  // Frictionless contact: the grounded part carries H throughout, so it is stretched
  // uniformly by H/EA. With H = 0 the slack grounded part has no defined shape; it is
  // spread evenly (compressed) between the anchor and the foot of the vertical part.
  const double ground_scale =
      h > 0.0 ? 1.0 + h / ea : (grounded > 0.0 ? slack_span / grounded : 0.0);
  if (s <= grounded) return {s * ground_scale, 0.0};
  const Eigen::Vector2d offset = HangingOffset(h, 0.0, s - grounded, w, ea);
  return {grounded * ground_scale + offset.x(), offset.y()};
}

void CheckArcLength(const CatenaryLineProperties& line, double& s) {
  const double slack = 1e-12 * line.length;
  if (!std::isfinite(s) || s < -slack || s > line.length + slack) {
    std::ostringstream out;
    out << "catenary: arc length s = " << s << " m is outside [0, " << line.length << "] m";
    throw Error(out.str());
  }
  s = std::clamp(s, 0.0, line.length);
}

}  // namespace

CatenarySolution SolveCatenary(const CatenaryLineProperties& line, double span, double height) {
  CheckLine(line);
  if (!std::isfinite(span) || !std::isfinite(height) || span < 0.0 || height <= 0.0) {
    throw Error(Describe(line, span, height) +
                ": the fairlead must be above the anchor (height > 0) at a span >= 0");
  }
  const double len = line.length;
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  const double chord = std::hypot(span, height);
  if (chord > len * (1.0 + kMaxStrain)) {
    std::ostringstream out;
    out << Describe(line, span, height) << ": the line cannot reach: the anchor-fairlead "
        << "distance " << chord << " m exceeds the unstretched length by "
        << 100.0 * (chord / len - 1.0) << " % (limit " << 100.0 * kMaxStrain << " %)";
    throw Error(out.str());
  }

  CatenarySolution solution;
  const double vertical_length = VerticalHangingLength(line, height);
  if (vertical_length <= len && span <= len - vertical_length) {
    // Slack: even with H -> 0 the grounded part reaches past the span (the line would
    // double back on the seabed, FAST v7 / MoorPy "profile 4"). Frictionless contact
    // cannot hold any H, so H = 0 and the line hangs vertically over its grounded heap;
    // span = 0 (fairlead straight above the anchor) is the same case.
    solution = MakeSolution(line, 0.0, w * vertical_length);
  } else if (span == 0.0) {
    // Vertical and lifted off: height = L + (V L - w L^2/2)/EA.
    solution = MakeSolution(line, 0.0, 0.5 * w * len + ea * (height - len) / len);
  } else {
    // Regime of the starting point: at lift-off (V = w L, Lb = 0) the height equation gives
    // a = H/w in closed form: sqrt(a^2 + L^2) - a = h' with h' = height - w L^2/(2 EA).
    const double reduced_height = height - w * len * len / (2.0 * ea);
    bool touchdown = true;
    if (reduced_height > 0.0 && reduced_height < len) {
      const double a = (len * len - reduced_height * reduced_height) / (2.0 * reduced_height);
      const double liftoff_span = a * std::asinh(len / a) + w * a * len / ea;
      touchdown = span < liftoff_span;
    } else if (reduced_height >= len) {
      touchdown = false;
    }
    const std::array<Eigen::Vector2d, 2> guesses = {
        touchdown ? TouchdownGuess(line, span, height) : SuspendedGuess(line, span, height),
        JonkmanGuess(line, span, height)};
    Eigen::Vector2d tensions;
    double residual = std::numeric_limits<double>::infinity();
    bool converged = false;
    for (const Eigen::Vector2d& guess : guesses) {
      tensions = guess;
      if ((converged = NewtonSolve(line, span, height, tensions, residual))) break;
    }
    if (!converged) {
      tensions = BisectionGuess(line, span, height, 1e-8);
      converged = NewtonSolve(line, span, height, tensions, residual);
    }
    if (!converged) {
      std::ostringstream out;
      out << Describe(line, span, height) << ": Newton iteration did not converge (residual "
          << residual << " m)";
      throw Error(out.str());
    }
    solution = MakeSolution(line, tensions(0), tensions(1));
  }

  const double strain = solution.fairlead_tension / ea;
  if (strain > kMaxStrain) {
    std::ostringstream out;
    out << Describe(line, span, height) << ": the line cannot reach without a fairlead strain of "
        << 100.0 * strain << " % (limit " << 100.0 * kMaxStrain << " %)";
    throw Error(out.str());
  }
  return solution;
}

TouchdownRange SolveTouchdownRange(const CatenaryLineProperties& line, double height) {
  CheckLine(line);
  const double len = line.length;
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  if (!std::isfinite(height) || height <= 0.0) {
    throw Error(Describe(line, 0.0, height) + ": the fairlead must be above the seabed");
  }
  const double hanging = VerticalHangingLength(line, height);
  if (!(len > hanging)) {
    std::ostringstream out;
    out << "a line of " << len << " m hanging straight down from " << height
        << " m above the seabed does not reach it (it needs more than " << hanging
        << " m, stretched by its own weight)";
    throw Error(out.str());
  }
  TouchdownRange range;
  range.min_span = len - hanging;
  range.min_tension = w * hanging;
  // Lift-off (V = w L, no grounded length): the closed form SolveCatenary uses to pick its
  // regime, a = H/w from sqrt(a^2 + L^2) - a = height - w L^2 / (2 EA).
  // A line whose own weight stretches it by more than the height never lifts off.
  const double reduced_height = height - w * len * len / (2.0 * ea);
  const double a = (len * len - reduced_height * reduced_height) / (2.0 * reduced_height);
  range.max_span = a * std::asinh(len / a) + w * a * len / ea;
  range.max_tension = w * std::hypot(a, len);
  if (!(reduced_height > 0.0) || !(range.max_tension <= kMaxStrain * ea)) {
    std::ostringstream out;
    out << "a line of " << len << " m with its fairlead " << height
        << " m above the seabed does not lift off below a fairlead strain of " << 100.0 * kMaxStrain
        << " %";
    throw Error(out.str());
  }
  return range;
}

double SpanForFairleadTension(const CatenaryLineProperties& line, double height, double tension) {
  const TouchdownRange range = SolveTouchdownRange(line, height);
  if (!(tension > range.min_tension && tension <= range.max_tension)) {
    std::ostringstream out;
    out << "catenary: a fairlead tension of " << tension << " N is outside the touchdown range ("
        << range.min_tension << ", " << range.max_tension << "] N";
    throw Error(out.str());
  }
  double lo = range.min_span;
  double hi = range.max_span;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (SolveCatenary(line, mid, height).fairlead_tension < tension ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::Vector2d CatenaryPointAt(const CatenaryLineProperties& line,
                                const CatenarySolution& solution, double s) {
  CheckLine(line);
  CheckArcLength(line, s);
  // With H = 0 and a grounded part (a slack line) the solution does not record the span;
  // the hanging part is then placed straight above the anchor, which is exact for span = 0.
  // LineCatenary::NodePositions knows the span and places slack lines exactly.
  return PointInPlane(line, solution, s, 0.0);
}

Eigen::Matrix3Xd LineCatenary::NodePositions(int segments) const {
  if (segments < 1) {
    throw Error("catenary: NodePositions needs at least 1 segment, got " +
                std::to_string(segments));
  }
  const Vec3 chord = fairlead - anchor;
  const double span = std::hypot(chord.x(), chord.y());
  // Unit horizontal from the anchor toward the fairlead (any horizontal if vertical).
  const Vec3 along = span > 0.0 ? Vec3(chord.x() / span, chord.y() / span, 0.0) : Vec3::UnitX();
  Eigen::Matrix3Xd nodes(3, segments + 1);
  for (int k = 0; k <= segments; ++k) {
    const double s = k == segments ? line.length : line.length * k / segments;
    const Eigen::Vector2d p = PointInPlane(line, solution, s, span);
    nodes.col(k) = anchor + p.x() * along - p.y() * Vec3::UnitZ();  // NED: z_up = -z
  }
  nodes.col(0) = anchor;  // exact, whatever the rounding above
  return nodes;
}

LineCatenary SolveLineCatenary(const CatenaryLineProperties& line, const Vec3& anchor,
                               const Vec3& fairlead) {
  const double height = anchor.z() - fairlead.z();
  if (!anchor.allFinite() || !fairlead.allFinite() || !(height > 0.0)) {
    std::ostringstream out;
    out << "catenary: the fairlead (z = " << fairlead.z()
        << " m, NED) must be above the anchor (z = " << anchor.z() << " m)";
    throw Error(out.str());
  }
  const Vec3 chord = fairlead - anchor;
  const double span = std::hypot(chord.x(), chord.y());
  LineCatenary result;
  result.line = line;
  result.anchor = anchor;
  result.fairlead = fairlead;
  result.solution = SolveCatenary(line, span, height);
  // The line pulls the fairlead horizontally toward the anchor and down (+z in NED).
  const Vec3 toward_anchor =
      span > 0.0 ? Vec3(-chord.x() / span, -chord.y() / span, 0.0) : Vec3::Zero();
  result.fairlead_force = result.solution.horizontal_tension * toward_anchor +
                          result.solution.vertical_tension * Vec3::UnitZ();
  return result;
}

}  // namespace moorsim::mooring_fem
