// Sensor faults injected into a simulated run (a scenario's `faults:`): what a real ship sees
// when its AIS receiver loses a target, its GNSS drops out or its position jumps. Applied to the
// sensors' outputs after the world sensed them, so the world itself (and the sensor noise
// streams) run on unchanged. No DDS, no clock: the caller passes the simulated time.
#pragma once

#include <cstdint>
#include <vector>

#include "mpgc/ship_simulator/world.hpp"

namespace mpgc::ship_simulator {

class SensorFaults {
 public:
  enum class Kind { kAisOutage, kGnssDropout, kPositionJump };
  struct Fault {
    Kind kind;
    int64_t from_ns, until_ns;  // [ns] simulated, [from, until)
    uint32_t mmsi = 0;          // kAisOutage
    double dx = 0, dy = 0;      // [m] kPositionJump
  };
  // Throws std::invalid_argument on an empty or reversed window or a non-finite offset.
  void add(const Fault& f);
  // What `out` becomes at time t: reports of targets in an outage removed, no navigation output in
  // a dropout, the position offset during a jump. Returns the number of outputs it changed.
  int apply(int64_t t_ns, SensorOutputs* out) const;
  bool empty() const { return faults_.empty(); }

 private:
  std::vector<Fault> faults_;
};

}  // namespace mpgc::ship_simulator
