#include "ranging/teammate_view.h"

#include <gtest/gtest.h>

namespace ranging {
namespace {

TEST(TeammateViewTest, EachTeammateOnceWithWhatIsKnownOfIt) {
  Range b;
  b.teammate = "b";
  b.range = 4.0;
  const std::map<std::string, HeardBearing> bearings = {{"b", {0.5, 0.9, 8.0}}, {"c", {-1.0, 0.4, 2.0}}};
  const std::vector<TeammateView> v = ViewTeammates({b}, bearings, 10.0);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].name, "b");
  ASSERT_TRUE(v[0].range && v[0].bearing);
  EXPECT_DOUBLE_EQ(v[0].range->range, 4.0);
  EXPECT_DOUBLE_EQ(v[0].bearing->bearing, 0.5);
  EXPECT_DOUBLE_EQ(v[0].bearing_age, 2.0);
  EXPECT_EQ(v[1].name, "c");
  EXPECT_FALSE(v[1].range);
  EXPECT_DOUBLE_EQ(v[1].bearing_age, 8.0);
  EXPECT_TRUE(ViewTeammates({}, {}, 0.0).empty());
}

}  // namespace
}  // namespace ranging
