// mpgc_situational_awareness: nav/own_state + sensors/ais + sensors/radar -> sa/tracks and
// sa/encounters at a fixed rate. Seed 000 §2 "situational awareness"; the tracker and the COLREG
// geometry live in the library (its parameters and own-ship picture: node.hpp), this file only
// converts messages and wires topics.
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
#include "mpgc/situational_awareness/node.hpp"
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
  sa::NodeParams p;
  mpgc::rt::ParamSet ps;
  sa::declare(ps, p);
  std::optional<sa::Tracker> tracker;
  std::optional<msg::NavState> own;
  std::optional<mpgc::nav::JumpGate> own_jumps;
  mpgc::rt::SilenceWatch sensors;
  return mpgc::rt::run_component("situational_awareness", argc, argv, ps, [&](mpgc::rt::Component& c) {
    own_jumps.emplace(p.jump_gate());
    p.colreg = sa::colreg_params(p);  // p outlives setup: the callbacks read it
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
      // The list holds at the newest stamp taken when that is ahead of our clock (never negative
      // since_update); silence is still judged on our own clock.
      const int64_t heard = c.now_ns();
      const int64_t now = tracker->list_time(heard);
      const std::vector<sa::Track> tracks = tracker->tracks_at(now);
      msg::TrackList tl;
      tl.header = c.header();
      tl.header.stamp_ns = now;
      for (const auto& t : tracks) tl.tracks.push_back(to_msg(t, now));
      tracks_out.write(tl);
      c.count("cycles");
      for (const auto& v : sensors.at(heard)) c.set_problem(v.name, v.detail);
      const double age = own ? mpgc::rt::seconds_between(now, own->header.stamp_ns) : 0.0;
      const std::string own_problem = sa::own_problem(p, own.has_value(), age);
      c.set_problem("own", own_problem);
      if (!own_problem.empty()) return;
      const cr::ShipKinematics k = sa::own_at({own->x, own->y, own->sog, own->cog, own->heading,
                                               (own->valid_mask & msg::NAV_VELOCITY_VALID) != 0,
                                               (own->valid_mask & msg::NAV_HEADING_VALID) != 0},
                                              age);
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
