#include "mpgc/ship_simulator/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_simulator {
namespace {
void in_range(double v, double lo, double hi, const std::string& name) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw std::invalid_argument(name + " = " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
}
constexpr double kKn = geo::kKnot;
}  // namespace

void NavSensorConfig::validate() const {
  in_range(period, 0.01, 60.0, "sensors.nav.period_s");
  in_range(sigma_position, 0.0, 1000.0, "sensors.nav.sigma_position_m");
  in_range(sigma_heading, 0.0, 1.0, "sensors.nav.sigma_heading");
  in_range(sigma_sog, 0.0, 10.0, "sensors.nav.sigma_sog_mps");
  in_range(sigma_cog, 0.0, 1.0, "sensors.nav.sigma_cog");
  in_range(sigma_rot, 0.0, 0.1, "sensors.nav.sigma_rot");
}

NavSensor::NavSensor(const NavSensorConfig& c) : c_(c), rng_(c.seed) { c_.validate(); }

NavMeasurement NavSensor::measure(const Kinematics& t) {
  // Draw order is fixed (x, y, heading, sog, cog, rot): the same seed gives the same samples.
  NavMeasurement m{};
  m.x = t.x + c_.sigma_position * n01_(rng_);
  m.y = t.y + c_.sigma_position * n01_(rng_);
  m.heading = geo::wrap_pi(t.heading + c_.sigma_heading * n01_(rng_));
  m.sog = std::max(0.0, t.sog + c_.sigma_sog * n01_(rng_));
  m.cog = geo::wrap_pi(t.cog + c_.sigma_cog * n01_(rng_));
  m.rot = t.rot + c_.sigma_rot * n01_(rng_);
  return m;
}

double ais_class_a_interval(double sog, bool changing_course, uint8_t nav_status) {
  const double kn = sog / kKn;
  if ((nav_status == 1 || nav_status == 5) && kn <= 3.0) return 180.0;  // at anchor / moored, not moving fast
  if (kn <= 14.0) return changing_course ? 10.0 / 3.0 : 10.0;
  if (kn <= 23.0) return changing_course ? 2.0 : 6.0;
  return 2.0;
}

void AisConfig::validate() const {
  in_range(sigma_position, 0.0, 1000.0, "sensors.ais.sigma_position_m");
  in_range(sigma_sog, 0.0, 10.0, "sensors.ais.sigma_sog_mps");
  in_range(sigma_cog, 0.0, 1.0, "sensors.ais.sigma_cog");
  in_range(drop_probability, 0.0, 1.0, "sensors.ais.drop_probability");
  in_range(turning_threshold, 0.0, 0.1, "sensors.ais.turning_threshold");
}

AisTransmitter::AisTransmitter(uint32_t mmsi, uint8_t nav_status, const AisConfig& c, uint64_t stream)
    : mmsi_(mmsi), nav_status_(nav_status), c_(c) {
  c_.validate();
  // One stream per transmitter derived from the seed (seed_seq mixes both words).
  std::seed_seq seq{static_cast<uint32_t>(c.seed), static_cast<uint32_t>(c.seed >> 32), static_cast<uint32_t>(stream),
                    static_cast<uint32_t>(mmsi)};
  rng_.seed(seq);
}

bool AisTransmitter::poll(int64_t t_ns, const Kinematics& t, AisMeasurement* out) {
  const double interval = ais_class_a_interval(t.sog, std::abs(t.rot) > c_.turning_threshold, nav_status_);
  const auto interval_ns = static_cast<int64_t>(std::llround(interval * 1e9));
  if (next_ns_ < 0) {  // random phase: transmitters are not synchronised
    next_ns_ = t_ns + static_cast<int64_t>(std::uniform_real_distribution<double>(0.0, 1.0)(rng_) * interval_ns);
  }
  // A shorter interval (ship started turning or sped up) applies at once.
  next_ns_ = std::min(next_ns_, t_ns + interval_ns);
  if (t_ns < next_ns_) return false;
  next_ns_ = t_ns + interval_ns;
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  AisMeasurement m{};
  m.mmsi = mmsi_;
  m.x = t.x + c_.sigma_position * n01_(rng_);
  m.y = t.y + c_.sigma_position * n01_(rng_);
  m.sog = std::max(0.0, t.sog + c_.sigma_sog * n01_(rng_));
  m.cog = geo::wrap_pi(t.cog + c_.sigma_cog * n01_(rng_));
  m.heading = geo::wrap_pi(t.heading);
  m.rot = t.rot;
  m.nav_status = nav_status_;
  m.report_time_ns = t_ns;
  if (u < c_.drop_probability) {
    ++dropped_;
    return false;
  }
  *out = m;
  return true;
}

void RadarConfig::validate() const {
  in_range(period, 0.1, 60.0, "sensors.radar.period_s");
  in_range(max_range, 100.0, 200000.0, "sensors.radar.max_range_m");
  in_range(min_range, 0.0, max_range, "sensors.radar.min_range_m");
  in_range(sigma_range, 0.0, 1000.0, "sensors.radar.sigma_range_m");
  in_range(sigma_bearing, 0.0, 0.5, "sensors.radar.sigma_bearing");
  in_range(detection_probability, 0.0, 1.0, "sensors.radar.detection_probability");
  in_range(clutter_per_scan, 0.0, 100.0, "sensors.radar.clutter_per_scan");
}

RadarSensor::RadarSensor(const RadarConfig& c) : c_(c), rng_(c.seed) { c_.validate(); }

std::vector<RadarContactOut> RadarSensor::sweep(double ax, double ay, const std::vector<Kinematics>& targets) {
  std::vector<RadarContactOut> out;
  for (const auto& t : targets) {
    const double range = std::hypot(t.x - ax, t.y - ay);
    // Draw for every target, in range or not, so one target's presence does not shift the
    // random stream of the others.
    const double u = u01_(rng_), er = n01_(rng_), eb = n01_(rng_);
    if (range > c_.max_range || range < c_.min_range || u >= c_.detection_probability) continue;
    out.push_back({std::max(0.0, range + c_.sigma_range * er),
                   geo::wrap_pi(geo::course_of(t.x - ax, t.y - ay) + c_.sigma_bearing * eb), false});
  }
  const int n_clutter = std::poisson_distribution<int>(c_.clutter_per_scan)(rng_);
  for (int i = 0; i < n_clutter; ++i) {
    // uniform over the annulus min_range..max_range
    const double a = c_.min_range * c_.min_range, b = c_.max_range * c_.max_range;
    const double r = std::sqrt(a + (b - a) * u01_(rng_));
    const double brg = geo::wrap_pi(2.0 * geo::kPi * u01_(rng_));
    out.push_back({r, brg, true});
  }
  std::shuffle(out.begin(), out.end(), rng_);
  return out;
}

}  // namespace mpgc::ship_simulator
