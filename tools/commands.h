// The moorsim subcommands. Each registers its options on a CLI11 subcommand and returns a
// callable that runs it; main() maps exceptions to exit codes (docs/design.md section 2).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace moorsim::cli {

using Command = std::function<int()>;

Command AddStaticCommand(CLI::App& app);
Command AddSimulateLinesCommand(CLI::App& app);
Command AddValidateCommand(CLI::App& app);
/// `moorsim schema`: the scenario or campaign format as a JSON Schema.
Command AddSchemaCommand(CLI::App& app);
Command AddRunCommand(CLI::App& app);
Command AddAnalyzeCommand(CLI::App& app);
Command AddDetectCommand(CLI::App& app);
/// `moorsim compare A B`: two outputs channel by channel, exit 0 (equal) or 1 (differ).
Command AddCompareCommand(CLI::App& app);
/// `moorsim template`: a starting scenario with its anchors placed from the catenary.
Command AddTemplateCommand(CLI::App& app);
/// `moorsim batch`; argc/argv are recorded in the campaign's results.
Command AddBatchCommand(CLI::App& app, int argc, char** argv);

/// Declares `--plugin PATH` (repeatable) on a subcommand that makes detectors. main()
/// registers the libraries before the commands are built (RegisterPlugins), so that their
/// types are in the subcommand's --help and nameable by `type:` alone.
void AddPluginOption(CLI::App* sub);
/// Registers every `--plugin PATH` / `--plugin=PATH` of the command line
/// (detectors::RegisterPluginLibrary), a relative path from the working directory; returns
/// the paths registered. Throws InputError "--plugin: ..." for one that cannot be used.
std::vector<std::string> RegisterPlugins(int argc, char** argv);

/// Splits "a,b,c" into numbers; throws InputError naming the flag on anything else.
std::vector<double> ParseNumberList(const std::string& flag, const std::string& text);
/// The flag's text if it is not empty; throws InputError naming the flag otherwise (an
/// empty value is never taken as "not given").
const std::string& RequireText(const std::string& flag, const std::string& text);
/// One number (no list); throws InputError naming the flag otherwise.
double ParseNumber(const std::string& flag, const std::string& text);
/// One whole number in [min, max]; throws InputError naming the flag and the range.
int ParseInteger(const std::string& flag, const std::string& text, int min, int max);
/// Checks `--out PATH` for a scenario file about to be written: not a folder or a device,
/// its folder there, and not an existing file unless `force`. Throws InputError naming
/// --out.
void CheckScenarioOut(const std::string& path, bool force);
/// The scenario commands' --help note for --out.
inline constexpr const char* kScenarioOutNote =
    "Without --out the scenario goes to stdout; --out does not replace an existing file\n"
    "unless --force.";
/// `moorsim monitor CONFIG`: the detection on a vessel's own sensor feeds.
Command AddMonitorCommand(CLI::App& app);
/// `moorsim stream SCENARIO --to CONFIG`: a simulated ship's sensors played to a monitor.
Command AddStreamCommand(CLI::App& app);
/// Registers `moorsim import`.
Command AddImportCommand(CLI::App& app);

}  // namespace moorsim::cli
