#include "mpgc/situational_awareness/tracker.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>

#include "mpgc/geo/angles.hpp"
#include "mpgc/situational_awareness/assignment.hpp"

namespace mpgc::sa {

namespace {
constexpr double kNsToS = 1e-9;
// Durations compared in integer nanoseconds so that "30 s after" is exact.
int64_t to_ns(double s) { return std::llround(s * 1e9); }

void require(bool ok, const char* field, const std::string& what) {
  if (!ok) throw std::invalid_argument(std::string("TrackerParams.") + field + " " + what);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Disjoint sets over track and contact indices, for splitting a sweep into independent clusters.
struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};
}  // namespace

void TrackerParams::validate() const {
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(pos(process_noise), "process_noise", "must be finite and > 0 m^2/s^3");
  require(pos(ais_pos_std), "ais_pos_std", "must be finite and > 0 m");
  require(pos(ais_vel_std), "ais_vel_std", "must be finite and > 0 m/s");
  require(pos(init_vel_std), "init_vel_std", "must be finite and > 0 m/s");
  require(pos(gate), "gate", "must be finite and > 0");
  require(confirm_n >= 1 && confirm_n <= 32, "confirm_n", "must be in [1, 32]");
  require(confirm_m >= 1 && confirm_m <= confirm_n, "confirm_m", "must be in [1, confirm_n]");
  require(pos(coast_after), "coast_after", "must be finite and > 0 s");
  require(pos(delete_after) && delete_after >= coast_after, "delete_after", "must be finite and >= coast_after");
  require(pos(tentative_timeout), "tentative_timeout", "must be finite and > 0 s");
  require(pos(max_input_gap), "max_input_gap", "must be finite and > 0 s");
  require(std::isfinite(max_future) && max_future >= 0.0, "max_future", "must be finite and >= 0 s");
  require(std::isfinite(max_lag) && max_lag >= 0.0, "max_lag", "must be finite and >= 0 s");
  require(max_contacts >= 1, "max_contacts", "must be >= 1");
  require(max_tracks >= 1, "max_tracks", "must be >= 1");
  require(pos(max_speed), "max_speed", "must be finite and > 0 m/s");
}

const char* to_string(TrackStatus s) {
  switch (s) {
    case TrackStatus::kTentative: return "tentative";
    case TrackStatus::kConfirmed: return "confirmed";
    case TrackStatus::kCoasting: return "coasting";
  }
  return "?";
}

ConvertedContact convert_contact(double r, double b, double sr, double sb) {
  // Mo Longbin et al. 1998, eq. for the unbiased converted measurement and its covariance, with
  // x = north = r cos b and y = east = r sin b (the same form as the textbook x = r cos theta).
  const double lb = std::exp(-0.5 * sb * sb);  // E[cos(bearing noise)]
  const double lb4 = lb * lb * lb * lb;        // exp(-2 sb^2)
  const double c = std::cos(b), s = std::sin(b), c2 = std::cos(2 * b), s2 = std::sin(2 * b);
  const double r2 = r * r, k = 0.5 * (r2 + sr * sr);
  const double a = 1.0 / (lb * lb) - 2.0;
  ConvertedContact out;
  out.z = Vec2(r * c / lb, r * s / lb);
  out.R(0, 0) = a * r2 * c * c + k * (1.0 + lb4 * c2);
  out.R(1, 1) = a * r2 * s * s + k * (1.0 - lb4 * c2);
  out.R(0, 1) = out.R(1, 0) = a * r2 * c * s + k * lb4 * s2;
  return out;
}

Mat4 cv_transition(double dt) {
  Mat4 F = Mat4::Identity();
  F(0, 2) = F(1, 3) = dt;
  return F;
}

Mat4 cv_process_noise(double dt, double q) {
  const double a = std::fabs(dt);
  const double q11 = q * a * a * a / 3.0, q12 = q * a * a / 2.0 * (dt < 0 ? -1.0 : 1.0), q22 = q * a;
  Mat4 Q = Mat4::Zero();
  Q(0, 0) = Q(1, 1) = q11;
  Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = q12;
  Q(2, 2) = Q(3, 3) = q22;
  return Q;
}

Tracker::Tracker(const TrackerParams& p) : p_(p) { p_.validate(); }

void Tracker::refuse(std::vector<Rejection>& why, const std::string& key, const std::string& detail) {
  ++rejected_[key];
  why.push_back({key, detail});
}

bool Tracker::check_time(int64_t stamp_ns, int64_t receive_ns, const char* what, std::vector<Rejection>& why) {
  const std::string w(what);
  if (stamp_ns < 0) {
    refuse(why, w + ".bad_stamp", "stamp " + std::to_string(stamp_ns) + " ns is negative");
    return false;
  }
  // Differences in double: int64 stamps from anywhere (a fuzzed -9.2e18 ns) must not overflow.
  const double ahead = (static_cast<double>(stamp_ns) - static_cast<double>(receive_ns)) * kNsToS;
  if (ahead > p_.max_future) {
    refuse(why, w + ".future_stamp", "stamp is " + num(ahead) + " s after its reception");
    return false;
  }
  const double behind = (static_cast<double>(now_ns_) - static_cast<double>(stamp_ns)) * kNsToS;
  if (have_time_ && behind > p_.max_lag) {
    refuse(why, w + ".stale_stamp", "stamp is " + num(behind) + " s older than the newest");
    return false;
  }
  return true;
}

Track& Tracker::start_track(const Vec4& x, const Mat4& P, int64_t t_ns) {
  Track t;
  t.id = next_id_++;
  t.x = x;
  t.P = P;
  t.t_ns = t.born_ns = t.updated_ns = t_ns;
  t.outage_at_update_ns = outage_until(t_ns);
  t.length = std::nan("");
  tracks_.push_back(t);
  return tracks_.back();
}

void Tracker::update(Track& t, const Eigen::VectorXd& z, const Eigen::MatrixXd& H, const Eigen::MatrixXd& R,
                     int64_t t_ns) {
  const double dt = static_cast<double>(t_ns - t.t_ns) * kNsToS;
  Eigen::MatrixXd Hx = H, Rx = R;
  if (dt >= 0.0) {
    const Mat4 F = cv_transition(dt);
    t.x = F * t.x;
    t.P = F * t.P * F.transpose() + cv_process_noise(dt, p_.process_noise);
    t.t_ns = t_ns;
  } else {
    // Out-of-sequence measurement: map it to the current state through the backward transition
    // and add the process noise of the lag to its covariance (Bar-Shalom's approximate
    // retrodiction, neglecting the noise/state cross-correlation; fine for lags of seconds).
    Hx = H * cv_transition(dt);
    Rx = R + H * cv_process_noise(dt, p_.process_noise) * H.transpose();
  }
  const Eigen::MatrixXd S = Hx * t.P * Hx.transpose() + Rx;
  const Eigen::MatrixXd K = t.P * Hx.transpose() * S.ldlt().solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
  t.x += K * (z - Hx * t.x);
  const Mat4 IKH = Mat4::Identity() - K * Hx;
  t.P = IKH * t.P * IKH.transpose() + K * Rx * K.transpose();  // Joseph form: stays symmetric PSD
  t.P = 0.5 * (t.P + t.P.transpose());
  t.updated_ns = std::max(t.updated_ns, t_ns);
  t.outage_at_update_ns = outage_until(t.updated_ns);
}

void Tracker::note_input(int64_t stamp_ns) {
  if (have_input_ && stamp_ns <= last_input_ns_) return;  // out of sequence: inside a counted span
  if (have_input_) outage_ns_ = outage_until(stamp_ns);
  last_input_ns_ = stamp_ns;
  have_input_ = true;
}

int64_t Tracker::outage_until(int64_t t_ns) const {
  if (!have_input_ || t_ns <= last_input_ns_) return outage_ns_;
  // In double and saturated: stamps from anywhere (a fuzzed 9.2e18 ns) must not overflow int64.
  const double gap = static_cast<double>(t_ns) - static_cast<double>(last_input_ns_);
  const double total = static_cast<double>(outage_ns_) + std::max(0.0, gap - p_.max_input_gap * 1e9);
  return static_cast<int64_t>(std::min(total, 4.0e18));
}

std::vector<Rejection> Tracker::add_ais(const AisInput& r, int64_t receive_ns) {
  std::vector<Rejection> why;
  if (r.mmsi == 0 || r.mmsi > 999999999u) {
    refuse(why, "ais.bad_mmsi", "MMSI " + std::to_string(r.mmsi) + " is not a 9-digit identity");
    return why;
  }
  const std::string who = "MMSI " + std::to_string(r.mmsi);
  try {
    geo::check_latlon(r.lat, r.lon);
  } catch (const std::invalid_argument& e) {
    refuse(why, "ais.bad_position", who + ": " + e.what());
    return why;
  }
  if (std::isinf(r.cog) || std::isinf(r.sog) || r.sog < 0.0 || r.sog > p_.max_speed) {
    refuse(why, "ais.bad_velocity", who + ": SOG " + num(r.sog) + " m/s / COG " + num(r.cog) + " rad");
    return why;
  }
  if (!check_time(r.stamp_ns, receive_ns, "ais", why)) return why;
  if (!ned_) {
    refuse(why, "ais.no_origin", who + ": no local NED origin yet");
    return why;
  }
  const geo::NorthEast ne = ned_->to_ned({r.lat, r.lon});
  const bool has_vel = std::isfinite(r.sog) && std::isfinite(r.cog);

  auto it = std::find_if(tracks_.begin(), tracks_.end(), [&](const Track& t) { return t.mmsi == r.mmsi; });
  if (it != tracks_.end() && r.stamp_ns <= it->last_ais_ns) {
    refuse(why, "ais.out_of_order", who + ": report not newer than the last one used");
    return why;
  }
  now_ns_ = have_time_ ? std::max(now_ns_, r.stamp_ns) : r.stamp_ns;
  have_time_ = true;
  note_input(r.stamp_ns);

  Eigen::VectorXd z(has_vel ? 4 : 2);
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(z.size(), 4);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(z.size(), z.size());
  z(0) = ne.x;
  z(1) = ne.y;
  R(0, 0) = R(1, 1) = p_.ais_pos_std * p_.ais_pos_std;
  if (has_vel) {
    z(2) = r.sog * std::cos(r.cog);
    z(3) = r.sog * std::sin(r.cog);
    R(2, 2) = R(3, 3) = p_.ais_vel_std * p_.ais_vel_std;
  }

  Track* trk = it != tracks_.end() ? &*it : nullptr;
  if (!trk) {
    // A ship seen by radar before its first AIS report: fuse with the radar-only track whose
    // predicted position gates best (position only; the radar track's velocity may be poor).
    // Fixed-size 2x2 arithmetic: this runs over every radar-only track for each new MMSI.
    double best = p_.gate;
    const Vec2 zp(z(0), z(1));
    const Mat2 Rp = R.topLeftCorner(2, 2);
    for (Track& t : tracks_) {
      if (t.mmsi != 0) continue;
      const double dt = static_cast<double>(r.stamp_ns - t.t_ns) * kNsToS;
      const Mat4 F = cv_transition(dt);
      const Vec2 nu = zp - (F * t.x).head<2>();
      const Mat2 S = (F * t.P * F.transpose() + cv_process_noise(dt, p_.process_noise)).topLeftCorner<2, 2>() + Rp;
      const double d2 = nu.dot(S.inverse() * nu);
      if (d2 < best) best = d2, trk = &t;
    }
  }
  if (trk) {
    update(*trk, z, H, R, r.stamp_ns);
  } else {
    if (static_cast<int>(tracks_.size()) >= p_.max_tracks) {
      refuse(why, "ais.too_many_tracks", who + ": track table full");
      return why;
    }
    Vec4 x = Vec4::Zero();
    Mat4 P = Mat4::Zero();
    x.head<2>() = z.head(2);
    P(0, 0) = P(1, 1) = p_.ais_pos_std * p_.ais_pos_std;
    if (has_vel) x.tail<2>() = z.tail(2);
    const double sv = has_vel ? p_.ais_vel_std : p_.init_vel_std;
    P(2, 2) = P(3, 3) = sv * sv;
    trk = &start_track(x, P, r.stamp_ns);
  }
  trk->mmsi = r.mmsi;
  trk->sources |= kSourceAis;
  trk->last_ais_ns = r.stamp_ns;
  trk->status = TrackStatus::kConfirmed;  // an identified, self-reported ship needs no M-of-N
  if (std::isfinite(r.length) && r.length > 0.0) trk->length = r.length;
  delete_stale(now_ns_);
  return why;
}

std::vector<Rejection> Tracker::add_radar(const RadarScanInput& s, int64_t receive_ns) {
  std::vector<Rejection> why;
  if (!std::isfinite(s.antenna_x) || !std::isfinite(s.antenna_y) || !std::isfinite(s.max_range) ||
      s.max_range <= 0.0) {
    refuse(why, "radar.bad_scan", "antenna position or max_range not finite/positive");
    return why;
  }
  if (s.contacts.size() > static_cast<size_t>(p_.max_contacts)) {
    refuse(why, "radar.too_many_contacts",
           std::to_string(s.contacts.size()) + " contacts > max_contacts " + std::to_string(p_.max_contacts));
    return why;
  }
  if (!check_time(s.stamp_ns, receive_ns, "radar", why)) return why;
  now_ns_ = have_time_ ? std::max(now_ns_, s.stamp_ns) : s.stamp_ns;
  have_time_ = true;
  note_input(s.stamp_ns);

  // Valid contacts converted to absolute NED positions.
  std::vector<ConvertedContact> meas;
  meas.reserve(s.contacts.size());
  for (size_t k = 0; k < s.contacts.size(); ++k) {
    const RadarContactInput& c = s.contacts[k];
    if (!std::isfinite(c.range) || !std::isfinite(c.bearing) || !std::isfinite(c.range_std) ||
        !std::isfinite(c.bearing_std) || c.range <= 0.0 || c.range > 1.01 * s.max_range || c.range_std <= 0.0 ||
        c.bearing_std <= 0.0 || c.bearing_std > 0.5) {
      refuse(why, "radar.bad_contact",
             "contact " + std::to_string(k) + ": range " + num(c.range) + " m, bearing " + num(c.bearing) +
                 " rad, sigmas " + num(c.range_std) + " m / " + num(c.bearing_std) + " rad");
      continue;
    }
    ConvertedContact m = convert_contact(c.range, c.bearing, c.range_std, c.bearing_std);
    m.z += Vec2(s.antenna_x, s.antenna_y);
    meas.push_back(m);
  }

  // Predicted position and its covariance per track at the sweep time (forward or retrodicted).
  const int nt = static_cast<int>(tracks_.size()), nc = static_cast<int>(meas.size());
  std::vector<Vec2> zp(nt);
  std::vector<Mat2> Sp(nt);
  std::vector<char> covered(nt);
  for (int i = 0; i < nt; ++i) {
    const Track& t = tracks_[i];
    const double dt = static_cast<double>(s.stamp_ns - t.t_ns) * kNsToS;
    const Mat4 F = cv_transition(dt);
    const Mat4 P = F * t.P * F.transpose() + cv_process_noise(dt, p_.process_noise);
    zp[i] = (F * t.x).head<2>();
    Sp[i] = P.topLeftCorner<2, 2>();
    covered[i] = (zp[i] - Vec2(s.antenna_x, s.antenna_y)).norm() <= s.max_range;
  }
  // Gating: Mahalanobis distance of every (track, contact) pair, with a cheap Euclidean
  // pre-test (d2 >= |nu|^2 / trace(S) because trace(S) bounds the largest eigenvalue).
  std::vector<std::vector<std::pair<int, double>>> gated(nt);
  for (int i = 0; i < nt; ++i) {
    const double tr_t = Sp[i].trace();
    for (int j = 0; j < nc; ++j) {
      const Vec2 nu = meas[j].z - zp[i];
      const double n2 = nu.squaredNorm();
      if (n2 > p_.gate * (tr_t + meas[j].R.trace())) continue;
      const Mat2 S = Sp[i] + meas[j].R;
      const double d2 = nu.dot(S.inverse() * nu);
      if (d2 < p_.gate) gated[i].emplace_back(j, d2);
    }
  }
  // Global nearest neighbour per cluster of tracks and contacts linked by gates, in two stages:
  // confirmed tracks first, then tentative ones with what is left, so that a tentative track
  // born from one gate miss cannot steal the contacts of an established track.
  std::vector<int> assigned(nt, -1);
  std::vector<char> used(nc, 0);
  for (int stage = 0; stage < 2; ++stage) {
    UnionFind uf(nt + nc);
    std::vector<char> in_stage(nt, 0);
    for (int i = 0; i < nt; ++i) {
      in_stage[i] = (tracks_[i].status == TrackStatus::kTentative) == (stage == 1);
      if (!in_stage[i]) continue;
      for (const auto& [j, d2] : gated[i])
        if (!used[j]) uf.join(i, nt + j);
    }
    std::map<int, std::pair<std::vector<int>, std::vector<int>>> clusters;  // root -> (tracks, contacts)
    for (int i = 0; i < nt; ++i)
      if (in_stage[i] && !gated[i].empty()) clusters[uf.find(i)].first.push_back(i);
    for (int j = 0; j < nc; ++j)
      if (!used[j]) clusters[uf.find(nt + j)].second.push_back(j);
    for (auto& [root, members] : clusters) {
      const auto& [rows, cols] = members;
      if (rows.empty() || cols.empty()) continue;
      std::vector<std::vector<double>> cost(rows.size(), std::vector<double>(cols.size(), p_.gate));
      for (size_t r = 0; r < rows.size(); ++r)
        for (const auto& [j, d2] : gated[rows[r]]) {
          if (used[j]) continue;
          const size_t c = std::lower_bound(cols.begin(), cols.end(), j) - cols.begin();
          cost[r][c] = d2;
        }
      const std::vector<int> a = solve_assignment(cost, static_cast<int>(cols.size()), p_.gate);
      for (size_t r = 0; r < rows.size(); ++r)
        if (a[r] >= 0) assigned[rows[r]] = cols[a[r]];
    }
    for (int i = 0; i < nt; ++i)
      if (in_stage[i] && assigned[i] >= 0) used[assigned[i]] = 1;
  }

  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 4);
  for (int i = 0; i < nt; ++i) {
    Track& t = tracks_[i];
    if (assigned[i] >= 0) {
      const ConvertedContact& m = meas[assigned[i]];
      update(t, m.z, H, m.R, s.stamp_ns);
      t.sources |= kSourceRadar;
    }
    if (covered[i] || assigned[i] >= 0) {
      t.hit_history = (t.hit_history << 1) | (assigned[i] >= 0 ? 1u : 0u);
      t.sweeps = std::min(t.sweeps + 1, 32);
    }
  }
  // M-of-N confirmation of radar-only tentative tracks.
  const uint32_t window = p_.confirm_n >= 32 ? 0xffffffffu : ((1u << p_.confirm_n) - 1u);
  for (Track& t : tracks_) {
    if (t.status != TrackStatus::kTentative) continue;
    const int hits = static_cast<int>(std::bitset<32>(t.hit_history & window).count());
    if (hits >= p_.confirm_m) t.status = TrackStatus::kConfirmed;
  }
  // Contacts no track took start tentative tracks (position known, velocity unknown).
  for (int j = 0; j < nc; ++j) {
    if (used[j]) continue;
    if (static_cast<int>(tracks_.size()) >= p_.max_tracks) {
      refuse(why, "radar.too_many_tracks", "track table full, contact not tracked");
      continue;
    }
    Vec4 x = Vec4::Zero();
    x.head<2>() = meas[j].z;
    Mat4 P = Mat4::Zero();
    P.topLeftCorner<2, 2>() = meas[j].R;
    P(2, 2) = P(3, 3) = p_.init_vel_std * p_.init_vel_std;
    Track& t = start_track(x, P, s.stamp_ns);
    t.sources = kSourceRadar;
    t.hit_history = 1;
    t.sweeps = 1;
    if (p_.confirm_m <= 1) t.status = TrackStatus::kConfirmed;
  }
  // Tentative tracks that can no longer collect M hits in their last N sweeps are clutter.
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& t) {
                                 if (t.status != TrackStatus::kTentative) return false;
                                 const int n = std::min(t.sweeps, p_.confirm_n);
                                 const int misses =
                                     n - static_cast<int>(std::bitset<32>(t.hit_history & window).count());
                                 const bool dead = misses > p_.confirm_n - p_.confirm_m;
                                 deleted_ += dead;
                                 return dead;
                               }),
                tracks_.end());
  delete_stale(now_ns_);
  return why;
}

