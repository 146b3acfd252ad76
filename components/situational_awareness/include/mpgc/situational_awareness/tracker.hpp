// Multi-target tracker of situational awareness: one constant-velocity Kalman filter per target
// in the local NED frame, fed by AIS reports (identified by MMSI) and radar sweeps (anonymous
// range/bearing contacts). No DDS, no clock: every input carries its own stamp, and the caller
// passes the time it received the input only so that stamps from the future can be refused.
//
//   sa::Tracker trk(params);
//   trk.set_origin(origin);                               // needed for AIS lat/lon
//   auto why = trk.add_ais(report, now_ns);               // empty: accepted; else Rejections
//   auto bad = trk.add_radar(scan, now_ns);               // one reason per refused contact
//   trk.advance(nav_stamp_ns);                            // drop tracks silent for too long
//   const int64_t t = trk.list_time(now_ns);              // now, or the newest stamp if later
//   for (const sa::Track& t : trk.tracks_at(t)) ...       // predicted to t
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpgc/geo/geodesy.hpp"

namespace mpgc::sa {

using Vec4 = Eigen::Matrix<double, 4, 1>;
using Mat4 = Eigen::Matrix<double, 4, 4>;
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

// One decoded AIS position report. NaN cog/sog mean "not available" (position-only update).
struct AisInput {
  uint32_t mmsi = 0;
  int64_t stamp_ns = 0;  // [ns] time of the position fix
  double lat = 0.0;      // [rad]
  double lon = 0.0;      // [rad]
  double cog = 0.0;      // [rad] course over ground, NaN if unavailable
  double sog = 0.0;      // [m/s] speed over ground, NaN if unavailable
  double length = 0.0;   // [m] NaN if unknown
};

struct RadarContactInput {
  double range = 0.0;        // [m]
  double bearing = 0.0;      // [rad] true bearing
  double range_std = 0.0;    // [m] one sigma
  double bearing_std = 0.0;  // [rad] one sigma
};

struct RadarScanInput {
  int64_t stamp_ns = 0;    // [ns] time of the sweep
  double antenna_x = 0.0;  // [m] north
  double antenna_y = 0.0;  // [m] east
  double max_range = 0.0;  // [m] instrumented range
  std::vector<RadarContactInput> contacts;
};

// Range/bearing converted to a north/east position with the unbiased converted-measurement
// covariance of Mo Longbin et al. (IEEE TAES 34(3), 1998): the plain polar-to-Cartesian
// conversion is biased by E[cos(b_noise)] = exp(-sb^2/2), and its linearised covariance
// J diag(sr^2, sb^2) J^T is too small at long range / large bearing error. Offsets are relative
// to the antenna.
struct ConvertedContact {
  Vec2 z;  // [m] (north, east) relative to the antenna
  Mat2 R;  // [m^2]
};
ConvertedContact convert_contact(double range, double bearing, double range_std, double bearing_std);

struct TrackerParams {
  double process_noise = 0.01;  // [m^2/s^3] PSD of the white acceleration per axis (CV model)
  double ais_pos_std = 10.0;    // [m] AIS position error (one sigma, per axis)
  double ais_vel_std = 0.25;    // [m/s] AIS velocity error from SOG/COG (one sigma, per axis)
  double init_vel_std = 8.0;    // [m/s] velocity sigma of a track started from one position
  double gate = 13.82;          // [-] Mahalanobis gate, chi-square 2 dof at 99.9 %
  int confirm_m = 3;            // [-] radar hits needed ...
  int confirm_n = 5;            // [-] ... within this many sweeps to confirm a tentative track
  double coast_after = 10.0;    // [s] a confirmed track without updates is reported as coasting
  double delete_after = 60.0;   // [s] a track without updates while the sensors report is deleted
  double tentative_timeout = 15.0;  // [s] a tentative track without updates is deleted (same rule)
  // [s] inputs further apart than this mark a sensor outage: the time beyond it does not count as
  // silence of any track (no sensor could have seen it), so tracks coast through a total outage
  // or a host cut, their covariance growing, and are there to take the first reports after it.
  double max_input_gap = 30.0;
  double max_future = 1.0;      // [s] stamps later than the receive time by more are refused
  double max_lag = 10.0;        // [s] reports older than the newest accepted stamp by more are refused
  int max_contacts = 5000;      // [-] a sweep with more contacts is refused as a whole
  int max_tracks = 5000;        // [-] no track is started beyond this many
  double max_speed = 40.0;      // [m/s] AIS SOG above this is refused (102.3 kn = "not available" is NaN)
  // Throws std::invalid_argument naming the bad field.
  void validate() const;
};

enum class TrackStatus { kTentative, kConfirmed, kCoasting };

// Why an input (or part of it) was not used: `reason` is a short counter key such as
// "ais.bad_mmsi" or "radar.future_stamp", `detail` says which value was wrong.
struct Rejection {
  std::string reason;
  std::string detail;
};

struct Track {
  uint32_t id = 0;          // stable for the life of the track, never reused
  uint32_t mmsi = 0;        // 0 until an AIS report has been associated
  uint32_t sources = 0;     // kSourceAis | kSourceRadar bits of what updated it
  Vec4 x = Vec4::Zero();    // [m, m, m/s, m/s] (north, east, v_north, v_east)
  Mat4 P = Mat4::Zero();    // covariance of x
  int64_t t_ns = 0;         // [ns] time of validity of x and P
  int64_t born_ns = 0;      // [ns] stamp of the first measurement
  int64_t updated_ns = 0;   // [ns] stamp of the newest measurement used
  int64_t last_ais_ns = 0;  // [ns] stamp of the newest AIS report used (0: none)
  int64_t outage_at_update_ns = 0;  // [ns] the tracker's outage total when it was last updated
  double length = 0.0;      // [m] NaN if unknown
  TrackStatus status = TrackStatus::kTentative;
  uint32_t hit_history = 0;  // radar sweeps, newest in bit 0: 1 = updated, 0 = missed
  int sweeps = 0;            // radar sweeps seen since birth (capped at 32)
};
inline constexpr uint32_t kSourceAis = 1;    // == msg::TRACK_SOURCE_AIS
inline constexpr uint32_t kSourceRadar = 2;  // == msg::TRACK_SOURCE_RADAR

// Constant-velocity model: transition and process noise (discretised white acceleration,
// Bar-Shalom "Estimation with Applications" §6.2.2) for a step dt (negative dt retrodicts).
Mat4 cv_transition(double dt);
Mat4 cv_process_noise(double dt, double q);

class Tracker {
 public:
  explicit Tracker(const TrackerParams& p);

