// A stand-alone driver for MoorDyn v2 (C API, MoorDyn2.h), used by
// benchmarks/moordyn_side_by_side.sh to run the same model and the same prescribed
// fairlead motion as `moorsim simulate-lines`. It is built against an external MoorDyn
// build; nothing of MoorDyn is part of this project.
//
//   moordyn_driver INPUT OUT.csv DURATION COUPLING_DT OUTPUT_INTERVAL MOTION...
//
// MOTION is DOF:A1,T1[,A2,T2...] with DOF surge, sway or heave, as moorsim's --motion:
// every coupled point is offset by sum A_i sin(2 pi t / T_i) along the DOF, with moorsim's
// axes (x forward, y starboard, z down), i.e. MoorDyn's (x, -y, -z). Every COUPLING_DT
// the coupled points get their position at t and the secant velocity to t + COUPLING_DT
// (MoorDyn moves them linearly within a coupling step, so the path is continuous). The
// CSV has time and, per coupled point (in MoorDyn's order), the magnitude of the force
// its lines exert on it minus the end nodes' mass times the prescribed acceleration
// (the load-cell force, as moorsim's simulate-lines writes it). The wall time of the
// stepping loop alone (not MoorDyn_Init's initial condition) goes to stdout.
#include <moordyn/MoorDyn2.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Harmonic {
  int axis;  // 0 x, 1 y, 2 z, moorsim frame
  double amplitude, period;
};

std::vector<Harmonic> ParseMotion(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw std::string("bad motion '" + text + "'");
  const std::string dof = text.substr(0, colon);
  int axis = dof == "surge" ? 0 : dof == "sway" ? 1 : dof == "heave" ? 2 : -1;
  if (axis < 0) throw std::string("unknown DOF '" + dof + "' (surge, sway, heave)");
  std::vector<double> v;
  std::string rest = text.substr(colon + 1);
  size_t start = 0;
  while (start <= rest.size()) {
    size_t comma = rest.find(',', start);
    if (comma == std::string::npos) comma = rest.size();
    v.push_back(std::atof(rest.substr(start, comma - start).c_str()));
    start = comma + 1;
  }
  if (v.size() % 2 != 0 || v.empty()) throw std::string("motion '" + text + "': A,T pairs");
  std::vector<Harmonic> h;
  for (size_t i = 0; i < v.size(); i += 2) h.push_back({axis, v[i], v[i + 1]});
  return h;
}

// Offset, velocity and acceleration of the motion at t, in MoorDyn's frame.
void Motion(const std::vector<Harmonic>& hs, double t, double p[3], double v[3], double a[3]) {
  const double sign[3] = {1.0, -1.0, -1.0};  // moorsim (x, y, z) -> MoorDyn (x, -y, -z)
  for (int k = 0; k < 3; ++k) p[k] = v[k] = a[k] = 0.0;
  for (const Harmonic& h : hs) {
    const double w = 2.0 * M_PI / h.period, s = sign[h.axis];
    p[h.axis] += s * h.amplitude * std::sin(w * t);
    v[h.axis] += s * h.amplitude * w * std::cos(w * t);
    a[h.axis] -= s * h.amplitude * w * w * std::sin(w * t);
  }
}

