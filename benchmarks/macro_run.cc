// Macro benchmark of the coupled simulation: runs the real `moorsim run` on a scenario
// (default: the seed FPSO with waves, current, PI controller and sensors,
// scenarios/library/thesis_no_failure_current.yaml) and prints the real-time factor, where
// the time goes (right-hand side, Jacobian, linear-solver factorisations and solves, the rest:
// CVODE's own work, events, controller, sensors, output) and the child's peak memory.
//
//   moorsim_macro_run [--duration S] [--scenario FILE] [--set key=value]... [--moorsim PATH]
//
// One process, one core (the build is not multi-threaded). The output directory is a fresh
// temporary one, removed afterwards.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::string scenario = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure_current.yaml";
  std::string moorsim = MOORSIM_CLI;
  std::string duration = "1000";
  std::vector<std::string> sets;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--duration" && has_value) {
      duration = argv[++i];
    } else if (arg == "--scenario" && has_value) {
      scenario = argv[++i];
    } else if (arg == "--set" && has_value) {
      sets.push_back(argv[++i]);
    } else if (arg == "--moorsim" && has_value) {
      moorsim = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: moorsim_macro_run [--duration S] [--scenario FILE] [--set k=v]... "
                   "[--moorsim PATH]\n");
      return 2;
    }
  }
  char pattern[] = "/tmp/moorsim_macro_XXXXXX";
  if (mkdtemp(pattern) == nullptr) return 1;
  const std::string out = pattern;
  std::vector<std::string> args = {moorsim,  "run",   scenario, "--duration",
                                   duration, "--out", out,      "--quiet"};
  for (const std::string& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  std::vector<char*> argv_child;
  for (std::string& a : args) argv_child.push_back(a.data());
  argv_child.push_back(nullptr);
  const pid_t child = fork();
  if (child == 0) {
    execv(argv_child[0], argv_child.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "moorsim run failed (status %d)\n", status);
    return 1;
  }
  std::ifstream file(out + "/summary.json");
  const nlohmann::json s = nlohmann::json::parse(file);
  const auto h5_size = std::filesystem::file_size(out + "/run.h5");
  std::filesystem::remove_all(out);

  const double wall = s["wall_time"].get<double>();
  const nlohmann::json& integ = s["integrator"];
  const double rhs = integ["rhs_seconds"].get<double>();
  const double jac = integ["jacobian_seconds"].get<double>();
  const double setup = integ["linear_setup_seconds"].get<double>();
  const double solve = integ["linear_solve_seconds"].get<double>();
  const double other = wall - rhs - jac - setup - solve;
  std::printf("scenario %s, %s s simulated, seed %s\n", s["scenario"].get<std::string>().c_str(),
              duration.c_str(), s["seed"].dump().c_str());
  std::printf("wall %.2f s, real-time factor %.0fx\n", wall, s["real_time_factor"].get<double>());
  std::printf(
      "steps %ld, rhs %ld, jacobians %ld, linear setups %ld, newton failures %ld, "
      "error-test failures %ld\n",
      integ["steps"].get<long>(), integ["rhs_evaluations"].get<long>(),
      integ["jacobian_evaluations"].get<long>(), integ["linear_setups"].get<long>(),
      integ["newton_failures"].get<long>(), integ["error_test_failures"].get<long>());
  std::printf(
      "time shares: rhs %.1f %%, jacobian %.1f %%, factorisations %.1f %%, "
      "solves %.1f %%, everything else %.1f %%\n",
      100 * rhs / wall, 100 * jac / wall, 100 * setup / wall, 100 * solve / wall,
      100 * other / wall);
  if (s.contains("detection") && s["detection"]["samples"].get<long>() > 0) {
    const nlohmann::json& d = s["detection"];
    const double update = d["update_seconds"].get<double>();
    const double setup = d["setup_seconds"].get<double>();
    const long samples = d["samples"].get<long>();
    std::printf(
        "detection: %ld samples, %.1f us per sample (observers + detectors), updates %.1f %% "
        "of wall, setup %.3f s (%.1f %% of wall)\n",
        samples, 1e6 * update / samples, 100 * update / wall, setup, 100 * setup / wall);
  }
  std::printf("peak memory (max RSS of the run) %.1f MB, run.h5 %.1f MB\n",
              usage.ru_maxrss / 1024.0, h5_size / 1e6);
  return 0;
}
