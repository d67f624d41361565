#include "audio_propagation/channel_validation.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "measured_rooms.h"
#include "test_room.h"
#include "world_sim/world_file.h"

namespace audio_propagation {
namespace {

ValidationLink Link(double length, double model, int decoded, int packets = 4) {
  ValidationLink l;
  l.reachable = true;
  l.path_length = length;
  l.model = model;
  l.decoded = decoded;
  l.packets = packets;
  return l;
}

TEST(ChannelValidation, BinsTooSmallAreMergedIntoTheirNeighbours) {
  std::vector<ValidationLink> links;
  for (int k = 0; k < 20; ++k) links.push_back(Link(1.0, 1.0, 4));   // 0-3: 20 links
  for (int k = 0; k < 5; ++k) links.push_back(Link(4.0, 0.5, 0));    // 3-6: 5, merged with 6-10
  for (int k = 0; k < 12; ++k) links.push_back(Link(7.0, 0.5, 4));   // 6-10: 12
  for (int k = 0; k < 3; ++k) links.push_back(Link(40.0, 0.0, 0));   // 30+: 3, into the bin before
  const std::vector<double> edges(std::begin(kDefaultEdges), std::end(kDefaultEdges));
  const std::vector<DistanceBin> bins = BinByLength(links, edges, 15);
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].links, 20);
  EXPECT_DOUBLE_EQ(bins[0].low, 0.0);
  EXPECT_DOUBLE_EQ(bins[0].high, 3.0);
  EXPECT_DOUBLE_EQ(bins[0].model, 100.0);
  EXPECT_DOUBLE_EQ(bins[0].rendered, 100.0);
  EXPECT_EQ(bins[1].links, 20);
  EXPECT_DOUBLE_EQ(bins[1].low, 3.0);
  EXPECT_TRUE(std::isinf(bins[1].high));
  EXPECT_DOUBLE_EQ(bins[1].model, 100.0 * (17 * 0.5) / 20.0);
  EXPECT_DOUBLE_EQ(bins[1].rendered, 100.0 * 12.0 / 20.0);
  EXPECT_DOUBLE_EQ(bins[1].mean_length, (5 * 4.0 + 12 * 7.0 + 3 * 40.0) / 20.0);
  EXPECT_DOUBLE_EQ(Agreement(bins), 100.0 * (12.0 - 8.5) / 20.0);
}

using test::TestRoom;

TEST(ChannelValidation, LinksAreDrawnAwayFromWallsAndJudgedTheSameOnAnyNumberOfThreads) {
  const TestRoom room;
  ValidationOptions o;
  o.links = 4;
  o.packets = 1;
  o.seed = 7;
  o.threads = 1;
  const std::vector<ValidationLink> one =
      ValidateLinks(room.propagation, *room.world.config.acoustics, test::FlatTable("nava"), room.names, room.resting, o);
  o.threads = 2;
  const std::vector<ValidationLink> two =
      ValidateLinks(room.propagation, *room.world.config.acoustics, test::FlatTable("nava"), room.names, room.resting, o);
  ASSERT_EQ(one.size(), 4u);
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].sender, two[k].sender);
    EXPECT_EQ(one[k].decoded, two[k].decoded);
    EXPECT_EQ(one[k].model, two[k].model);
    ASSERT_EQ(one[k].judged.size(), 1u);
    ASSERT_EQ(two[k].judged.size(), 1u);
    EXPECT_EQ(one[k].judged[0].noise_gap_db, two[k].judged[0].noise_gap_db);
    EXPECT_EQ(one[k].judged[0].decoded, two[k].judged[0].decoded);
    EXPECT_EQ(one[k].judged[0].decoded, one[k].decoded == 1);
    EXPECT_DOUBLE_EQ(one[k].model, 0.5);  // the table says so, wherever the link is
    for (const Eigen::Vector2d& p : {one[k].sender, one[k].listener}) {
      // 0.3 m clear of the room's outer walls and of the dividing wall (x 3.0 to 3.15, y < 2.5).
      EXPECT_TRUE(p.x() > 0.3 && p.x() < 5.7 && p.y() > 0.3 && p.y() < 3.7) << p.transpose();
      if (p.y() < 2.5) {
        EXPECT_TRUE(p.x() < 2.7 || p.x() > 3.45) << p.transpose();
      }
    }
    EXPECT_GE((one[k].sender - one[k].listener).norm(), o.min_separation);
    EXPECT_TRUE(one[k].reachable);
    // The rendered noise is the model's, but for the fan switching during a packet.
    EXPECT_NEAR(one[k].judged[0].noise_gap_db, 0.0, 3.0);
  }
}

