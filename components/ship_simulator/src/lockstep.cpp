#include "mpgc/ship_simulator/lockstep.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace mpgc::ship_simulator {

LockstepBarrier::LockstepBarrier(const std::vector<std::string>& participants) {
  for (const auto& p : participants) {
    if (p.empty()) throw std::invalid_argument("lockstep participant name is empty");
    if (!participants_.insert(p).second) throw std::invalid_argument("lockstep participant '" + p + "' listed twice");
  }
}

void LockstepBarrier::begin(uint64_t step) {
  step_ = step;
  acked_.clear();
}

LockstepBarrier::Ack LockstepBarrier::ack(const std::string& component, uint64_t step, int64_t next_due_ns) {
  if (!participants_.count(component)) return Ack::Unknown;
  due_ns_[component] = std::max<int64_t>(next_due_ns, 0);  // a negative one: at once
  if (absent_.erase(component) > 0) {
    if (step == step_) acked_.insert(component);
    else acked_.erase(component);  // an old step's ack: it owes the current one
    return Ack::Readmitted;
  }
  if (step != step_) return Ack::Stale;
  return acked_.insert(component).second ? Ack::Counted : Ack::Duplicate;
}

bool LockstepBarrier::drop(const std::string& component) {
  if (!participants_.count(component) || absent_.count(component)) return false;
  absent_.insert(component);
  acked_.erase(component);
  return true;
}

std::vector<std::string> LockstepBarrier::drop_missing() {
  std::vector<std::string> dropped = missing();
  for (const auto& m : dropped) drop(m);
  return dropped;
}

bool LockstepBarrier::complete() const {
  for (const auto& p : participants_)
    if (!absent_.count(p) && !acked_.count(p)) return false;
  return true;
}

int64_t LockstepBarrier::due_ns() const {
  int64_t due = std::numeric_limits<int64_t>::max();
  for (const auto& p : participants_) {
    if (absent_.count(p)) continue;
    const auto it = due_ns_.find(p);
    due = std::min(due, it == due_ns_.end() ? 0 : it->second);
  }
  return due;
}

std::vector<std::string> LockstepBarrier::missing() const {
  std::vector<std::string> out;
  for (const auto& p : participants_)
    if (!absent_.count(p) && !acked_.count(p)) out.push_back(p);
  return out;
}

}  // namespace mpgc::ship_simulator
