// The one way components read time: the wall clock, or the simulator's `clock` topic.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>

namespace mpgc::rt {

// [ns] stamps from here on are wall-clock times (2001 onwards), not simulated time (< 3 years).
inline constexpr int64_t kWallStamp_ns = 1'000'000'000'000'000'000;
inline bool wall_clock_stamp(int64_t t_ns) { return t_ns >= kWallStamp_ns; }

// [ns] later - earlier for stamps that come off the bus, saturated at the int64 range (a stamp
// near INT64_MIN would overflow the plain subtraction: undefined behaviour).
inline int64_t ns_between(int64_t later_ns, int64_t earlier_ns) {
  int64_t d;
  if (!__builtin_sub_overflow(later_ns, earlier_ns, &d)) return d;
  return later_ns > earlier_ns ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
}
// [s] the same in seconds (the components' `(now - stamp) * 1e-9`, bit for bit where it did not overflow).
inline double seconds_between(int64_t later_ns, int64_t earlier_ns) {
  return static_cast<double>(ns_between(later_ns, earlier_ns)) * 1e-9;
}

class Clock {
 public:
  virtual ~Clock() = default;
  virtual int64_t now_ns() const = 0;  // [ns] wall: since the Unix epoch; simulated: since run start
  virtual bool simulated() const = 0;
  double now_s() const { return static_cast<double>(now_ns()) * 1e-9; }
};

class WallClock final : public Clock {
 public:
  int64_t now_ns() const override;
  bool simulated() const override { return false; }
};

// Simulated time, advanced by the executor from `clock` samples; never goes backwards.
class SimClock final : public Clock {
 public:
  int64_t now_ns() const override { return now_ns_; }
  bool simulated() const override { return true; }
  bool started() const { return started_; }
  // Returns false (and keeps the time) when t_ns is earlier than the current time.
  bool advance_to(int64_t t_ns);

 private:
  std::atomic<int64_t> now_ns_{0};  // read by other threads (tests, loggers)
  bool started_ = false;
};

}  // namespace mpgc::rt
