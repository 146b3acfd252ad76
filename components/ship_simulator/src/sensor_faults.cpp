#include "mpgc/ship_simulator/sensor_faults.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mpgc::ship_simulator {

void SensorFaults::add(const Fault& f) {
  if (!(f.until_ns > f.from_ns)) throw std::invalid_argument("sensor fault: the window must end after it begins");
  if (!std::isfinite(f.dx) || !std::isfinite(f.dy)) throw std::invalid_argument("sensor fault: non-finite position offset");
  faults_.push_back(f);
}

int SensorFaults::apply(int64_t t_ns, SensorOutputs* out) const {
  int changed = 0;
  for (const auto& f : faults_) {
    if (t_ns < f.from_ns || t_ns >= f.until_ns) continue;
    switch (f.kind) {
      case Kind::kAisOutage: {
        const auto n = out->ais.size();
        out->ais.erase(std::remove_if(out->ais.begin(), out->ais.end(), [&](const AisMeasurement& a) { return a.mmsi == f.mmsi; }),
                       out->ais.end());
        changed += static_cast<int>(n - out->ais.size());
        break;
      }
      case Kind::kGnssDropout:
        if (out->nav) out->nav.reset(), ++changed;
        break;
      case Kind::kPositionJump:
        if (out->nav) out->nav->x += f.dx, out->nav->y += f.dy, ++changed;
        break;
    }
  }
  return changed;
}

}  // namespace mpgc::ship_simulator
