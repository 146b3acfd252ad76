#include "mpgc/colreg/colreg.hpp"

#include <stdexcept>

#include "mpgc/geom/vec2.hpp"

#include <yaml-cpp/yaml.h>

namespace mpgc::colreg {

using geo::kPi;

Cpa cpa(const ShipKinematics& own, const ShipKinematics& target) {
  // Seed 003 eq. 12: relative position and velocity of the target.
  const double dx = target.x - own.x, dy = target.y - own.y;
  const double du = target.vx - own.vx, dv = target.vy - own.vy;
  const double range = std::hypot(dx, dy);
  const double w2 = du * du + dv * dv;
  // No relative motion: the distance never changes; "now" is as close as it gets.
  if (!(w2 > 1e-12)) return {range, 0.0, range};
  const double t = geom::cpa_time({dx, dy}, {du, dv});  // eq. 14
  return {std::hypot(dx + du * t, dy + dv * t), t, range};  // eq. 13 at t
}

double bearing(const ShipKinematics& own, const ShipKinematics& target) {
  return geo::course_of(target.x - own.x, target.y - own.y);
}

double relative_bearing(const ShipKinematics& own, const ShipKinematics& target) {
  return geo::wrap_pi(bearing(own, target) - own.bow());
}

const char* to_string(EncounterType t) {
  switch (t) {
    case EncounterType::kNone: return "none";
    case EncounterType::kHeadOn: return "head-on";
    case EncounterType::kCrossingGiveWay: return "crossing-give-way";
    case EncounterType::kCrossingStandOn: return "crossing-stand-on";
    case EncounterType::kOvertaking: return "overtaking";
    case EncounterType::kOvertaken: return "overtaken";
  }
  return "?";
}

const char* dnv_name(EncounterType t) {
  switch (t) {
    case EncounterType::kNone: return "noRiskCollision";
    case EncounterType::kHeadOn: return "head-on";
    case EncounterType::kCrossingGiveWay: return "crossing-give-way";
    case EncounterType::kCrossingStandOn: return "crossing-stand-on";
    case EncounterType::kOvertaking: return "overtaking-give-way";
    case EncounterType::kOvertaken: return "overtaking-stand-on";
  }
  return "?";
}

const char* to_string(Role r) {
  switch (r) {
    case Role::kNone: return "none";
    case Role::kGiveWay: return "give-way";
    case Role::kStandOn: return "stand-on";
    case Role::kBothGiveWay: return "both-give-way";
  }
  return "?";
}

Role role_of(EncounterType t) {
  switch (t) {
    case EncounterType::kHeadOn: return Role::kBothGiveWay;
    case EncounterType::kCrossingGiveWay:
    case EncounterType::kOvertaking: return Role::kGiveWay;
    case EncounterType::kCrossingStandOn:
    case EncounterType::kOvertaken: return Role::kStandOn;
    case EncounterType::kNone: break;
  }
  return Role::kNone;
}

namespace {
void check_angle(double v, double lo, double hi, const char* name) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw std::invalid_argument(std::string("ColregParams.") + name + " = " + std::to_string(geo::rad2deg(v)) +
                                " deg is outside [" + std::to_string(geo::rad2deg(lo)) + ", " +
                                std::to_string(geo::rad2deg(hi)) + "] deg");
}
void check_positive(double v, const char* name) {
  if (std::isnan(v) || v <= 0.0)
    throw std::invalid_argument(std::string("ColregParams.") + name + " = " + std::to_string(v) +
                                " must be > 0 (infinity disables it)");
}
}  // namespace

void ColregParams::validate() const {
  check_angle(abaft_beam, 0.0, kPi / 2, "abaft_beam");
  check_angle(head_on_sector, 0.0, kPi / 2, "head_on_sector");
  check_angle(overtake_aspect, 0.0, kPi, "overtake_aspect");
  check_angle(crossing_aspect, 0.0, kPi / 2, "crossing_aspect");
  check_positive(d_colreg, "d_colreg");
  check_positive(cpa_risk, "cpa_risk");
  check_positive(tcpa_max, "tcpa_max");
}

