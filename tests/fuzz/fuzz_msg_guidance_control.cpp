// guidance_control's input topics as a stream of up to 32 samples: plan/path (any status value,
// empty to huge waypoint lists, NaN speeds and stamps) through to_plan and on_plan, and
// nav/own_state through check_nav, to_nav and on_nav (mpgc/guidance_control/validate.hpp), with a
// control cycle (step) after every sample at a time that moves forward, back or stays. The
// input's first bytes are also the speed.map parameter (parse_speed_map). on_plan and on_nav
// return reasons; expected exception: std::invalid_argument (parse_speed_map's documented error).
#include "msg.hpp"
#include "mpgc/guidance_control/autopilot.hpp"
#include "mpgc/guidance_control/guidance_control.hpp"
#include "mpgc/guidance_control/validate.hpp"

namespace gc = mpgc::guidance_control;
namespace msg = mpgc::msg;
namespace fz = mpgc::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fz::Reader r(data, size);
  gc::GuidanceControlParams p;
  const std::string map = r.str(48);
  fz::expect<std::invalid_argument>([&] { gc::parse_speed_map(map, p.speed); });
  gc::GuidanceController ctl(p);
  double t = 1000.0;
  for (int i = 0; i < 32 && !r.empty(); ++i) {
    t += (static_cast<double>(r.byte()) - 32.0) * 0.1;
    if (r.flag()) {
      (void)ctl.on_plan(gc::to_plan(fz::path(r, 8, 50000)), t);
    } else {
      const msg::NavState s = fz::nav_state(r);
      if (gc::check_nav(s).empty()) {
        bool rate_missing = false;
        (void)ctl.on_nav(gc::to_nav(s, &rate_missing), t);
      }
    }
    (void)ctl.step(t);
  }
  return 0;
}
