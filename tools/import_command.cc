// `moorsim import moordyn FILE`: a MoorDyn input file as a moorsim scenario
// (scenarios/moordyn.h), checked by the loader before it is written.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "runner/run.h"
#include "scenarios/moordyn.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct ImportOptions {
  std::string format;
  std::string file;
  std::optional<std::string> out;
  bool force = false;
};

int RunImport(const ImportOptions& o) {
  if (o.format != "moordyn") {
    throw InputError("import: format '" + o.format + "' is not known (known: moordyn)");
  }
  const std::string file = RequireText("FILE", o.file);
  if (o.out) CheckScenarioOut(RequireText("--out", *o.out), o.force);
  std::string command = "moorsim import moordyn " + file;
  if (o.out) command += " --out " + *o.out;
  const scenarios::MoorDynImport imported = scenarios::ImportMoorDyn(
      file, command, o.out ? std::filesystem::path(*o.out).stem().string() : "");
  for (const std::string& warning : imported.warnings) {
    std::cerr << "moorsim: warning: " << warning << "\n";
  }
  if (!o.out) {
    if (!imported.files.empty()) {
      throw InputError(file + ": the scenario names a file of its own (" +
                       imported.files.front().first + ") to be written beside it: give --out");
    }
    std::cout << imported.yaml;
    return 0;
  }
  const std::filesystem::path folder = std::filesystem::path(*o.out).parent_path();
  // The scenario and the files it names are written together or not at all.
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  for (const auto& [name, contents] : imported.files) {
    const std::string beside = (folder / name).string();
    if (!o.force && std::filesystem::exists(beside)) {
      throw InputError("--out: " + beside + " exists (give --force to replace it)");
    }
    files.emplace_back(beside, contents);
  }
  files.emplace_back(*o.out, imported.yaml);
  runner::WriteFilesAtomically(files);
  std::printf("%s: %d line%s from %s\n", o.out->c_str(), imported.lines,
              imported.lines == 1 ? "" : "s", file.c_str());
  return 0;
}

}  // namespace

Command AddImportCommand(CLI::App& app) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* sub =
      app.add_subcommand("import", "write a scenario from another program's mooring model");
  sub->footer(
      "\nFormats:\n"
      "  moordyn: a MoorDyn (v1 or v2) input file: its line types (with the static and\n"
      "    dynamic stiffness of a visco-elastic rope, or a stiffness table as a\n"
      "    tension-strain curve), points (fixed: anchors; vessel or\n"
      "    coupled: fairleads; free points joining two lines: the joints of a composite\n"
      "    line; other free points: moorsim's free points, with their mass, volume, CdA and\n"
      "    Ca) and lines, water depth and density, gravity, seabed stiffness, damping and\n"
      "    friction, a SeafloorFile as a depth grid written beside the scenario, MoorDyn's\n"
      "    waves (WaveKin 2, 3, 7) as the regular waves they are made of, felt by the\n"
      "    lines, and its currents (Currents 1, 2, 5) as a depth profile or as a current\n"
      "    table written beside the scenario. Frames are converted (MoorDyn's z up and y to\n"
      "    port to moorsim's z down and y to starboard) and the tangential drag coefficient\n"
      "    multiplied by pi (MoorDyn applies it to the circumference); a fixed point above\n"
      "    the seabed holds its line's end in the water (anchor_in_water). Rods, bodies,\n"
      "    SYROPE ropes and lines between two fixed points are refused, one line each;\n"
      "    bending stiffness is left out with a warning. The scenario holds the mooring\n"
      "    only: `moorsim static` and `moorsim simulate-lines` run it; add a vessel for\n"
      "    `moorsim run`.\n" +
      std::string(kScenarioOutNote));
  sub->add_option("format", o->format, "the model's format: moordyn")->required();
  sub->add_option("FILE", o->file, "the model's input file")->required();
  sub->add_option("--out", o->out, "write the scenario to this file (default: stdout)");
  sub->add_flag("--force", o->force, "with --out: replace an existing file");
  return [o] { return RunImport(*o); };
}

}  // namespace moorsim::cli
