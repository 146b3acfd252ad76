#include "mpgc/ship_simulator/helmsman.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mpgc::ship_simulator {
namespace {

void positive(double v, double hi, const std::string& what) {
  if (!std::isfinite(v) || !(v > 0.0) || v > hi)
    throw std::invalid_argument("helmsman." + what + " must be in (0, " + std::to_string(hi) + "]");
}

// Passed and clear, as a master judges it: the other ship is abaft the beam and the range opens,
// or it is beyond the range where ships are assessed at all.
bool passed_and_clear(const colreg::Assessment& a, double d_colreg) {
  return a.cpa.range > d_colreg || (std::abs(a.beta) > 0.5 * geo::kPi && a.cpa.tcpa <= 0.0);
}

}  // namespace

const char* to_string(HelmMode m) {
  switch (m) {
    case HelmMode::kRoute: return "route";
    case HelmMode::kGiveWay: return "give-way";
    case HelmMode::kStandOn: return "stand-on";
    case HelmMode::kActAlone: return "act-alone";
  }
  return "?";
}

void HelmsmanParams::validate() const {
  positive(d_colreg, 1.0e6, "d_colreg [m]");
  positive(cpa_risk, d_colreg, "cpa_risk [m] (at most d_colreg)");
  positive(tcpa_max, 1.0e5, "tcpa_max [s]");
  // Rule 8(b): below 10 deg an alteration is not readily apparent; beyond 90 deg the "alteration
  // to starboard" would be a turn away of another kind.
  if (!std::isfinite(alteration) || alteration < geo::deg2rad(10.0) || alteration > geo::deg2rad(90.0))
    throw std::invalid_argument("helmsman.alteration [deg] must be in [10, 90]");
  if (!std::isfinite(max_alteration) || max_alteration < alteration || max_alteration > geo::deg2rad(120.0))
    throw std::invalid_argument("helmsman.max_alteration [deg] must be in [alteration, 120]");
  if (!std::isfinite(alteration_step) || alteration_step < geo::deg2rad(1.0) || alteration_step > geo::deg2rad(45.0))
    throw std::invalid_argument("helmsman.alteration_step [deg] must be in [1, 45]");
  positive(act_alone_range, d_colreg, "act_alone_range [m] (at most d_colreg)");
  positive(act_alone_cpa, cpa_risk, "act_alone_cpa [m] (at most cpa_risk)");
}

colreg::ColregParams HelmsmanParams::colreg_params() const {
  colreg::ColregParams c;
  c.d_colreg = d_colreg;
  c.cpa_risk = cpa_risk;
  c.tcpa_max = tcpa_max;
  return c;
}

Helmsman::Helmsman(HelmsmanParams p) : p_(p) {
  p_.validate();
  cp_ = p_.colreg_params();
  cp_.validate();
}

double Helmsman::avoidance_course(const colreg::ShipKinematics& me, double speed,
                                  const std::vector<SeenShip>& others) const {
  // The smallest alteration from the first readily apparent one up that lets every ship it acts
  // for pass at cpa_risk or more (rule 8(d)); max_alteration when none does.
  for (double alt = p_.alteration; alt <= p_.max_alteration + 1e-9; alt += p_.alteration_step) {
    const auto mine = colreg::ShipKinematics::from_course(me.x, me.y, base_course_ + alt, speed);
    bool ok = true;
    for (const auto& e : engaged_) {
      if (e.duty == Duty::kStandOn) continue;
      for (const auto& o : others) {
        if (o.id != e.id || !o.k.finite()) continue;
        const colreg::Cpa c = colreg::cpa(mine, o.k);
        if (c.tcpa > 0.0 && c.dcpa < p_.cpa_risk) ok = false;
      }
    }
    if (ok) return alt;
  }
  return p_.max_alteration;
}

