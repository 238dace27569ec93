// moorsim command-line entry point: wires the subcommands and turns errors into one line
// on stderr with exit code 2 (bad input) or 1 (a run that failed).
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/version.h"
#include "tools/commands.h"
#include "tools/exit_codes.h"

int main(int argc, char** argv) {
  // Plugin libraries first: the commands' help lists their detector types.
  try {
    moorsim::cli::RegisterPlugins(argc, argv);
  } catch (const moorsim::InputError& e) {
    std::cerr << "moorsim: " << e.what() << "\n";
    return 2;
  }
  // Named "moorsim" in every usage line, whatever path the program was started by.
  CLI::App app{std::string("moorsim ") + moorsim::kVersion +
                   " - turret-moored FPSO mooring simulator (lumped-mass FEM lines on CVODE)",
               "moorsim"};
  app.require_subcommand(1);
  app.set_version_flag("--version", moorsim::kVersion);
  // In registration order, which is also the order of the help listing.
  std::vector<std::pair<const CLI::App*, moorsim::cli::Command>> commands;
  auto add = [&](moorsim::cli::Command (*factory)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    moorsim::cli::Command command = factory(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(command));
  };
  add(&moorsim::cli::AddStaticCommand);
  add(&moorsim::cli::AddRunCommand);
  add(&moorsim::cli::AddSimulateLinesCommand);
  add(&moorsim::cli::AddValidateCommand);
  add(&moorsim::cli::AddSchemaCommand);
  add(&moorsim::cli::AddAnalyzeCommand);
  add(&moorsim::cli::AddDetectCommand);
  add(&moorsim::cli::AddMonitorCommand);
  add(&moorsim::cli::AddStreamCommand);
  add(&moorsim::cli::AddTemplateCommand);
  add(&moorsim::cli::AddImportCommand);
  {
    const std::size_t before = app.get_subcommands({}).size();
    moorsim::cli::Command command = moorsim::cli::AddBatchCommand(app, argc, argv);
    commands.emplace_back(app.get_subcommands({})[before], std::move(command));
  }
  add(&moorsim::cli::AddCompareCommand);
  // CLI11 would only say "A subcommand is required" for a misspelt command.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string name = argv[1];
    bool known = false;
    std::string names;
    for (const auto& [sub, command] : commands) {
      known |= sub->get_name() == name;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "moorsim: unknown command '" << name << "' (known: " << names << ")\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "moorsim: " << e.what() << "\n";
    return 2;
  }
  try {
    for (const auto& [sub, command] : commands) {
      if (sub->parsed()) return command();
    }
    return 2;
  } catch (const moorsim::OptionError& e) {  // a library option, named as its flag
    std::cerr << "moorsim: " << moorsim::cli::FlagMessage(e) << "\n";
    return 2;
  } catch (const moorsim::InputError& e) {
    // One located line per problem (a scenario reports all of its errors at once).
    std::istringstream lines(e.what());
    for (std::string line; std::getline(lines, line);) std::cerr << "moorsim: " << line << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "moorsim: " << e.what() << "\n";
    return 1;
  }
}
