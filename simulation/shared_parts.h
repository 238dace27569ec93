// Read-only parts that do not change between the runs of a campaign, built once per process
// and shared by every run that asks for them with the same key (moorsim batch's threads):
// the WAMIT data (by file stem and options) and the detectors' hypothesis bank and GLR
// signatures (by everything in the scenario that determines them). Entries stay until the
// process ends; a campaign has a handful.
//
// Thread-safe. Two threads that ask for a missing entry at once may both build it; the first
// stored is kept and both get that one. Builds are deterministic, so a run gets the same
// bits from the cache as from building the part itself (tested: a campaign's row equals the
// same run done alone).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <typeinfo>

namespace moorsim::simulation {

namespace shared_parts_detail {
std::shared_ptr<const void> Find(const std::string& key);
std::shared_ptr<const void> Store(const std::string& key, std::shared_ptr<const void> value);
}  // namespace shared_parts_detail

/// The entry of type T under `key`, built by `build()` (returning a T) if absent.
template <class T, class Build>
std::shared_ptr<const T> SharedPart(const std::string& key, Build build) {
  std::string typed = typeid(T).name();
  typed += '\n';
  typed += key;
  if (std::shared_ptr<const void> found = shared_parts_detail::Find(typed)) {
    return std::static_pointer_cast<const T>(found);
  }
  std::shared_ptr<const void> built = std::make_shared<const T>(build());
  return std::static_pointer_cast<const T>(shared_parts_detail::Store(typed, std::move(built)));
}

/// How many entries the cache holds (of every type), for tests and diagnostics.
std::size_t SharedPartCount();

}  // namespace moorsim::simulation
