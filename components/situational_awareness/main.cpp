// mpgc_situational_awareness: nav/own_state + sensors/ais + sensors/radar -> sa/tracks and
// sa/encounters at a fixed rate. Seed 000 §2 "situational awareness"; the tracker and the COLREG
// geometry live in the library, this file only converts messages and wires topics.
#include <cmath>
#include <optional>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/colreg/msg.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/runtime/silence_watch.hpp"
#include "mpgc/situational_awareness/situation.hpp"
#include "mpgc/situational_awareness/tracker.hpp"
#include "mpgc/topics.hpp"
#include "mpgc/situational_awareness/validate.hpp"

namespace sa = mpgc::sa;
namespace cr = mpgc::colreg;
namespace msg = mpgc::msg;
namespace geo = mpgc::geo;

namespace {

using mpgc::sa::check_nav;
using mpgc::sa::to_input;

struct Params {
  double period = 0.5;          // [s] sa/tracks and sa/encounters period
  std::string origin_source;    // "nav": from the first valid NavState fix; "param": origin.lat/lon
  double origin_lat = 0.0;      // [deg]
  double origin_lon = 0.0;      // [deg]
  double own_timeout = 5.0;     // [s] no encounters from an own state older than this
  double ais_timeout = 30.0;    // [s] sensors/ais heard, then silent this long: health DEGRADED
  double radar_timeout = 10.0;  // [s] sensors/radar likewise
  mpgc::nav::JumpGateParams jumps;  // own position jumps (timeout: own_timeout)
  sa::TrackerParams tracker;
  cr::ColregParams colreg;
  double abaft_beam_deg = 22.5, head_on_sector_deg = 22.5, overtake_deg = 67.5, crossing_deg = 5.0;  // [deg]
};

void declare(mpgc::rt::ParamSet& ps, Params& p) {
  const double inf = 1e12;  // ParamSet refuses infinities; a huge bound is "no limit"
  ps.add("period", &p.period, 0.5, "s", 0.01, 60.0, "publication period of sa/tracks and sa/encounters");
  ps.add("origin.source", &p.origin_source, "nav", "local NED origin: from the first NavState fix, or origin.lat/lon",
         {"nav", "param"});
  ps.add("origin.lat", &p.origin_lat, 0.0, "deg", -90.0, 90.0, "NED origin latitude (origin.source = param)");
  ps.add("origin.lon", &p.origin_lon, 0.0, "deg", -180.0, 180.0, "NED origin longitude (origin.source = param)");
  ps.add("own.timeout", &p.own_timeout, 5.0, "s", 0.1, 3600.0, "no encounters from an older own state");
  mpgc::nav::declare_params(ps, &p.jumps);
  ps.add("sensors.ais_timeout", &p.ais_timeout, 30.0, "s", 1.0, 3600.0,
         "AIS reports heard, then none this long: degraded (class B reports every 30 s, class A 2-10 s)");
  ps.add("sensors.radar_timeout", &p.radar_timeout, 10.0, "s", 1.0, 3600.0,
         "radar scans heard, then none this long: degraded (a scan every 2-3 s)");
  auto& t = p.tracker;
  ps.add("tracker.process_noise", &t.process_noise, 0.01, "m^2/s^3", 1e-8, 100.0, "CV white-acceleration PSD");
  ps.add("tracker.ais_pos_std", &t.ais_pos_std, 10.0, "m", 0.1, 1000.0, "AIS position sigma per axis");
  ps.add("tracker.ais_vel_std", &t.ais_vel_std, 0.25, "m/s", 0.01, 10.0, "AIS velocity sigma per axis");
  ps.add("tracker.init_vel_std", &t.init_vel_std, 8.0, "m/s", 0.1, 100.0, "velocity sigma of a new radar track");
  ps.add("tracker.gate", &t.gate, 13.82, "-", 1.0, 100.0, "Mahalanobis gate (chi2 2 dof; 13.82 = 99.9 %)");
  ps.add("tracker.confirm_m", &t.confirm_m, 3, "-", 1, 32, "M of M-of-N confirmation");
  ps.add("tracker.confirm_n", &t.confirm_n, 5, "-", 1, 32, "N of M-of-N confirmation");
  ps.add("tracker.coast_after", &t.coast_after, 10.0, "s", 0.1, 3600.0, "confirmed track reported coasting after");
  ps.add("tracker.delete_after", &t.delete_after, 60.0, "s", 0.1, 3600.0, "track deleted when silent this long");
  ps.add("tracker.tentative_timeout", &t.tentative_timeout, 15.0, "s", 0.1, 3600.0, "tentative track deleted after");
  ps.add("tracker.max_future", &t.max_future, 1.0, "s", 0.0, 3600.0, "stamps further in the future are refused");
  ps.add("tracker.max_lag", &t.max_lag, 10.0, "s", 0.0, 3600.0, "stamps older than the newest by more are refused");
  ps.add("tracker.max_contacts", &t.max_contacts, 5000, "-", 1, 1000000, "larger radar sweeps are refused");
  ps.add("tracker.max_tracks", &t.max_tracks, 5000, "-", 1, 1000000, "no tracks are started beyond this");
  ps.add("tracker.max_speed", &t.max_speed, 40.0, "m/s", 1.0, 200.0, "faster AIS SOG is refused");
  ps.add("colreg.abaft_beam", &p.abaft_beam_deg, 22.5, "deg", 0.0, 90.0, "overtaking: abaft the beam by more (rule 13)");
  ps.add("colreg.head_on_sector", &p.head_on_sector_deg, 22.5, "deg", 0.0, 90.0, "head-on half sector (seed 000; DNV uses 5)");
  ps.add("colreg.overtake_aspect", &p.overtake_deg, 67.5, "deg", 0.0, 180.0, "DNV theta13Criteria");
  ps.add("colreg.crossing_aspect", &p.crossing_deg, 5.0, "deg", 0.0, 90.0, "DNV theta15Criteria");
  ps.add("colreg.d_colreg", &p.colreg.d_colreg, 6.0 * geo::kNauticalMile, "m", 1.0, inf, "COLREG zone radius");
  ps.add("colreg.cpa_risk", &p.colreg.cpa_risk, 0.7 * geo::kNauticalMile, "m", 1.0, inf, "risk if CPA closer");
  ps.add("colreg.tcpa_max", &p.colreg.tcpa_max, 1800.0, "s", 1.0, inf, "risk if CPA sooner");
}

msg::Track to_msg(const sa::Track& t, int64_t now_ns) {
  msg::Track m;
  m.id = t.id;
  m.mmsi = t.mmsi;
  m.sources = t.sources;
  m.x = t.x(0);
  m.y = t.x(1);
  m.vx = t.x(2);
  m.vy = t.x(3);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.cov[r * 4 + c] = t.P(r, c);
  m.age = (now_ns - t.born_ns) * 1e-9;
  m.since_update = (now_ns - t.updated_ns) * 1e-9;
  m.length = t.length;
  m.status = t.status == sa::TrackStatus::kTentative   ? msg::TrackStatus::TRACK_TENTATIVE
             : t.status == sa::TrackStatus::kConfirmed ? msg::TrackStatus::TRACK_CONFIRMED
                                                       : msg::TrackStatus::TRACK_COASTING;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  mpgc::rt::ParamSet ps;
  declare(ps, p);
  std::optional<sa::Tracker> tracker;
  std::optional<msg::NavState> own;
  std::optional<mpgc::nav::JumpGate> own_jumps;
  mpgc::rt::SilenceWatch sensors;
  return mpgc::rt::run_component("situational_awareness", argc, argv, ps, [&](mpgc::rt::Component& c) {
    own_jumps.emplace(mpgc::nav::JumpGateParams{p.jumps.max_speed, p.jumps.margin, p.own_timeout});
    p.colreg.abaft_beam = geo::deg2rad(p.abaft_beam_deg);
    p.colreg.head_on_sector = geo::deg2rad(p.head_on_sector_deg);
    p.colreg.overtake_aspect = geo::deg2rad(p.overtake_deg);
    p.colreg.crossing_aspect = geo::deg2rad(p.crossing_deg);
    p.colreg.validate();
    tracker.emplace(p.tracker);  // validates the tracker parameters
    if (p.origin_source == "param") tracker->set_origin({geo::deg2rad(p.origin_lat), geo::deg2rad(p.origin_lon)});

    auto& tracks_out = c.publisher<msg::TrackList>(mpgc::topics::kTracks, mpgc::dds::QosProfile::state(3 * p.period));
    auto& enc_out =
        c.publisher<msg::EncounterList>(mpgc::topics::kEncounters, mpgc::dds::QosProfile::state(3 * p.period));
    // Captured by value below: this lambda is a local of setup, which returns before spin().
    auto report = [&c](const char* topic, const std::vector<sa::Rejection>& why) {
      for (const auto& r : why) c.reject(r.reason, std::string(topic) + ": " + r.detail);
    };

    c.subscribe<msg::NavState>(
        mpgc::topics::kOwnState, mpgc::dds::QosProfile::state(),
        [&](const msg::NavState& s) {
          if (!tracker->has_origin() && std::isfinite(s.lat) && std::isfinite(s.lon)) {
            try {
              const geo::LatLon o = sa::origin_from_fix({s.lat, s.lon}, {s.x, s.y});
              tracker->set_origin(o);
              c.log().info("NED origin from own fix: {:.7f} {:.7f} deg", geo::rad2deg(o.lat), geo::rad2deg(o.lon));
            } catch (const std::exception& e) {
              c.reject("nav.bad_fix", e.what());
            }
          }
          std::string jump;
          if (own_jumps->check(s.x, s.y, s.header.stamp_ns, &jump) != mpgc::nav::JumpGate::Verdict::kTaken) {
            c.reject("nav.jump", jump);  // encounters from the last good state until it is stale
            return;
          }
          own = s;
          tracker->advance(s.header.stamp_ns);
        },
        check_nav);
    // A sensor that falls silent is said on health (the tracks coast on the other one, then age out).
    sensors.expect(mpgc::topics::kAis, p.ais_timeout);
    sensors.expect(mpgc::topics::kRadar, p.radar_timeout);
    c.subscribe<msg::AisReport>(mpgc::topics::kAis, mpgc::dds::QosProfile::command(64),
                                [&, report](const msg::AisReport& r) {
                                  sensors.heard(mpgc::topics::kAis, c.now_ns());
                                  report(mpgc::topics::kAis, tracker->add_ais(to_input(r), c.now_ns()));
                                });
    c.subscribe<msg::RadarScan>(mpgc::topics::kRadar, mpgc::dds::QosProfile::state(),
                                [&, report](const msg::RadarScan& s) {
                                  sensors.heard(mpgc::topics::kRadar, c.now_ns());
                                  report(mpgc::topics::kRadar, tracker->add_radar(to_input(s), c.now_ns()));
                                });

    c.every(p.period, [&] {
      const int64_t now = c.now_ns();
      const std::vector<sa::Track> tracks = tracker->tracks_at(now);
      msg::TrackList tl;
      tl.header = c.header();
      tl.header.stamp_ns = now;
      for (const auto& t : tracks) tl.tracks.push_back(to_msg(t, now));
      tracks_out.write(tl);
      c.count("cycles");
      for (const auto& v : sensors.at(now)) c.set_problem(v.name, v.detail);
      const bool own_ok = own && mpgc::rt::seconds_between(now, own->header.stamp_ns) <= p.own_timeout;
      c.set_problem("own", own_ok ? "" : own ? "own state stale" : "no own state yet");
      if (!own_ok) return;
      // Own ship predicted to now at its velocity over ground.
      const double dt = mpgc::rt::seconds_between(now, own->header.stamp_ns);
      const bool vel = own->valid_mask & msg::NAV_VELOCITY_VALID;
      const double vx = vel ? own->sog * std::cos(own->cog) : 0.0, vy = vel ? own->sog * std::sin(own->cog) : 0.0;
      const double hdg = (own->valid_mask & msg::NAV_HEADING_VALID) ? own->heading : std::nan("");
      const cr::ShipKinematics k{own->x + vx * dt, own->y + vy * dt, vx, vy, hdg};
      msg::EncounterList el;
      el.header = tl.header;
      for (const auto& e : sa::encounters(k, tracks, p.colreg)) {
        msg::Encounter m;
        m.track_id = e.track_id;
        m.mmsi = e.mmsi;
        m.type = to_msg(e.assessment.type);
        m.role = to_msg(e.assessment.role);
        m.cpa = e.assessment.cpa.dcpa;
        m.tcpa = e.assessment.cpa.tcpa;
        m.range = e.assessment.cpa.range;
        m.bearing = e.bearing;
        el.encounters.push_back(m);
      }
      enc_out.write(el);
    });
  });
}
