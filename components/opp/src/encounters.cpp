#include "mpgc/opp/encounters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mpgc::opp {

namespace {

// Every situation with a rule is pinned: the duties, and the stand-on ones for 17(c) and rule 8(b) when acting.
Obligation obligation_of(colreg::EncounterType t) { return pinnable(t) ? t : Obligation::kNone; }

}  // namespace

void EncounterMemoryParams::validate() const {
  auto need = [](bool ok, const char* field, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("EncounterMemoryParams.") + field + " " + what);
  };
  need(std::isfinite(cpa_risk) && cpa_risk >= 0, "cpa_risk", "must be finite and >= 0");
  need(tcpa_max > 0, "tcpa_max", "must be > 0");
  need(std::isfinite(release_range) && release_range >= 0, "release_range", "must be finite and >= 0");
  need(new_course > 0 && new_course <= geo::kPi, "new_course", "must be in (0, pi]");
  need(abaft_beam > 0 && abaft_beam < geo::kPi / 2, "abaft_beam", "must be in (0, pi/2)");
  need(head_on_sector > 0 && head_on_sector < geo::kPi / 2, "head_on_sector", "must be in (0, pi/2)");
  need(acted_turn > 0 && acted_turn < geo::kPi / 2, "acted_turn", "must be in (0, pi/2)");
  need(apparent_turn >= 0 && apparent_turn < geo::kPi, "apparent_turn", "must be in [0, pi)");
  need(acted_slowdown >= 0 && acted_slowdown < 1, "acted_slowdown", "must be in [0, 1)");
  need(apparent_slowdown >= 0 && apparent_slowdown < 1, "apparent_slowdown", "must be in [0, 1)");
  need(port_turn_range > 0, "port_turn_range", "must be > 0");
}

colreg::ColregParams EncounterMemoryParams::assessment() const {
  colreg::ColregParams cp;
  cp.abaft_beam = abaft_beam;
  cp.head_on_sector = head_on_sector;
  cp.d_colreg = std::numeric_limits<double>::infinity();  // the TCPA limit bounds the range
  cp.cpa_risk = cpa_risk;
  cp.tcpa_max = tcpa_max;
  return cp;
}

PinnedEncounter EncounterMemory::find(uint32_t id) const {
  const auto it = pinned_.find(id);
  return it == pinned_.end() ? PinnedEncounter{} : it->second.e;
}

