#include "detectors/alarm_history.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "core/error.h"

namespace moorsim::detectors {

std::string_view AlarmEventName(AlarmEvent::Kind kind) {
  switch (kind) {
    case AlarmEvent::Kind::kOnset:
      return "onset";
    case AlarmEvent::Kind::kRevision:
      return "revision";
    case AlarmEvent::Kind::kEnd:
      return "end";
  }
  return "?";
}

void AlarmHistory::Update(double t, bool alarm, int hypothesis) {
  if (!std::isfinite(t) || t < time_) {
    std::ostringstream out;
    out << "alarm history: time " << t << " s after " << time_ << " s";
    throw ContractError(out.str());
  }
  time_ = t;
  if (alarm && !alarm_) {
    events_.push_back({t, AlarmEvent::Kind::kOnset, hypothesis});
  } else if (alarm && hypothesis != hypothesis_) {
    events_.push_back({t, AlarmEvent::Kind::kRevision, hypothesis});
  } else if (!alarm && alarm_) {
    events_.push_back({t, AlarmEvent::Kind::kEnd, 0});
  }
  alarm_ = alarm;
  hypothesis_ = alarm ? hypothesis : 0;
}

int AlarmHistory::OnsetsBefore(double t) const {
  return static_cast<int>(std::count_if(events_.begin(), events_.end(), [t](const AlarmEvent& e) {
    return e.kind == AlarmEvent::Kind::kOnset && e.time < t;
  }));
}

std::optional<AlarmEvent> AlarmHistory::FirstOnset(double t) const {
  const auto e = std::find_if(events_.begin(), events_.end(), [t](const AlarmEvent& e) {
    return e.kind == AlarmEvent::Kind::kOnset && e.time >= t;
  });
  if (e == events_.end()) return std::nullopt;
  return *e;
}

std::optional<double> AlarmHistory::FirstNamed(int hypothesis, double t) const {
  if (hypothesis == 0) return std::nullopt;
  // The verdict standing at t is that of the last event at or before t.
  const auto later =
      std::upper_bound(events_.begin(), events_.end(), t,
                       [](double time, const AlarmEvent& e) { return time < e.time; });
  if (later != events_.begin() && std::prev(later)->hypothesis == hypothesis) return t;
  for (auto e = later; e != events_.end(); ++e) {
    if (e->kind != AlarmEvent::Kind::kEnd && e->hypothesis == hypothesis) return e->time;
  }
  return std::nullopt;
}

double AlarmHistory::AlarmSeconds(double t0, double t1) const {
  double total = 0.0;
  bool standing = false;
  double since = 0.0;  // onset of the alarm standing
  for (const AlarmEvent& e : events_) {
    if (e.kind == AlarmEvent::Kind::kOnset) {
      standing = true;
      since = e.time;
    } else if (e.kind == AlarmEvent::Kind::kEnd && standing) {
      total += std::max(0.0, std::min(e.time, t1) - std::max(since, t0));
      standing = false;
    }
  }
  if (standing) total += std::max(0.0, t1 - std::max(since, t0));
  return total;
}

std::string SensorId::Name() const {
  switch (kind) {
    case Kind::kGnss:
      return "GNSS";
    case Kind::kGyro:
      return "gyro";
    case Kind::kPose:
      return "pose";
    case Kind::kCell:
      break;
  }
  std::string name = "cell ";  // built in steps: GCC 12 warns wrongly on "..." + string
  name += std::to_string(line);
  return name;
}

std::string_view SensorSymptomName(SensorSymptom symptom) {
  switch (symptom) {
    case SensorSymptom::kDisagrees:
      return "disagrees";
    case SensorSymptom::kFrozen:
      return "frozen";
    case SensorSymptom::kJump:
      return "jump";
    case SensorSymptom::kNoisy:
      return "noisy";
    case SensorSymptom::kSilent:
      return "silent";
  }
  return "disagrees";
}

void SensorFaultHistory::Update(double t, const std::vector<SensorFinding>& faulty) {
  if (faulty == current_) return;
  const auto contains = [](const std::vector<SensorFinding>& list, const SensorFinding& f) {
    return std::find(list.begin(), list.end(), f) != list.end();
  };
  for (const SensorFinding& f : current_) {
    if (contains(faulty, f)) continue;
    for (auto spell = spells_.rbegin(); spell != spells_.rend(); ++spell) {
      if (spell->sensor == f.sensor && spell->symptom == f.symptom && !spell->until) {
        spell->until = t;
        break;
      }
    }
  }
  for (const SensorFinding& f : faulty) {
    if (!contains(current_, f)) {
      spells_.push_back({.sensor = f.sensor, .symptom = f.symptom, .since = t, .until = {}});
    }
  }
  current_ = faulty;
}

}  // namespace moorsim::detectors
