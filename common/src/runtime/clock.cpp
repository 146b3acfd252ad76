#include "mpgc/runtime/clock.hpp"

#include <dds/dds.h>

namespace mpgc::rt {

// The single place the system clock is read.
int64_t WallClock::now_ns() const { return dds_time(); }

bool SimClock::advance_to(int64_t t_ns) {
  if (started_ && t_ns < now_ns_) return false;
  now_ns_ = t_ns;
  started_ = true;
  return true;
}

}  // namespace mpgc::rt