void EncounterMemory::update(const EncounterMemoryParams& p, const colreg::ShipKinematics& own,
                             std::vector<Target>& targets) {
  p.validate();
  const colreg::ColregParams cp = p.assessment();
  std::vector<colreg::Assessment> as;  // all first, so that bad input leaves the memory unchanged
  for (const Target& t : targets) as.push_back(colreg::assess(own, {t.p.x, t.p.y, t.v.x, t.v.y}, cp));
  std::map<uint32_t, Entry> next;
  // Rule 17(c): while a crossing ship closes on the port side within port_turn_range with a risk
  // of collision (predicted CPA below cpa_risk), the most starboard course held is the one not to
  // turn to port of (PinnedEncounter::held_17c). Like the stand-on's stage 3 (rule 17(a)(ii)) the
  // range is a time too: the CPA nearer than the own ship takes to sail it. A ship converging
  // slowly on the port beam, CPA an hour ahead, is no reason to give up the route yet (paper
  // s1_unexpected held a 99 deg give-way course for 3000 s for one 15 km off, CPA in 3000 s).
  auto follow_17c = [&](PinnedEncounter& e, const colreg::Assessment& a) {
    const double u = std::isfinite(e.speed0) && e.speed0 > 0.5 ? e.speed0 : own.speed();
    e.at_risk_17c = e.obligation == Obligation::kCrossingStandOn && own.speed() > 0.5 && a.cpa.tcpa > 0.0 &&
                    a.cpa.dcpa < p.cpa_risk && a.cpa.range <= p.port_turn_range && a.beta < 0.0 &&
                    a.cpa.tcpa < p.port_turn_range / u;
    if (!e.at_risk_17c) return;
    const double turned = std::remainder(own.course() - e.course0, 2.0 * geo::kPi);
    e.held_17c = std::isnan(e.held_17c) ? turned : std::max(e.held_17c, turned);
  };
  for (std::size_t i = 0; i < targets.size(); ++i) {
    Target& t = targets[i];
    const colreg::Assessment& a = as[i];
    const colreg::ShipKinematics tk{t.p.x, t.p.y, t.v.x, t.v.y};
    const Vec2 r{own.x - t.p.x, own.y - t.p.y};
    const auto it = pinned_.find(t.id);
    if (it != pinned_.end()) {
      const PinnedEncounter& e = it->second.e;
      // Opening and farther than where it began (a give-way manoeuvre that opens the range for a
      // while has not ended the encounter).
      bool done = a.cpa.tcpa <= 0.0 && a.cpa.range > std::max(p.release_range, it->second.range0);
      if (tk.speed() > 0.5) {  // the course of a (nearly) stopped target is noise
        // A target that turns starts a new encounter, unless it turns as the rules ask of it: to
        // starboard when head-on (rule 14) or giving way to the own ship (rules 15-16), either way
        // when overtaking it (rule 13). Its compliance is no reason to drop the own ship's part.
        const double turn = std::remainder(tk.course() - e.target_course, 2.0 * geo::kPi);
        const bool expected = ((e.obligation == Obligation::kHeadOn || e.obligation == Obligation::kCrossingStandOn) &&
                               turn > 0.0) ||
                              e.obligation == Obligation::kOvertaken;
        done = done || (std::fabs(turn) > p.new_course && !expected);
      }
      if (a.cpa.tcpa <= 0.0 && e.obligation == Obligation::kCrossingGiveWay)
        done = done || across_astern(e, t.v, r);
      else if (a.cpa.tcpa <= 0.0)
        done = done || std::fabs(a.beta) > 0.5 * geo::kPi;  // abaft the beam and opening
      if (!done) {
        Entry kept = it->second;
        const double own_turn = std::remainder(own.course() - e.course0, 2.0 * geo::kPi);
        const bool either = e.obligation == Obligation::kOvertaking || e.obligation == Obligation::kOvertaken;
        const double turned = either ? std::fabs(own_turn) : own_turn;
        const bool duty = e.obligation == Obligation::kCrossingGiveWay || e.obligation == Obligation::kHeadOn ||
                          e.obligation == Obligation::kOvertaking;
        const double slowed = duty && e.speed0 > 0.5 ? 1.0 - own.speed() / e.speed0 : 0.0;
        if ((own.speed() > 0.5 && turned > p.acted_turn) || (p.acted_slowdown > 0.0 && slowed > p.acted_slowdown))
          kept.e.acted = true;
        if ((own.speed() > 0.5 && p.apparent_turn > 0.0 && turned >= p.apparent_turn) ||
            (p.apparent_slowdown > 0.0 && slowed >= p.apparent_slowdown))
          kept.e.completed = true;
        // An alteration given up while the risk of collision remains was not made: back on course0
        // with the CPA still inside cpa_risk, it is to be made again (Annapolis: 33 deg to starboard
        // and back within a minute, 2.9 km from a head-on ship later passed at 190 m after 17 deg).
        if (kept.e.completed && own.speed() > 0.5 && turned < p.acted_turn && !(slowed > p.acted_slowdown) &&
            a.cpa.tcpa > 0.0 && a.cpa.dcpa < p.cpa_risk)
          kept.e.completed = false;
        follow_17c(kept.e, a);
        next[t.id] = kept;
        t.pinned = kept.e;
        continue;
      }
    }
    t.pinned = {};
    const Obligation o = obligation_of(a.type);
    if (o != Obligation::kNone) {
      t.pinned = {o, own.course(), track_side(t.v, r), tk.course()};
      t.pinned.speed0 = own.speed();
      follow_17c(t.pinned, a);
      next[t.id] = {t.pinned, a.cpa.range};
    }
  }
  pinned_ = std::move(next);  // targets no longer tracked are forgotten
}

std::vector<PinnedRecord> EncounterMemory::records() const {
  std::vector<PinnedRecord> out;
  for (const auto& [id, entry] : pinned_) out.push_back({id, entry.e, entry.range0});
  return out;
}

void EncounterMemory::restore(const std::vector<PinnedRecord>& records) {
  std::map<uint32_t, Entry> next;
  for (const auto& r : records) {
    const std::string what = "pinned encounter of target " + std::to_string(r.id);
    if (!std::isfinite(r.e.course0) || !std::isfinite(r.e.target_course) || !(std::isfinite(r.range0) && r.range0 >= 0))
      throw std::invalid_argument(what + ": non-finite course or range");
    if (r.e.obligation == Obligation::kNone || !pinnable(r.e.obligation))
      throw std::invalid_argument(what + ": no obligation");
    if (r.e.track_side < -1 || r.e.track_side > 1) throw std::invalid_argument(what + ": track_side must be -1, 0 or 1");
    if (!next.emplace(r.id, Entry{r.e, r.range0}).second) throw std::invalid_argument(what + ": listed twice");
  }
  pinned_ = std::move(next);
}

}  // namespace mpgc::opp
