// situational_awareness's input topics as a stream of up to 48 samples (nav/own_state,
// sensors/ais, sensors/radar in any order, receive times moving forward or not), each through
// the component's validator and conversions (mpgc/situational_awareness/validate.hpp) and into
// the tracker as its main does (origin from the first fix, advance, add_ais, add_radar), with the
// published products computed after every sample: tracks_at and the COLREG encounters.
// The tracker refuses bad values by returning Rejections; expected exception: std::invalid_argument
// (origin_from_fix on an impossible fix, the COLREG geometry).
#include <optional>

#include "msg.hpp"
#include "mpgc/colreg/colreg.hpp"
#include "mpgc/situational_awareness/situation.hpp"
#include "mpgc/situational_awareness/tracker.hpp"
#include "mpgc/situational_awareness/validate.hpp"

namespace sa = mpgc::sa;
namespace msg = mpgc::msg;
namespace fz = mpgc::fuzz;
namespace cr = mpgc::colreg;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fz::Reader r(data, size);
  sa::TrackerParams tp;
  tp.max_contacts = 2000;
  tp.max_tracks = 500;
  sa::Tracker tracker(tp);
  if (r.flag()) tracker.set_origin({1.04, 0.19});
  cr::ColregParams cp;
  std::optional<msg::NavState> own;
  int64_t now = fz::kBaseNs;
  for (int i = 0; i < 48 && !r.empty(); ++i) {
    now += static_cast<int64_t>(r.byte()) * 20'000'000 - 1'000'000'000;
    switch (r.byte() % 4) {
      case 0: {
        const msg::NavState s = fz::nav_state(r);
        if (!sa::check_nav(s).empty()) break;
        if (!tracker.has_origin() && std::isfinite(s.lat) && std::isfinite(s.lon)) {
          fz::expect<std::invalid_argument, std::runtime_error>(
              [&] { tracker.set_origin(sa::origin_from_fix({s.lat, s.lon}, {s.x, s.y})); });
        }
        own = s;
        tracker.advance(s.header.stamp_ns);
        break;
      }
      case 1:
      case 2:
        (void)tracker.add_ais(sa::to_input(fz::ais(r)), now);
        break;
      default:
        (void)tracker.add_radar(sa::to_input(fz::radar(r, 8, 6000)), now);
        break;
    }
    const std::vector<sa::Track> tracks = tracker.tracks_at(now);
    if (!own) continue;
    // The main computes (now - stamp) in int64: signed overflow for a stamp near INT64_MIN (a
    // finding, README.md); here in double.
    const double dt = (static_cast<double>(now) - static_cast<double>(own->header.stamp_ns)) * 1e-9;
    const bool vel = own->valid_mask & msg::NAV_VELOCITY_VALID;
    const double vx = vel ? own->sog * std::cos(own->cog) : 0.0, vy = vel ? own->sog * std::sin(own->cog) : 0.0;
    const double hdg = (own->valid_mask & msg::NAV_HEADING_VALID) ? own->heading : std::nan("");
    const cr::ShipKinematics k{own->x + vx * dt, own->y + vy * dt, vx, vy, hdg};
    fz::expect<std::invalid_argument>([&] { (void)sa::encounters(k, tracks, cp); });
  }
  return 0;
}