void Check(int err, const char* what) {
  if (err != MOORDYN_SUCCESS) {
    std::fprintf(stderr, "moordyn_driver: %s failed (error %d)\n", what, err);
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: %s INPUT OUT.csv DURATION COUPLING_DT OUTPUT_INTERVAL MOTION...\n",
                 argv[0]);
    return 2;
  }
  const std::string input = argv[1], out_path = argv[2];
  const double duration = std::atof(argv[3]), dtc = std::atof(argv[4]), dto = std::atof(argv[5]);
  std::vector<Harmonic> motion;
  try {
    for (int i = 6; i < argc; ++i) {
      const auto h = ParseMotion(argv[i]);
      motion.insert(motion.end(), h.begin(), h.end());
    }
  } catch (const std::string& e) {
    std::fprintf(stderr, "moordyn_driver: %s\n", e.c_str());
    return 2;
  }
  const long per_output = std::lround(dto / dtc);
  if (per_output < 1 || std::fabs(per_output * dtc - dto) > 1e-9 * dto) {
    std::fprintf(stderr, "moordyn_driver: OUTPUT_INTERVAL must be a multiple of COUPLING_DT\n");
    return 2;
  }

  MoorDyn md = MoorDyn_Create(input.c_str());
  if (!md) {
    std::fprintf(stderr, "moordyn_driver: MoorDyn_Create(%s) failed\n", input.c_str());
    return 1;
  }
  unsigned int ndof = 0, npoints = 0;
  Check(MoorDyn_NCoupledDOF(md, &ndof), "MoorDyn_NCoupledDOF");
  Check(MoorDyn_GetNumberPoints(md, &npoints), "MoorDyn_GetNumberPoints");
  std::vector<MoorDynPoint> coupled;
  std::vector<double> x0;
  for (unsigned int i = 1; i <= npoints; ++i) {
    MoorDynPoint p = MoorDyn_GetPoint(md, i);
    int type = 0;
    Check(MoorDyn_GetPointType(p, &type), "MoorDyn_GetPointType");
    if (type != -1) continue;  // -1: coupled (vessel, fairlead)
    double r[3];
    Check(MoorDyn_GetPointPos(p, r), "MoorDyn_GetPointPos");
    coupled.push_back(p);
    x0.insert(x0.end(), r, r + 3);
  }
  if (ndof != 3 * coupled.size()) {
    std::fprintf(stderr, "moordyn_driver: %u coupled DOF, expected 3 per coupled point only\n",
                 ndof);
    return 1;
  }
  const size_t n = coupled.size();
  std::vector<double> x(ndof), xd(ndof), f(ndof);
  auto set_state = [&](double t) {
    double p0[3], v0[3], a0[3], p1[3], v1[3], a1[3];
    Motion(motion, t, p0, v0, a0);
    Motion(motion, t + dtc, p1, v1, a1);
    for (size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) {
        x[3 * i + k] = x0[3 * i + k] + p0[k];
        xd[3 * i + k] = (p1[k] - p0[k]) / dtc;
      }
    }
  };
  set_state(0.0);
  {
    // Initial condition at the mean position, at rest (as moorsim's static start).
    std::vector<double> still(ndof, 0.0);
    Check(MoorDyn_Init(md, x0.data(), still.data()), "MoorDyn_Init");
  }

  std::FILE* out = std::fopen(out_path.c_str(), "w");
  if (!out) {
    std::fprintf(stderr, "moordyn_driver: cannot write %s\n", out_path.c_str());
    return 1;
  }
  std::fprintf(out, "# MoorDyn %s", input.c_str());
  for (int i = 6; i < argc; ++i) std::fprintf(out, " motion=%s", argv[i]);
  std::fprintf(out, " coupling_dt=%g\ntime", dtc);
  for (size_t i = 0; i < n; ++i) std::fprintf(out, ",line%zu", i + 1);
  std::fprintf(out, "\n");
  std::vector<std::vector<double>> rows;
  const long steps = std::lround(duration / dtc);
  rows.reserve(steps / per_output + 2);
  auto record = [&](double t) {
    double p[3], v[3], a[3];
    Motion(motion, t, p, v, a);
    std::vector<double> row{t};
    for (size_t i = 0; i < n; ++i) {
      double F[3], M[3][3];
      Check(MoorDyn_GetPointForce(coupled[i], F), "MoorDyn_GetPointForce");
      Check(MoorDyn_GetPointM(coupled[i], M), "MoorDyn_GetPointM");
      double s = 0.0;
      for (int r = 0; r < 3; ++r) {
        double c = F[r];
        for (int k = 0; k < 3; ++k) c -= M[r][k] * a[k];
        s += c * c;
      }
      row.push_back(std::sqrt(s));
    }
    rows.push_back(std::move(row));
  };
  // The forces at t = 0 (a zero-length step only returns them).
  double t = 0.0, zero = 0.0;
  Check(MoorDyn_Step(md, x.data(), xd.data(), f.data(), &t, &zero), "MoorDyn_Step");
  record(0.0);

  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    const double tk = k * dtc;
    set_state(tk);
    double dt = dtc;
    t = tk;
    const int err = MoorDyn_Step(md, x.data(), xd.data(), f.data(), &t, &dt);
    if (err != MOORDYN_SUCCESS) {
      std::fprintf(stderr, "moordyn_driver: MoorDyn_Step failed at t = %g s (error %d)\n", tk, err);
      return 1;
    }
    if ((k + 1) % per_output == 0) record((k + 1) * dtc);
    for (size_t i = 0; i < n; ++i) {
      for (int r = 0; r < 3; ++r) {
        if (!std::isfinite(f[3 * i + r])) {
          std::fprintf(stderr, "moordyn_driver: non-finite force at t = %g s (unstable)\n",
                       (k + 1) * dtc);
          return 1;
        }
      }
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const auto& row : rows) {
    std::fprintf(out, "%.4f", row[0]);
    for (size_t i = 1; i < row.size(); ++i) std::fprintf(out, ",%.10g", row[i]);
    std::fprintf(out, "\n");
  }
  std::fclose(out);
  MoorDyn_Close(md);
  std::printf("moordyn_driver: simulated %.1f s in %.3f s wall\n", duration, wall);
  return 0;
}
