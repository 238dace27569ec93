#include "simulation/shared_parts.h"

#include <map>
#include <mutex>

namespace moorsim::simulation::shared_parts_detail {

std::mutex& Mutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<std::string, std::shared_ptr<const void>>& Entries() {
  static std::map<std::string, std::shared_ptr<const void>> entries;
  return entries;
}

std::shared_ptr<const void> Find(const std::string& key) {
  const std::lock_guard<std::mutex> guard(Mutex());
  const auto it = Entries().find(key);
  return it == Entries().end() ? nullptr : it->second;
}

std::shared_ptr<const void> Store(const std::string& key, std::shared_ptr<const void> value) {
  const std::lock_guard<std::mutex> guard(Mutex());
  return Entries().emplace(key, std::move(value)).first->second;  // the first stored wins
}

}  // namespace moorsim::simulation::shared_parts_detail

namespace moorsim::simulation {

std::size_t SharedPartCount() {
  const std::lock_guard<std::mutex> guard(shared_parts_detail::Mutex());
  return shared_parts_detail::Entries().size();
}

}  // namespace moorsim::simulation