// With each profile's shipped table, on the test room (few links, so quick): the model and the
// real receiver on rendered audio agree within 25 points in the room as it is, and with its fan
// roaring white noise all the time (SNRs about -10 dB: within the tables' axis, which starts at
// -15 dB; below it the table clamps, see the report of issue 17).
TEST(ChannelValidation, TheModelAgreesWithTheRealReceiverInTheTestRoom) {
  int profiles = 0;
  for (const nava_modem::Profile profile : {nava_modem::Profile::kNava, nava_modem::Profile::kRoom}) {
    const std::string name = nava_modem::ProfileName(profile);
    const std::string shipped = ShippedDecodeTable(name);
    if (!std::filesystem::exists(shipped)) continue;
    ++profiles;
    const DecodeTable table = LoadDecodeTable(shipped, name);
    const TestRoom room;
    ValidationOptions o;
    // A table measured over measured rooms renders its links through them.
    if (table.rooms == nava_modem::RoomOptions::Model::kMeasured) {
      const std::string rooms = MULTIROBOT_AUDIO_REALROOMS;
      if (!std::filesystem::exists(rooms)) {
        std::printf("%s: the measured rooms its table was measured over are not there (%s): skipped\n", name.c_str(),
                    rooms.c_str());
        continue;
      }
      o.measured_rooms = std::make_shared<const nava_modem::MovedRooms>(
          nava_modem::tools::MovableRooms(rooms + "," + rooms + "/more", o.sample_rate, {"channel_validation_test", ""}),
          o.sample_rate);
    }
    o.profile = profile;
    o.links = profile == nava_modem::Profile::kNava ? 30 : 15;
    o.packets = 2;
    const std::vector<double> edges = {0.0};  // one bin: the room is small
    const world_sim::Acoustics as_is = *room.world.config.acoustics;
    const std::vector<DistanceBin> calm =
        BinByLength(ValidateLinks(room.propagation, as_is, table, room.names, room.resting, o), edges, 1);
    world_sim::Acoustics loud = as_is;
    loud.noise_sources[0].level_db = 80.0;
    loud.noise_sources[0].kind = world_sim::NoiseKind::kWhite;
    loud.noise_sources[0].duty = 1.0;
    const std::vector<DistanceBin> drowned =
        BinByLength(ValidateLinks(room.propagation, loud, table, room.names, room.resting, o), edges, 1);
    ASSERT_EQ(calm.size(), 1u);
    ASSERT_EQ(drowned.size(), 1u);
    EXPECT_LE(Agreement(calm), 25.0) << name << ": model " << calm[0].model << " %, rendered " << calm[0].rendered << " %";
    EXPECT_LE(Agreement(drowned), 25.0) << name << " with the fan: model " << drowned[0].model << " %, rendered "
                                        << drowned[0].rendered << " %";
    EXPECT_LT(drowned[0].rendered, calm[0].rendered) << name;
  }
  if (profiles == 0) GTEST_SKIP() << "no shipped decode table yet (" << ShippedDecodeTable("nava") << ")";
}

// The shipped hospital world, on the thesis's map where it is (shared/maps): its robots stand
// free, its noise sources too (the model checks them), and a link along the main corridor is
// heard over its noise.
TEST(ChannelValidation, TheHospitalWorldLoadsWithItsAcoustics) {
  const std::string map = std::string(MULTIROBOT_AUDIO_SHARED_MAPS_DIR) + "/hospital_section.yaml";
  if (!std::filesystem::exists(map)) GTEST_SKIP() << map << " is not there";
  const world_sim::LoadedWorld world =
      world_sim::LoadWorldFile(std::string(MULTIROBOT_AUDIO_MAPS_DIR) + "/hospital_world.yaml", map);
  ASSERT_TRUE(world.config.acoustics.has_value());
  EXPECT_NEAR(world.map.width_m(), 34.0, 0.1);
  std::vector<std::string> names;
  std::vector<Eigen::Vector2d> resting;
  for (const world_sim::RobotSpec& r : world.config.robots) names.push_back(r.name), resting.push_back(r.start.position());
  const PropagationModel propagation(world.map, ValidationPropagation(world.map.width_m() + world.map.height_m(), 1));
  const AcousticModel model(propagation, *world.config.acoustics, test::FlatTable("nava"), names);
  ASSERT_EQ(model.acoustics().noise_sources.size(), 2u);
  EXPECT_NE(model.acoustics().noise_sources[0].kind, model.acoustics().noise_sources[1].kind);
  const SoundPath path = propagation.Path(resting[0], resting[1]);
  ASSERT_TRUE(path.reachable);
  const LinkPrediction p = model.Predict(path, resting[1], model.NoiseAt(resting[1], 0.0, resting));
  EXPECT_GT(p.snr_db, 0.0);
  EXPECT_NEAR(p.signal.rt60, 0.6, 1e-9);
}

}  // namespace
}  // namespace audio_propagation
