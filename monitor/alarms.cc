#include "monitor/alarms.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace moorsim::monitor {

void AlarmBoard::Restore(std::vector<Alarm> listed) {
  listed_.clear();
  for (Alarm& alarm : listed) listed_[alarm.number] = std::move(alarm);
}

std::vector<AlarmChange> AlarmBoard::Update(const std::map<int, std::string>& holding, double now) {
  std::vector<AlarmChange> changes;
  for (auto it = listed_.begin(); it != listed_.end();) {
    Alarm& alarm = it->second;
    if (alarm.Active() && !holding.contains(alarm.number)) {
      alarm.cleared = now;
      changes.push_back({AlarmChange::Kind::kCleared, alarm});
    }
    if (!alarm.Listed()) {
      it = listed_.erase(it);
    } else {
      ++it;
    }
  }
  for (const auto& [number, text] : holding) {
    const auto found = listed_.find(number);
    if (found != listed_.end() && found->second.Active()) continue;
    // New, or back while the previous occurrence waits for its acknowledgement: a new
    // occurrence replaces it (its history is in the store).
    Alarm alarm;
    alarm.number = number;
    alarm.text = text;
    alarm.raised = now;
    listed_[number] = alarm;
    changes.push_back({AlarmChange::Kind::kRaised, alarm});
  }
  std::stable_sort(changes.begin(), changes.end(), [](const AlarmChange& a, const AlarmChange& b) {
    return a.alarm.number < b.alarm.number;
  });
  return changes;
}

std::optional<AlarmChange> AlarmBoard::Acknowledge(int number, double now, const std::string& by) {
  const auto found = listed_.find(number);
  if (found == listed_.end() || found->second.acknowledged) return std::nullopt;
  Alarm& alarm = found->second;
  alarm.acknowledged = now;
  alarm.acknowledged_by = by;
  AlarmChange change{AlarmChange::Kind::kAcknowledged, alarm};
  if (!alarm.Listed()) listed_.erase(found);
  return change;
}

void AlarmBoard::SetId(int number, std::int64_t id) {
  const auto found = listed_.find(number);
  if (found != listed_.end()) found->second.id = id;
}

std::string AlrSentence(const std::string& talker, const Alarm& alarm) {
  const double changed = alarm.cleared.value_or(alarm.acknowledged.value_or(alarm.raised));
  char number[8];
  std::snprintf(number, sizeof number, "%03d", alarm.number % 1000);
  std::vector<std::string> fields = {NmeaTimeOfDay(changed), number, alarm.Active() ? "A" : "V",
                                     alarm.acknowledged ? "A" : "V", ""};
  const std::string address = talker + "ALR";
  // $ + address + 5 commas + fields + *hh: what is left for the text.
  std::size_t used = 1 + address.size() + 3;
  for (std::size_t i = 0; i + 1 < fields.size(); ++i) used += 1 + fields[i].size();
  used += 1;
  const std::size_t room = kNmeaMaxLength > used ? kNmeaMaxLength - used : 0;
  std::string text;
  for (const char c : alarm.text) {
    if (text.size() >= room) break;
    const bool reserved = c < 0x20 || c > 0x7e || c == ',' || c == '*' || c == '$' || c == '!' ||
                          c == '\\' || c == '^' || c == '~';
    text += reserved ? ' ' : c;
  }
  fields.back() = text;
  return NmeaText('$', address, fields);
}

std::optional<int> AckNumber(const NmeaSentence& sentence, std::string* why) {
  if (sentence.type != "ACK") {
    if (why != nullptr) *why = "a " + sentence.type + " sentence, not ACK";
    return std::nullopt;
  }
  const std::string field = sentence.fields.empty() ? std::string() : sentence.fields[0];
  int number = 0;
  bool digits = !field.empty() && field.size() <= 3;
  for (const char c : field) {
    digits = digits && c >= '0' && c <= '9';
    if (digits) number = 10 * number + (c - '0');
  }
  if (!digits) {
    if (why != nullptr) *why = "ACK field 1 '" + field + "': not an alarm number 000-999";
    return std::nullopt;
  }
  return number;
}

}  // namespace moorsim::monitor
