// The lockstep barrier of the simulator (no DDS): step k+1 may start only when every present
// participant has acknowledged step k. A participant that died or hangs is dropped (the caller
// decides when: liveliness lost, or a bounded wait) and the run goes on without it; its next ack,
// from a restart, re-admits it.
#pragma once

#include <cstdint>
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
  Ack ack(const std::string& component, uint64_t step);
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

 private:
  std::set<std::string> participants_;
  std::set<std::string> absent_;
  std::set<std::string> acked_;
  uint64_t step_ = 0;
};

// {"a", "b"} -> "a, b".
template <class Names>
std::string join_names(const Names& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace mpgc::ship_simulator