HelmOrder Helmsman::decide(const colreg::ShipKinematics& me, double route_course, double route_speed,
                           const std::vector<SeenShip>& others) {
  if (!me.finite() || !std::isfinite(route_course) || !std::isfinite(route_speed))
    throw std::invalid_argument("Helmsman::decide: non-finite own kinematics or route order");
  if (!started_) {
    last_course_ = route_course;
    last_speed_ = route_speed;
    started_ = true;
  }
  std::vector<std::pair<uint32_t, colreg::Assessment>> seen;
  for (const auto& o : others)
    if (o.k.finite()) seen.emplace_back(o.id, colreg::assess(me, o.k, cp_));
  auto find = [&](uint32_t id) -> const colreg::Assessment* {
    for (const auto& [i, a] : seen)
      if (i == id) return &a;
    return nullptr;
  };

  // A duty ends when its ship is passed and clear (or no longer seen).
  engaged_.erase(std::remove_if(engaged_.begin(), engaged_.end(),
                                [&](const Engaged& e) {
                                  const auto* a = find(e.id);
                                  return a == nullptr || passed_and_clear(*a, p_.d_colreg);
                                }),
                 engaged_.end());
  // New risks of collision (rule 7) give a duty by rules 13-15, kept until passed even when the
  // bearings later say something else (the encounter is what it was when the risk appeared).
  for (const auto& [id, a] : seen) {
    if (!a.risk) continue;
    if (std::any_of(engaged_.begin(), engaged_.end(), [&](const Engaged& e) { return e.id == id; })) continue;
    switch (a.type) {
      case colreg::EncounterType::kHeadOn:           // rule 14: both alter to starboard
      case colreg::EncounterType::kCrossingGiveWay:  // rules 15, 16: keep out of the way, not ahead
      case colreg::EncounterType::kOvertaking:       // rule 13: keep out of the way
        engaged_.push_back({id, Duty::kGiveWay});
        break;
      case colreg::EncounterType::kCrossingStandOn:  // rule 17(a)(i)
      case colreg::EncounterType::kOvertaken:
        engaged_.push_back({id, Duty::kStandOn});
        break;
      case colreg::EncounterType::kNone: break;
    }
  }
  // Rule 17(a)(ii), (b): the give-way ship has not acted (still passing too close) and is close.
  if (p_.act_alone) {
    for (auto& e : engaged_) {
      if (e.duty != Duty::kStandOn) continue;
      const auto* a = find(e.id);
      if (a && a->cpa.range < p_.act_alone_range && a->cpa.tcpa > 0.0 && a->cpa.dcpa < p_.act_alone_cpa)
        e.duty = Duty::kActAlone;
    }
  }

  const bool give = std::any_of(engaged_.begin(), engaged_.end(), [](const Engaged& e) { return e.duty == Duty::kGiveWay; });
  const bool alone = std::any_of(engaged_.begin(), engaged_.end(), [](const Engaged& e) { return e.duty == Duty::kActAlone; });
  const bool stand = std::any_of(engaged_.begin(), engaged_.end(), [](const Engaged& e) { return e.duty == Duty::kStandOn; });
  const bool acting = mode_ == HelmMode::kGiveWay || mode_ == HelmMode::kActAlone;
  HelmOrder out{route_course, route_speed, HelmMode::kRoute};
  if (give || alone) {
    if (!acting) {
      // The alteration is measured from the course steered until now (the held one when standing on).
      base_course_ = mode_ == HelmMode::kStandOn ? hold_course_ : route_course;
      hold_speed_ = mode_ == HelmMode::kStandOn ? hold_speed_ : route_speed;
      alteration_ = 0.0;
    }
    // Only ever more to starboard while acting: never a port turn back into the encounter (17(c)).
    alteration_ = std::max(alteration_, avoidance_course(me, hold_speed_, others));
    out = {geo::wrap_pi(base_course_ + alteration_), hold_speed_, give ? HelmMode::kGiveWay : HelmMode::kActAlone};
  } else if (stand) {
    if (mode_ != HelmMode::kStandOn) {
      // Keep the course and speed steered when the duty began (rule 17(a)(i)).
      hold_course_ = mode_ == HelmMode::kRoute ? route_course : last_course_;
      hold_speed_ = mode_ == HelmMode::kRoute ? route_speed : last_speed_;
    }
    out = {hold_course_, hold_speed_, HelmMode::kStandOn};
  }
  mode_ = out.mode;
  last_course_ = out.course;
  last_speed_ = out.speed;
  return out;
}

}  // namespace mpgc::ship_simulator