  void set_origin(geo::LatLon origin) { ned_.emplace(origin); }
  bool has_origin() const { return ned_.has_value(); }

  // Each returns the reasons of what was refused (empty when all was used); every reason is
  // also counted in rejected(). `receive_ns` is the time the caller received the input.
  std::vector<Rejection> add_ais(const AisInput& r, int64_t receive_ns);
  std::vector<Rejection> add_radar(const RadarScanInput& s, int64_t receive_ns);
  // Moves the tracker's notion of "now" forward to a trusted sample stamp (e.g. own navigation)
  // and deletes the tracks that have been silent too long while the sensors reported (a gap
  // between inputs beyond max_input_gap is an outage and does not count). Earlier stamps are
  // ignored.
  void advance(int64_t stamp_ns);

  // The time a track list can be valid at: now_ns, or the newest stamp taken if that is later.
  // Stamps up to max_future ahead of the receive time are taken (another host's clock, or a sim
  // clock that reaches this host later than the samples stamped by it); a list stamped before
  // them would report negative since_update and predict filters backwards.
  int64_t list_time(int64_t now_ns) const { return have_time_ ? std::max(now_ns, now_ns_) : now_ns; }
  // Tracks predicted to t_ns (the stored filters are not changed), with status by t_ns. A t_ns
  // before list_time(t_ns) is raised to it: a filter is never predicted backwards.
  std::vector<Track> tracks_at(int64_t t_ns) const;
  const std::vector<Track>& tracks() const { return tracks_; }
  int64_t time_ns() const { return now_ns_; }

  const std::map<std::string, uint64_t>& rejected() const { return rejected_; }
  uint64_t deleted_count() const { return deleted_; }
  // [s] sensor outage (time between inputs beyond max_input_gap) up to t_ns, the current one included.
  double outage_s(int64_t t_ns) const { return static_cast<double>(outage_until(t_ns)) * 1e-9; }

 private:
  bool check_time(int64_t stamp_ns, int64_t receive_ns, const char* what, std::vector<Rejection>& why);
  void refuse(std::vector<Rejection>& why, const std::string& key, const std::string& detail);
  Track& start_track(const Vec4& x, const Mat4& P, int64_t t_ns);
  // Kalman update with a linear measurement z = H x (+ noise R) taken at t_ns: the state is
  // predicted forward to t_ns, or, when t_ns is older than the state (out-of-sequence), the
  // measurement is mapped to the current state by retrodiction.
  void update(Track& t, const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::MatrixXd& R,
              int64_t t_ns);
  void delete_stale(int64_t t_ns);
  // An accepted input stamped stamp_ns: a gap beyond max_input_gap since the last one is outage.
  void note_input(int64_t stamp_ns);
  int64_t outage_until(int64_t t_ns) const;

  TrackerParams p_;
  std::optional<geo::LocalNed> ned_;
  std::vector<Track> tracks_;
  uint32_t next_id_ = 1;
  int64_t now_ns_ = 0;
  bool have_time_ = false;
  int64_t last_input_ns_ = 0;  // [ns] newest accepted AIS or radar stamp
  bool have_input_ = false;
  int64_t outage_ns_ = 0;      // [ns] outage before last_input_ns_
  uint64_t deleted_ = 0;
  std::map<std::string, uint64_t> rejected_;
};

const char* to_string(TrackStatus s);

}  // namespace mpgc::sa
