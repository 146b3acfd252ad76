// Encounters of tracks against the own ship, and the NED origin recovered from a navigation fix.
#include <gtest/gtest.h>

#include "mpgc/situational_awareness/situation.hpp"

namespace sa = mpgc::sa;
namespace cr = mpgc::colreg;
using mpgc::geo::deg2rad;

TEST(Situation, EncountersOfEstablishedTracksOnly) {
  sa::Track head_on, tentative, opening;
  head_on.id = 1;
  head_on.x << 3000, 20, -5, 0;
  head_on.status = sa::TrackStatus::kConfirmed;
  tentative = head_on;
  tentative.id = 2;
  tentative.status = sa::TrackStatus::kTentative;
  opening.id = 3;
  opening.mmsi = 257000001;
  opening.x << -3000, 0, -5, 0;
  opening.status = sa::TrackStatus::kCoasting;
  const auto own = cr::ShipKinematics::from_course(0, 0, 0, 5);
  const auto e = sa::encounters(own, {head_on, tentative, opening}, cr::ColregParams{});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].track_id, 1u);
  EXPECT_EQ(e[0].assessment.type, cr::EncounterType::kHeadOn);
  EXPECT_NEAR(e[0].assessment.cpa.dcpa, 20.0, 1e-9);
  EXPECT_NEAR(e[0].assessment.cpa.tcpa, 300.0, 1e-9);
  EXPECT_EQ(e[1].mmsi, 257000001u);
  EXPECT_EQ(e[1].assessment.type, cr::EncounterType::kNone);
  EXPECT_NEAR(e[1].bearing, deg2rad(180), 1e-12);
}

TEST(Situation, OriginFromFixRecoversTheFrame) {
  const mpgc::geo::LatLon o{deg2rad(58.76), deg2rad(10.49)};
  const mpgc::geo::LocalNed frame(o);
  for (const mpgc::geo::NorthEast p : {mpgc::geo::NorthEast{0, 0}, {12000, -8000}, {-30000, 25000}}) {
    const auto fix = frame.to_latlon(p);
    const auto got = sa::origin_from_fix(fix, p);
    const auto back = mpgc::geo::LocalNed(got).to_ned(fix);
    EXPECT_NEAR(back.x, p.x, 1e-3);
    EXPECT_NEAR(back.y, p.y, 1e-3);
    EXPECT_NEAR(got.lat, o.lat, 1e-9);
    EXPECT_NEAR(got.lon, o.lon, 1e-9);
  }
  EXPECT_THROW(sa::origin_from_fix({std::nan(""), 0.1}, {0, 0}), std::invalid_argument);
  EXPECT_THROW(sa::origin_from_fix({0.1, 0.1}, {std::numeric_limits<double>::infinity(), 0}), std::invalid_argument);
}
