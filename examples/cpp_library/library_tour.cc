// moorsim's C++ interface from a program of one's own, built against an installed moorsim
// (find_package(moorsim), target moorsim::moorsim):
//   1. a mooring built in code from typed parameters, no YAML, and its lines stepped
//      along the body's motion (mooring_fem::CoupledLines);
//   2. a scenario run as one call, its rows handed to a callback, stopped on request
//      after the first minute (runner::RunScenario);
//   3. the coupled plant stepped with a thrust command of one's own
//      (runner::SteppedPlant);
//   4. the plant's typed model (simulation::PlantModel) taken from the scenario, changed
//      in code (no failure, another setpoint) and simulated (simulation::Simulation).
//
//   library_tour SCENARIO.yaml
#include <cmath>
#include <cstdio>
#include <numbers>

#include <moorsim/core/version.h>
#include <moorsim/mooring_fem/coupled_lines.h>
#include <moorsim/runner/run.h>
#include <moorsim/runner/stepped_plant.h>
#include <moorsim/scenarios/load.h>
#include <moorsim/scenarios/plant_builder.h>
#include <moorsim/simulation/simulation.h>

namespace ms = moorsim;

// Four chains at 90 deg in 150 m of water, as typed parameters.
ms::mooring_fem::MooringParameters FourChains() {
  ms::mooring_fem::MooringParameters m;
  m.water.depth = 150.0;
  ms::mooring_fem::LineType chain;
  chain.name = "chain";
  chain.diameter = 0.08;
  chain.mass_per_length = 140.0;
  chain.axial_stiffness = 6.0e8;
  chain.axial_damping_ratio = 0.5;
  chain.drag_normal = 1.2;
  chain.drag_tangential = 0.4;
  chain.added_mass_normal = 1.0;
  m.line_types.push_back(chain);
  for (int i = 0; i < 4; ++i) {
    const double a = i * std::numbers::pi / 2.0;
    const ms::Vec3 direction(std::cos(a), std::sin(a), 0.0);
    m.lines.push_back(ms::mooring_fem::LineParameters::Uniform(
        i + 1, "chain", 640.0, 20, 600.0 * direction + ms::Vec3(0, 0, 150),
        10.0 * direction + ms::Vec3(0, 0, 5)));
  }
  return m;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: library_tour SCENARIO.yaml\n");
    return 2;
  }
  std::printf("moorsim %s\n", ms::kVersion);
  try {
    // 1. Lines from typed parameters, the body surging 3 m at a 30 s period.
    ms::mooring_fem::CoupledLines lines(FourChains(), ms::mooring_fem::SolverSettings{});
    ms::mooring_fem::BodyDofs x{}, xd{};
    lines.Init(x, xd);
    const double w = 2.0 * std::numbers::pi / 30.0;
    for (int k = 1; k <= 100; ++k) {
      const double t = 0.1 * k;
      x[0] = 3.0 * std::sin(w * t);
      xd[0] = 3.0 * w * std::cos(w * t);
      lines.Step(x, xd, 0.1);
    }
    const std::vector<ms::Vec3> forces = lines.FairleadForces();
    std::printf("typed lines at %.1f s: fairlead tensions %.0f %.0f %.0f %.0f N\n", lines.time(),
                forces[0].norm(), forces[1].norm(), forces[2].norm(), forces[3].norm());

    // 2. A run with a row callback, stopped after its first 60 s.
    ms::runner::RunRequest request;
    request.scenario_path = argv[1];
    request.write_files = false;
    int rows = 0;
    double last_time = 0.0;
    request.on_row = [&](const ms::simulation::Sample& s) {
      ++rows;
      last_time = s.time;
    };
    request.stop_requested = [&] { return last_time >= 60.0 ? 2 : 0; };
    const ms::runner::RunResult result = ms::runner::RunScenario(request);
    std::printf("run: %s after %d rows, at %.0f s\n", ms::runner::StatusName(result.status), rows,
                result.simulated_time);

    // 3. The plant with a thrust of one's own: 1 MN forward for a minute.
    ms::runner::SteppedPlant plant(ms::scenarios::LoadScenario(argv[1]), 1);
    const ms::Vec6 start = plant.Now().pose_true;
    plant.SetThrustCommand(ms::Vec3(1.0e6, 0.0, 0.0));
    plant.AdvanceTo(60.0);
    const ms::Vec6 end = plant.Now().pose_true;
    const double forward =
        (end(0) - start(0)) * std::cos(start(5)) + (end(1) - start(1)) * std::sin(start(5));
    std::printf("plant: %.2f m forward in 60 s under 1 MN of its own thrust\n", forward);

    // 4. The typed model: the scenario's plant without its failure, its controller asked
    // to hold a point 10 m north of the scenario's setpoint.
    ms::simulation::PlantModel model =
        ms::scenarios::ToPlantModel(ms::scenarios::LoadScenario(argv[1]));
    model.failure.reset();
    model.controller.spec.setpoint.x() += 10.0;
    ms::simulation::Simulation moved(model, 1);
    const double north = moved.Record().pose_true(0);
    moved.AdvanceTo(120.0);
    std::printf("typed plant: %.2f m north in 120 s toward a setpoint moved 10 m north\n",
                moved.Record().pose_true(0) - north);
  } catch (const ms::Error& e) {
    std::fprintf(stderr, "library_tour: %s\n", e.what());
    return 1;
  }
  return 0;
}