ColregParams ColregParams::from_dnv_settings(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);  // JSON is a subset of YAML's flow style
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot read encounter settings: " + e.what());
  }
  auto angle = [&](const YAML::Node& n, const std::string& key) {
    if (!n || !n.IsScalar()) throw std::runtime_error(path + ": missing or non-scalar " + key);
    double v = 0.0;
    try {
      v = n.as<double>();
    } catch (const std::exception&) {
      throw std::runtime_error(path + ": " + key + " is not a number");
    }
    if (!std::isfinite(v)) throw std::runtime_error(path + ": " + key + " is not finite");
    return geo::deg2rad(v);
  };
  const YAML::Node c = root["classification"];
  if (!c || !c.IsMap()) throw std::runtime_error(path + ": missing object classification");
  const YAML::Node t15 = c["theta15"];
  if (!t15 || !t15.IsSequence() || t15.size() != 2)
    throw std::runtime_error(path + ": classification.theta15 must be a list of two angles");
  const double lo = angle(t15[0], "classification.theta15[0]");
  const double hi = angle(t15[1], "classification.theta15[1]");
  // Our sector is symmetric about the stern (rule 13 does not distinguish the quarters).
  if (std::fabs((lo + hi) - 2.0 * kPi) > 1e-9)
    throw std::runtime_error(path + ": classification.theta15 is not symmetric about the stern");
  ColregParams p;
  p.abaft_beam = lo - kPi / 2;
  p.head_on_sector = angle(c["theta14Criteria"], "classification.theta14Criteria");
  p.overtake_aspect = angle(c["theta13Criteria"], "classification.theta13Criteria");
  p.crossing_aspect = angle(c["theta15Criteria"], "classification.theta15Criteria");
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return p;
}

EncounterType classify_sectors(double beta, double alpha, const ColregParams& p) {
  const double b360 = geo::wrap_2pi(beta), a360 = geo::wrap_2pi(alpha);
  const double b180 = geo::wrap_pi(beta), a180 = geo::wrap_pi(alpha);
  const double stern_lo = kPi / 2 + p.abaft_beam, stern_hi = 1.5 * kPi - p.abaft_beam;  // DNV theta15
  // Rule 13 first: "any vessel overtaking any other shall keep out of the way" overrides 14/15.
  if (b360 > stern_lo && b360 < stern_hi && std::fabs(a180) <= p.overtake_aspect) return EncounterType::kOvertaken;
  if (a360 > stern_lo && a360 < stern_hi && std::fabs(b180) <= p.overtake_aspect) return EncounterType::kOvertaking;
  if (std::fabs(b180) <= p.head_on_sector && std::fabs(a180) <= p.head_on_sector) return EncounterType::kHeadOn;
  // Rule 15: the ship that has the other on her own starboard side keeps out of the way.
  if (b360 > 0.0 && b360 < stern_lo && a180 > -stern_lo && a180 <= p.crossing_aspect)
    return EncounterType::kCrossingGiveWay;
  if (a360 > 0.0 && a360 < stern_lo && b180 > -stern_lo && b180 <= p.crossing_aspect)
    return EncounterType::kCrossingStandOn;
  return EncounterType::kNone;
}

Assessment assess(const ShipKinematics& own, const ShipKinematics& target, const ColregParams& p) {
  if (!own.finite()) throw std::invalid_argument("colreg::assess: own ship kinematics not finite");
  if (!target.finite()) throw std::invalid_argument("colreg::assess: target kinematics not finite");
  Assessment a;
  a.cpa = cpa(own, target);
  a.beta = relative_bearing(own, target);
  a.alpha = aspect(own, target);
  a.sector = classify_sectors(a.beta, a.alpha, p);
  a.risk = a.cpa.range <= p.d_colreg && a.cpa.tcpa > 0.0 && a.cpa.dcpa <= p.cpa_risk && a.cpa.tcpa <= p.tcpa_max;
  a.type = a.risk ? a.sector : EncounterType::kNone;
  a.role = role_of(a.type);
  return a;
}

}  // namespace mpgc::colreg
