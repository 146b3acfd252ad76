// The lockstep barrier of the simulator (no DDS): the step after a Clock may start only when every
// present participant has acknowledged that Clock. A participant that died or hangs is dropped (the
// caller decides when: liveliness lost, or a bounded wait) and the run goes on without it; its next
// ack, from a restart, re-admits it. Each ack says when the participant's next timer is due; the
// steps before the earliest of them run without a Clock (clock_due).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace mpgc::ship_simulator {

class LockstepBarrier {
 public:
  enum class Ack { Counted, Duplicate, Stale, Unknown, Readmitted };

  // Throws std::invalid_argument on an empty name or a duplicate.
  explicit LockstepBarrier(const std::vector<std::string>& participants);
  // Starts waiting for `step`; earlier acks are forgotten.
  void begin(uint64_t step);
  // An absent participant's ack re-admits it (Readmitted): counted when it is for the current step,
  // else expected again from the next step on.
  // `next_due_ns`: when the participant's next timer is due (its latest ack's counts).
  Ack ack(const std::string& component, uint64_t step, int64_t next_due_ns = 0);
  // Stops waiting for a present participant; false when it is unknown or already absent.
  bool drop(const std::string& component);
  // Drops every missing participant (a dead or hung one); returns them.
  std::vector<std::string> drop_missing();
  bool complete() const;
  std::size_t size() const { return participants_.size(); }
  std::size_t present() const { return participants_.size() - absent_.size(); }
  uint64_t step() const { return step_; }
  // Present participants that have not acknowledged the current step.
  std::vector<std::string> missing() const;
  const std::set<std::string>& absent() const { return absent_; }
  bool empty() const { return participants_.empty(); }
  // [ns] the earliest next timer of the present participants (0 for one that has not acked yet).
  int64_t due_ns() const;

 private:
  std::set<std::string> participants_;
  std::set<std::string> absent_;
  std::set<std::string> acked_;
  std::map<std::string, int64_t> due_ns_;
  uint64_t step_ = 0;
};

// At most this many steps in a row without a Clock: a state topic's reader keeps 8 samples
// (QosProfile::deterministic) until the next Clock hands them over.
inline constexpr uint64_t kMaxStepsWithoutClock = 4;

// Whether the step just integrated, at t_ns, is published with a Clock (and waits for the acks):
// when a participant's timer is due at it, or at the next step (so that what a participant wrote
// from an input callback on the steps without a Clock has arrived before any timer acts on it), or
// after kMaxStepsWithoutClock steps without one.
inline bool clock_due(int64_t t_ns, int64_t step_ns, int64_t due_ns, uint64_t steps_without_clock) {
  return t_ns >= due_ns - step_ns || steps_without_clock >= kMaxStepsWithoutClock;
}

// {"a", "b"} -> "a, b".
template <class Names>
std::string join_names(const Names& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace mpgc::ship_simulator
