// The links' fate through the simulated acoustic channel (fate_check.h): with a table that
// decodes every packet with probability one half, a static link held to its fate delivers all
// of its packets or none, one drawn anew delivers about half, and a moving one follows the model.
#include "audio_propagation/fate_check.h"

#include <string>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "test_room.h"

namespace audio_propagation {
namespace {

// 20 pairs of each kind, 20 packets each, in the test room.
FateCheckResult Check(const test::TestRoom& room, bool fate) {
  FateCheckOptions o;
  o.pairs = 20;
  o.packets = 20;
  o.link_fate = fate;
  return CheckLinkFate(room.propagation, *room.world.config.acoustics, test::FlatTable("nava", 0.5), room.names, room.resting, o);
}

TEST(FateCheck, StaticLinksKeepTheirFateAndMovingOnesFollowTheModel) {
  const test::TestRoom room;
  const FateCheckResult kept = Check(room, true);
  ASSERT_EQ(kept.static_pairs, 20);
  ASSERT_EQ(kept.cycling_pairs, 20);
  ASSERT_EQ(kept.moving_pairs, 20);
  EXPECT_EQ(kept.static_decided, 20);
  EXPECT_EQ(kept.cycling_decided, 20);  // the flat table does not care whether the fan runs
  EXPECT_NEAR(kept.moving_probability, 0.5, 0.05);
  // 400 packets: 4 standard deviations of the mean are 10 points.
  EXPECT_NEAR(kept.moving_delivered, kept.moving_probability, 0.1);
  const FateCheckResult drawn = Check(room, false);
  EXPECT_LE(drawn.static_decided, 1);  // 20 draws at one half are almost never 18 alike
  EXPECT_NEAR(drawn.moving_delivered, drawn.moving_probability, 0.1);
}

// The test room's fan runs half of every 4 s and drowns its white ambient. With a table that
// decodes 30 % under pink noise and 70 % under white, a held draw between the two delivers while
// the fan is off and fails while it runs: in steady noise (the fan held on) every static pair is
// all or nothing, on the fan's duty cycle some are not.
TEST(FateCheck, SourcesOnTheirDutyCyclesMakeHeldLinksDeliverInBetween) {
  const test::TestRoom room;
  DecodeTable table = test::FlatTable("nava", 0.7);
  table.At(Interference::kPink, 0, 0, 0).packet = 0.3;
  FateCheckOptions o;
  o.pairs = 20;
  o.packets = 20;
  const FateCheckResult r = CheckLinkFate(room.propagation, *room.world.config.acoustics, table, room.names, room.resting, o);
  ASSERT_EQ(r.static_pairs, 20);
  ASSERT_EQ(r.cycling_pairs, 20);
  EXPECT_EQ(r.static_decided, 20);
  // A draw in 0.3-0.7 (two pairs in five) delivers about half its packets.
  EXPECT_LE(r.cycling_decided, 17);
}

TEST(FateCheck, RefusesImpossibleOptionsByName) {
  auto refused = [](FateCheckOptions o, const std::string& field) {
    try {
      ValidateOptions(o);
      ADD_FAILURE() << field << ": accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  FateCheckOptions o;
  o.fate_distance = 0.0;
  refused(o, "fate_distance");
  o = FateCheckOptions{};
  o.pairs = 0;
  refused(o, "pairs");
  o = FateCheckOptions{};
  o.min_probability = 0.9;
  refused(o, "probabilities");
}

}  // namespace
}  // namespace audio_propagation
