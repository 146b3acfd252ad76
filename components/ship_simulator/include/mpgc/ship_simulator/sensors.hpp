// Sensor models, each with its own seeded generator (std::mt19937_64): own-ship navigation
// (GNSS position, heading, SOG/COG), AIS class A position reports (ITU-R M.1371 reporting
// intervals), and radar (range/bearing noise, detection probability, maximum range, clutter).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace mpgc::ship_simulator {

// True kinematics of one ship as the sensors see it.
struct Kinematics {
  double x = 0.0, y = 0.0;  // [m] NED
  double heading = 0.0;     // [rad]
  double cog = 0.0;         // [rad]
  double sog = 0.0;         // [m/s]
  double rot = 0.0;         // [rad/s] rate of turn, positive to starboard
};

struct NavSensorConfig {
  double period = 0.1;            // [s] output interval
  double sigma_position = 1.5;    // [m] GNSS horizontal error per axis (one sigma)
  double sigma_heading = 0.0017;  // [rad] gyro/GNSS compass error (~0.1 deg)
  double sigma_sog = 0.05;        // [m/s]
  double sigma_cog = 0.0087;      // [rad] (~0.5 deg)
  double sigma_rot = 0.0002;      // [rad/s]
  uint64_t seed = 1;
  void validate() const;
};

struct NavMeasurement {
  double x, y, heading, cog, sog, rot;  // [m] [m] [rad] [rad] [m/s] [rad/s]
};

class NavSensor {
 public:
  explicit NavSensor(const NavSensorConfig& c);
  NavMeasurement measure(const Kinematics& truth);
  const NavSensorConfig& config() const { return c_; }

 private:
  NavSensorConfig c_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n01_{0.0, 1.0};
};

// ITU-R M.1371-5 Annex 1 Table 1, class A reporting interval [s] for a ship moving at sog [m/s],
// changing course or not, with navigational status nav_status (1 at anchor, 5 moored).
double ais_class_a_interval(double sog, bool changing_course, uint8_t nav_status);

struct AisConfig {
  double sigma_position = 5.0;     // [m] position error per axis of the transmitting ship's GNSS
  double sigma_sog = 0.05;         // [m/s]
  double sigma_cog = 0.0087;       // [rad]
  double drop_probability = 0.0;   // [-] chance a report is lost (collisions, range)
  double turning_threshold = 0.0008727;  // [rad/s] |ROT| above which the ship "changes course" (~3 deg/min)
  uint64_t seed = 2;
  void validate() const;
};

struct AisMeasurement {
  uint32_t mmsi;
  double x, y, cog, sog, heading, rot;  // noisy position/velocity, true heading and ROT
  uint8_t nav_status;
  int64_t report_time_ns;
};

// One transmitter per target: decides when its next report is due and produces it.
class AisTransmitter {
 public:
  // The first report comes at a seeded random phase within the first interval.
  AisTransmitter(uint32_t mmsi, uint8_t nav_status, const AisConfig& c, uint64_t stream);
  // Returns true and fills `out` when a report is due at t_ns (and not dropped).
  bool poll(int64_t t_ns, const Kinematics& truth, AisMeasurement* out);
  int64_t next_due_ns() const { return next_ns_; }
  uint64_t dropped() const { return dropped_; }

 private:
  uint32_t mmsi_;
  uint8_t nav_status_;
  AisConfig c_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n01_{0.0, 1.0};
  int64_t next_ns_ = -1;
  uint64_t dropped_ = 0;
};

struct RadarConfig {
  double period = 2.5;                // [s] antenna rotation period
  double max_range = 12.0 * 1852.0;   // [m] instrumented range
  double min_range = 50.0;            // [m] blind zone around the antenna
  double sigma_range = 15.0;          // [m]
  double sigma_bearing = 0.0087;      // [rad] (~0.5 deg)
  double detection_probability = 0.95;  // [-] per target per sweep
  double clutter_per_scan = 0.5;      // [-] mean number of false contacts per sweep (Poisson)
  uint64_t seed = 3;
  void validate() const;
};

struct RadarContactOut {
  double range, bearing;  // [m] [rad]
  bool clutter;           // true for false alarms (evaluation only; not published)
};

class RadarSensor {
 public:
  explicit RadarSensor(const RadarConfig& c);
  // One sweep from the antenna at (ax, ay) over the given targets; contacts shuffled.
  std::vector<RadarContactOut> sweep(double ax, double ay, const std::vector<Kinematics>& targets);
  const RadarConfig& config() const { return c_; }

 private:
  RadarConfig c_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n01_{0.0, 1.0};
  std::uniform_real_distribution<double> u01_{0.0, 1.0};
};

}  // namespace mpgc::ship_simulator