void Tracker::advance(int64_t stamp_ns) {
  if (have_time_ && stamp_ns <= now_ns_) return;
  now_ns_ = stamp_ns;
  have_time_ = true;
  delete_stale(now_ns_);
}

void Tracker::delete_stale(int64_t t_ns) {
  const auto before = tracks_.size();
  const int64_t outage = outage_until(t_ns);
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& t) {
                                 // Silence while the sensors reported: an outage is no evidence of absence.
                                 const double silent =
                                     (static_cast<double>(t_ns) - static_cast<double>(t.updated_ns)) -
                                     static_cast<double>(outage - t.outage_at_update_ns);
                                 return t.status == TrackStatus::kTentative ? silent > to_ns(p_.tentative_timeout)
                                                                            : silent > to_ns(p_.delete_after);
                               }),
                tracks_.end());
  deleted_ += before - tracks_.size();
}

std::vector<Track> Tracker::tracks_at(int64_t t_ns) const {
  t_ns = list_time(t_ns);
  std::vector<Track> out;
  out.reserve(tracks_.size());
  for (Track t : tracks_) {
    const double dt = static_cast<double>(t_ns - t.t_ns) * kNsToS;
    const Mat4 F = cv_transition(dt);
    t.x = F * t.x;
    t.P = F * t.P * F.transpose() + cv_process_noise(dt, p_.process_noise);
    t.t_ns = t_ns;
    if (t.status == TrackStatus::kConfirmed && t_ns - t.updated_ns > to_ns(p_.coast_after))
      t.status = TrackStatus::kCoasting;
    out.push_back(t);
  }
  return out;
}

}  // namespace mpgc::sa
