// The lockstep barrier of the simulator (no DDS): step k+1 may start only when every listed
// participant has acknowledged step k.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace mpgc::ship_simulator {

class LockstepBarrier {
 public:
  enum class Ack { Counted, Duplicate, Stale, Unknown };

  // Throws std::invalid_argument on an empty name or a duplicate.
  explicit LockstepBarrier(const std::vector<std::string>& participants);
  // Starts waiting for `step`; earlier acks are forgotten.
  void begin(uint64_t step);
  Ack ack(const std::string& component, uint64_t step);
  bool complete() const { return acked_.size() == participants_.size(); }
  std::size_t size() const { return participants_.size(); }
  uint64_t step() const { return step_; }
  std::vector<std::string> missing() const;
  bool empty() const { return participants_.empty(); }

 private:
  std::set<std::string> participants_;
  std::set<std::string> acked_;
  uint64_t step_ = 0;
};

// "a, b,c" -> {"a", "b", "c"} (blanks trimmed, empty items dropped).
std::vector<std::string> split_names(const std::string& text);

}  // namespace mpgc::ship_simulator
