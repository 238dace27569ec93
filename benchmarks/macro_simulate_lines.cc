// Macro benchmark: runs the real `moorsim simulate-lines` on the seed mooring with the
// turret surging 5 m / 100 s plus 2 m / 10 s, at several segment counts, and judges each
// run against a reference run of the same model with tolerances 100x tighter
// (docs/design.md section 8.1: "it finished" is not "it is right").
//
//   moorsim_macro_benchmark [--duration S] [--segments 20,50,100] [--reference-scale 0.01]
//                           [--scenario FILE] [--moorsim PATH] [--no-reference]
//
// Prints wall time, real-time factor (simulated s / wall s, one process on one core),
// CVODE statistics, and the RMS fairlead-tension difference from the reference (CSV rows
// every 0.5 s, the CLI default, for both).
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Options {
  double duration = 1000.0;
  std::vector<int> segments = {20, 50, 100};
  double reference_scale = 0.01;
  bool reference = true;
  std::string scenario = MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml";
  std::string moorsim = MOORSIM_CLI;
  std::string motion = "surge:5,100,2,10";
  std::vector<std::string> sets;  // --set key.path=value, passed to both runs
};

struct RunResult {
  std::string summary;  // the two lines moorsim prints
  double wall = 0.0;
  double real_time_factor = 0.0;
  std::map<double, std::vector<double>> tensions;  // time -> per-line tension [N]
};

std::string Run(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    std::fprintf(stderr, "cannot run: %s\n", command.c_str());
    std::exit(1);
  }
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) out += buffer.data();
  if (pclose(pipe) != 0) {
    std::fprintf(stderr, "failed: %s\n%s", command.c_str(), out.c_str());
    std::exit(1);
  }
  return out;
}

RunResult Simulate(const Options& o, int segments, double tolerance_scale) {
  const std::string csv = "/tmp/moorsim_macro_" + std::to_string(segments) + "_" +
                          std::to_string(tolerance_scale) + ".csv";
  std::ostringstream cmd;
  cmd << o.moorsim << " simulate-lines " << o.scenario << " --motion " << o.motion << " --duration "
      << o.duration << " --segments " << segments << " --tolerance-scale " << tolerance_scale
      << " --quiet --out " << csv;
  for (const std::string& set : o.sets) cmd << " --set '" << set << "'";
  RunResult r;
  r.summary = Run(cmd.str());
  double simulated = 0.0;
  std::sscanf(r.summary.c_str(), "simulated %lf s in %lf s wall", &simulated, &r.wall);
  r.real_time_factor = simulated / r.wall;
  std::ifstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::stringstream fields(line);
    std::string f;
    std::getline(fields, f, ',');
    const double t = std::round(std::stod(f) * 1e6) / 1e6;
    std::vector<double>& row = r.tensions[t];
    while (std::getline(fields, f, ',')) row.push_back(std::stod(f));
  }
  std::remove(csv.c_str());
  return r;
}

struct Difference {
  double rms_relative_to_tension = 0.0;  // RMS(dT) / RMS(T_ref)
  double rms_relative_to_dynamic = 0.0;  // RMS(dT) / RMS(T_ref - mean of its line)
  double max_abs = 0.0;                  // [N]
};

Difference Compare(const RunResult& run, const RunResult& ref) {
  const std::size_t lines = ref.tensions.begin()->second.size();
  std::vector<double> mean(lines, 0.0);
  for (const auto& [t, row] : ref.tensions) {
    for (std::size_t i = 0; i < lines; ++i) mean[i] += row[i] / ref.tensions.size();
  }
  double d2 = 0.0, t2 = 0.0, dyn2 = 0.0;
  Difference d;
  long n = 0;
  for (const auto& [t, row] : ref.tensions) {
    const auto it = run.tensions.find(t);
    if (it == run.tensions.end()) continue;
    for (std::size_t i = 0; i < lines; ++i) {
      const double diff = it->second[i] - row[i];
      d2 += diff * diff;
      t2 += row[i] * row[i];
      dyn2 += (row[i] - mean[i]) * (row[i] - mean[i]);
      d.max_abs = std::max(d.max_abs, std::abs(diff));
      ++n;
    }
  }
  d.rms_relative_to_tension = std::sqrt(d2 / t2);
  d.rms_relative_to_dynamic = std::sqrt(d2 / dyn2);
  return d;
}

std::vector<int> ParseList(const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  for (std::string f; std::getline(in, f, ',');) values.push_back(std::stoi(f));
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--duration") {
      o.duration = std::stod(value());
    } else if (arg == "--segments") {
      o.segments = ParseList(value());
    } else if (arg == "--reference-scale") {
      o.reference_scale = std::stod(value());
    } else if (arg == "--scenario") {
      o.scenario = value();
    } else if (arg == "--moorsim") {
      o.moorsim = value();
    } else if (arg == "--no-reference") {
      o.reference = false;
    } else if (arg == "--set") {
      o.sets.push_back(value());
    } else {
      std::fprintf(stderr,
                   "usage: moorsim_macro_benchmark [--duration S] [--segments 20,50,100] "
                   "[--reference-scale 0.01] [--scenario FILE] [--moorsim PATH] "
                   "[--no-reference] [--set key.path=value]...\n");
      return 2;
    }
  }
  std::printf("moorsim simulate-lines %s, motion %s, %.0f s\n\n", o.scenario.c_str(),
              o.motion.c_str(), o.duration);
  std::vector<std::string> rows;
  for (int n : o.segments) {
    const RunResult run = Simulate(o, n, 1.0);
    std::printf("--- %d segments ---\n%s", n, run.summary.c_str());
    std::ostringstream row;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%4d | %8.2f | %8.1f", n, run.wall, run.real_time_factor);
    row << buf;
    if (o.reference) {
      const RunResult ref = Simulate(o, n, o.reference_scale);
      std::printf("reference (tolerances x %g):\n%s", o.reference_scale, ref.summary.c_str());
      const Difference d = Compare(run, ref);
      std::snprintf(buf, sizeof buf, " | %9.3f %% | %9.2f %% | %8.1f | %8.2f",
                    100.0 * d.rms_relative_to_tension, 100.0 * d.rms_relative_to_dynamic,
                    d.max_abs / 1e3, ref.wall);
      row << buf;
    }
    rows.push_back(row.str());
    std::printf("\n");
  }
  std::printf(
      "segments | wall [s] | RTF [x] | RMS dT / RMS T | RMS dT / RMS(T - mean) | "
      "max |dT| [kN] | reference wall [s]\n");
  for (const std::string& r : rows) std::printf("%s\n", r.c_str());
  return 0;
}
