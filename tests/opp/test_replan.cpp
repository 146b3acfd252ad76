#include <gtest/gtest.h>

#include "mpgc/opp/replan.hpp"

namespace opp = mpgc::opp;

TEST(ReplanPolicy, PeriodGoalAndTrackChange) {
  opp::ReplanParams p;
  p.period = 15;
  p.track_threshold = 200;
  p.track_horizon = 300;
  p.min_interval = 1;
  opp::ReplanPolicy pol(p);
  std::vector<opp::Target> tg{{7, {1000, 0}, {0, 5}}};
  EXPECT_EQ(pol.due(0, 1, tg), "first plan");
  pol.planned(0, 1, tg);
  // 5 s later, the target where eq. 3 said it would be: nothing due.
  std::vector<opp::Target> moved{{7, {1000, 25}, {0, 5}}};
  EXPECT_EQ(pol.due(5, 1, moved), "");
  EXPECT_EQ(pol.due(15, 1, moved), "period");
  EXPECT_EQ(pol.due(5, 2, moved), "new goal 2");
  // A course change of 90 deg: the prediction 150 s ahead is 1 km off.
  std::vector<opp::Target> turned{{7, {1000, 25}, {5, 0}}};
  EXPECT_NE(pol.due(5, 1, turned).find("target 7 track changed"), std::string::npos);
  // ... but not within min_interval of the last plan.
  EXPECT_EQ(pol.due(0.5, 1, turned), "");
  std::vector<opp::Target> more = moved;
  more.push_back({9, {0, 0}, {0, 0}});
  EXPECT_EQ(pol.due(5, 1, more), "new target 9");
}

TEST(ReplanPolicy, RetriesSoonAfterAFailedPlan) {
  opp::ReplanParams p;
  p.period = 15;
  p.min_interval = 2;
  opp::ReplanPolicy pol(p);
  pol.planned(0, 1, {}, false);
  EXPECT_EQ(pol.due(1, 1, {}), "");
  EXPECT_EQ(pol.due(2.5, 1, {}), "retry after a failed plan");
  pol.planned(2.5, 1, {}, true);
  EXPECT_EQ(pol.due(5, 1, {}), "");
}

TEST(ReplanPolicy, RejectsBadParams) {
  opp::ReplanParams p;
  p.period = 0;
  EXPECT_THROW(opp::ReplanPolicy{p}, std::invalid_argument);
  p = {};
  p.track_threshold = NAN;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}
