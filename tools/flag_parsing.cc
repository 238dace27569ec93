// Number parsing for command-line flags: every failure is an InputError that names the
// flag and the text it was given.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "detectors/registry.h"
#include "tools/commands.h"

namespace moorsim::cli {

void AddPluginOption(CLI::App* sub) {
  static std::vector<std::string> ignored;  // main() registered them already
  sub->add_option("--plugin", ignored,
                  "detector plugin library (repeatable): its detector types are named by "
                  "`type:` alone and listed below");
}

std::vector<std::string> RegisterPlugins(int argc, char** argv) {
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    std::string path;
    if (arg == "--plugin") {
      if (i + 1 >= argc) throw InputError("--plugin: needs a library path");
      path = argv[++i];
    } else if (arg.rfind("--plugin=", 0) == 0) {
      path = arg.substr(9);
    } else {
      continue;
    }
    RequireText("--plugin", path);
    // A path without a slash would make dlopen() search the system's library path.
    path = std::filesystem::absolute(path).lexically_normal().string();
    try {
      detectors::RegisterPluginLibrary(path);
    } catch (const InputError& error) {
      throw InputError(std::string("--plugin: ") + error.what());
    }
    paths.push_back(path);
  }
  return paths;
}

std::vector<double> ParseNumberList(const std::string& flag, const std::string& text) {
  if (text.empty()) throw InputError(flag + ": no numbers in ''");
  std::vector<double> values;
  // Every item between commas counts, so "1,2," and "1,,2" have an empty item: an error.
  for (std::size_t begin = 0;;) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? comma : comma - begin);
    if (item.empty()) throw InputError(flag + ": empty item in '" + text + "'");
    // strtod, not stod: a number too small for a normal double (1e-320) is read as the
    // nearest double (underflow is not an error); one too large is infinite, refused below.
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    const auto used = static_cast<std::size_t>(end - item.c_str());
    if (used == 0 || used != item.size() || !std::isfinite(value)) {
      throw InputError(flag + ": '" + item + "' in '" + text + "' is not a finite number");
    }
    values.push_back(value);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return values;
}

const std::string& RequireText(const std::string& flag, const std::string& text) {
  if (text.empty()) throw InputError(flag + ": empty value (give one or leave the flag out)");
  return text;
}

double ParseNumber(const std::string& flag, const std::string& text) {
  const std::vector<double> values = ParseNumberList(flag, text);
  if (values.size() != 1) throw InputError(flag + ": '" + text + "' must be a single number");
  return values.front();
}

int ParseInteger(const std::string& flag, const std::string& text, int min, int max) {
  const double value = ParseNumber(flag, text);
  if (value != std::floor(value) || value < min || value > max) {
    throw InputError(flag + ": '" + text + "' must be a whole number in " + std::to_string(min) +
                     ".." + std::to_string(max));
  }
  return static_cast<int>(value);
}

void CheckScenarioOut(const std::string& path, bool force) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw InputError("--out: '" + path + "' is a folder (give the scenario file's name)");
  }
  if (std::filesystem::exists(path, ignored) && !std::filesystem::is_regular_file(path, ignored)) {
    throw InputError("--out: '" + path +
                     "' is not a regular file (without --out the scenario goes to stdout)");
  }
  if (std::filesystem::exists(path, ignored) && !force) {
    throw InputError("--out: '" + path + "' exists (give --force to overwrite it)");
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder, ignored)) {
    throw InputError("--out: folder '" + folder.string() + "' does not exist");
  }
}

}  // namespace moorsim::cli
