// Detectors from shared libraries built outside the moorsim tree, through the C ABI of
// detectors/plugin/moorsim_detector_plugin.h: the library is loaded (dlopen), its ABI
// version checked before anything else is read, its parameter tables turned into the
// registry's form (so a plugin's parameters get the built-in ones' checks and messages),
// and each instance wrapped as a Detector that checks the plugin's side of the contract at
// every sample (finite scores, a hypothesis in range).
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "detectors/detector.h"
#include "detectors/plugin/moorsim_detector_plugin.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

/// A loaded plugin library; its types stay valid while any detector made from it lives.
class PluginLibrary {
 public:
  /// Loads `path` (a relative path is taken from the working directory, as the scenario's
  /// loader resolves it). Throws InputError "plugin <path>: <why>" if the library cannot be
  /// loaded, lacks an entry point, has another ABI version or declares a malformed table.
  static std::shared_ptr<const PluginLibrary> Load(const std::string& path);
  ~PluginLibrary();
  PluginLibrary(const PluginLibrary&) = delete;
  PluginLibrary& operator=(const PluginLibrary&) = delete;

  const std::string& path() const { return path_; }
  /// SHA-256 of the library file as loaded, lower-case hex: outputs record it so that a
  /// result names exactly the code that produced it.
  const std::string& sha256() const { return sha256_; }
  /// The types the library provides, in its order.
  std::vector<std::string_view> TypeNames() const;
  /// The type named `type`, or nullptr.
  const moorsim_detector_plugin* Find(std::string_view type) const;
  /// Its parameter table in the registry's form (sorted by name, as the plugin declared it).
  std::span<const DetectorParameter> Parameters(std::string_view type) const;

 private:
  explicit PluginLibrary(std::string path) : path_(std::move(path)) {}
  std::string path_;
  std::string sha256_;
  void* handle_ = nullptr;
  std::span<const moorsim_detector_plugin> types_;
  std::vector<std::vector<DetectorParameter>> parameters_;  // per type
};

/// A detector of `spec.type` from the plugin library at `path`, its parameters checked as
/// the registry checks the built-in ones (messages located at `key_path`). Throws
/// InputError for a library that does not load or a type it does not provide ("<key_path>:
/// plugin <path> has no detector 'x' (it has: a, b)"), and for a create() that fails.
std::unique_ptr<Detector> MakePluginDetector(const std::string& path, const DetectorSpec& spec,
                                             std::string_view key_path);

/// The libraries registered with RegisterPluginLibrary (detectors/registry.h), in order.
std::vector<std::shared_ptr<const PluginLibrary>> RegisteredPluginLibraries();

/// The registered library that provides `type`, or nullptr.
std::shared_ptr<const PluginLibrary> RegisteredPluginFor(std::string_view type);

/// The library a plugin detector came from; nullptr for a built-in detector.
std::shared_ptr<const PluginLibrary> PluginLibraryOf(const Detector& detector);

/// Gives a plugin detector the lines each hypothesis fails (failed_lines[h]: up to two
/// 1-based ids, 0 for none), which its next Reset passes on; call before Reset. Without it
/// a plugin is told moorsim's numbering without pairs (hypothesis h = line h). Detectors
/// that are not plugins are left as they are.
void SetPluginHypotheses(Detector& detector, std::vector<std::array<int, 2>> failed_lines);

}  // namespace moorsim::detectors
