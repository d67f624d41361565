#include "audio_propagation/channel_factory.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "audio_propagation/decode_table.h"
#include "grid/input_error.h"
#include "grid/map_file.h"

namespace audio_propagation {
namespace {

const std::string kMaps = MULTIROBOT_AUDIO_MAPS_DIR;

// test_room_world.yaml: robot_0 (omni) and robot_1 (bidirectional), no acoustics.
SimulatedChannelOptions ThresholdRoom() {
  SimulatedChannelOptions o;
  o.world_file = kMaps + "/test_room_world.yaml";
  return o;
}

// test_room_acoustic_world.yaml: robot_0, robot_1 and robot_2, all omni, with acoustics.
SimulatedChannelOptions AcousticRoom() {
  SimulatedChannelOptions o;
  o.world_file = kMaps + "/test_room_acoustic_world.yaml";
  o.channel_model = ChannelModel::kAcoustic;
  return o;
}

// `run` throws ChannelOptionError for `field`, with every one of `words` in its message.
void ExpectOptionError(const std::function<void()>& run, const std::string& field,
                       const std::vector<std::string>& words) {
  try {
    run();
    ADD_FAILURE() << "no error for " << field;
  } catch (const ChannelOptionError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_EQ(std::string(e.what()), field + ": " + e.problem());
    for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

void ExpectCheckError(const SimulatedChannelOptions& o, const std::string& field,
                      const std::vector<std::string>& words) {
  ExpectOptionError([&] { CheckSimulatedChannelOptions(o); }, field, words);
}

void ExpectBuildError(const SimulatedChannelOptions& o, const std::string& field,
                      const std::vector<std::string>& words) {
  ExpectOptionError([&] { BuildSimulatedChannel(o); }, field, words);
}

TEST(ChannelFactory, BuildsTheThresholdChannelOfAShippedWorld) {
  const SimulatedChannel c = BuildSimulatedChannel(ThresholdRoom());
  EXPECT_EQ(c.robots, (std::vector<std::string>{"robot_0", "robot_1"}));
  EXPECT_EQ(c.microphones, (std::vector<world_sim::Microphone>{world_sim::Microphone::kOmni,
                                                               world_sim::Microphone::kBidirectional}));
  ASSERT_TRUE(c.propagation && c.channel);
  EXPECT_FALSE(c.acoustic);
  EXPECT_EQ(c.channel->size(), 2u);
  EXPECT_EQ(c.channel->acoustic(), nullptr);
  EXPECT_DOUBLE_EQ(c.propagation->options().threshold_db, PropagationOptions{}.threshold_db);
  EXPECT_GT(c.propagation->graph().size(), 0u);
  EXPECT_TRUE(c.decode_table.empty());
  EXPECT_FALSE(c.delivery_robot);
}

TEST(ChannelFactory, BuildsTheAcousticChannelOfAShippedWorld) {
  SimulatedChannelOptions o = AcousticRoom();
  o.delivery_map_robot = "robot_2";
  const SimulatedChannel c = BuildSimulatedChannel(o);
  EXPECT_EQ(c.robots, (std::vector<std::string>{"robot_0", "robot_1", "robot_2"}));
  ASSERT_TRUE(c.acoustic && c.channel);
  EXPECT_EQ(c.channel->acoustic(), c.acoustic.get());
  EXPECT_EQ(c.decode_table, ShippedDecodeTable("nava"));
  EXPECT_EQ(c.delivery_robot, std::optional<std::size_t>(2));
  // Unset, the threshold falls to the acoustic model's, under the world's ambient level.
  EXPECT_LT(c.propagation->options().threshold_db, 30.0);

  o.threshold_db = 35.0;
  EXPECT_DOUBLE_EQ(BuildSimulatedChannel(o).propagation->options().threshold_db, 35.0);
}

// The frames robots may send, and how long each sounds: the profile's lengths at the options'
// rate with the threshold model; today's packet alone with the acoustic model, whose tables were
// measured on it; a rate off the ladder, or a faster one with the acoustic model, named.
TEST(ChannelFactory, FramesTakeTheProfilesLengthsAndTheOptionsRate) {
  SimulatedChannelOptions o = ThresholdRoom();
  o.profile = nava_modem::Profile::kRoom;
  o.rate = 2;
  const SimulatedChannel c = BuildSimulatedChannel(o);
  EXPECT_EQ(c.format.min_bytes, 1u);
  EXPECT_EQ(c.format.max_bytes, 255u);
  const nava_modem::MacFrame f = c.Frame(std::vector<std::uint8_t>(64, 9));
  EXPECT_EQ(f.rate, 2);
  EXPECT_DOUBLE_EQ(f.airtime, nava_modem::FrameAirtime(nava_modem::Profile::kRoom, {}, 64, 2));
  EXPECT_THROW(c.Frame(std::vector<std::uint8_t>(256)), std::invalid_argument);

  o.rate = 3;
  ExpectCheckError(o, "rate", {"[0, 2]", "3"});
  SimulatedChannelOptions a = AcousticRoom();
  a.profile = nava_modem::Profile::kRoom;
  a.rate = 1;
  ExpectCheckError(a, "rate", {"acoustic", "rate 0 only"});
  a.rate = 0;
  const SimulatedChannel acoustic = BuildSimulatedChannel(a);
  EXPECT_EQ(acoustic.format.min_bytes, 4u);
  EXPECT_EQ(acoustic.format.max_bytes, 4u);
  EXPECT_THROW(acoustic.Frame(std::vector<std::uint8_t>(64)), std::invalid_argument);
  EXPECT_DOUBLE_EQ(acoustic.Frame({1, 2, 3, 4}).airtime, nava_modem::ProfileAirtime(nava_modem::Profile::kRoom));
}

TEST(ChannelFactory, ServesTheRobotsAndMicrophonesAsked) {
  SimulatedChannelOptions o = ThresholdRoom();
  o.robots = {"robot_1"};
  o.microphones = {"none"};
  const SimulatedChannel c = BuildSimulatedChannel(o);
  EXPECT_EQ(c.robots, o.robots);
  EXPECT_EQ(c.microphones, (std::vector<world_sim::Microphone>{world_sim::Microphone::kNone}));
}

TEST(ChannelFactory, TakesTheCallersMapWhenTheOptionsNameNone) {
  SimulatedChannelOptions o;
  o.robots = {"a", "b", "c"};
  EXPECT_TRUE(NeedsMap(o));
  ExpectBuildError(o, "map", {"no map given"});
  const SimulatedChannel c = BuildSimulatedChannel(o, grid::LoadMapFile(kMaps + "/test_room.yaml"));
  EXPECT_EQ(c.microphones, std::vector<world_sim::Microphone>(3, world_sim::Microphone::kOmni));
  EXPECT_FALSE(NeedsMap(ThresholdRoom()));
}

TEST(ChannelFactory, ParsesEachChannelModelByItsName) {
  for (const ChannelModel m : {ChannelModel::kThreshold, ChannelModel::kAcoustic}) {
    EXPECT_EQ(ParseChannelModel(ChannelModelName(m)), m);
  }
  ExpectOptionError([] { ParseChannelModel("loud"); }, "channel_model", {"'loud'", kChannelModelNames});
  ExpectOptionError([] { ParseProfileOption("fast"); }, "profile", {"'fast'", nava_modem::kProfileNames});
  ExpectOptionError([] { ParseRuleOption("any"); }, "rule", {"'any'", "masks or convex_corners"});
  EXPECT_EQ(ParseRuleOption("convex_corners"), DiffractionRule::kConvexCorners);
}

TEST(ChannelFactory, RefusesAMissingWorldFile) {
  SimulatedChannelOptions o;
  o.world_file = kMaps + "/no_such_world.yaml";
  try {
    BuildSimulatedChannel(o);
    ADD_FAILURE() << "no error";
  } catch (const grid::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_world.yaml"), std::string::npos) << e.what();
  }
}

TEST(ChannelFactory, RefusesBadMicrophones) {
  SimulatedChannelOptions o = ThresholdRoom();
  o.microphones = {"omni"};
  ExpectBuildError(o, "microphones", {"one entry per robot (2), got 1"});
  o.microphones = {"omni", "stereo"};
  ExpectBuildError(o, "microphones[1]", {"'stereo'", "omni, bidirectional or none"});
}

TEST(ChannelFactory, RefusesRobotsTheWorldDoesNotHave) {
  SimulatedChannelOptions o = ThresholdRoom();
  o.robots = {"robot_0", "ghost"};
  ExpectBuildError(o, "robots", {"'ghost'", "test_room_world.yaml"});
}

TEST(ChannelFactory, RefusesTheAcousticModelWithoutAcoustics) {
  SimulatedChannelOptions o = ThresholdRoom();
  o.channel_model = ChannelModel::kAcoustic;
  ExpectBuildError(o, "channel_model", {"acoustics section", "test_room_world.yaml has none"});
  o = AcousticRoom();
  o.delivery_map_robot = "ghost";
  ExpectBuildError(o, "delivery_map_robot", {"'ghost'"});
  o = AcousticRoom();
  o.decode_table = kMaps + "/no_such_table.yaml";
  EXPECT_THROW(BuildSimulatedChannel(o), grid::InputError);
}

TEST(ChannelFactory, ChecksEachOptionsRange) {
  EXPECT_NO_THROW(CheckSimulatedChannelOptions(ThresholdRoom()));
  struct Bad {
    std::function<void(SimulatedChannelOptions&)> set;
    std::string field, words;
  };
  const std::vector<Bad> bad = {
      {[](auto& o) { o.source_level_db = std::numeric_limits<double>::quiet_NaN(); }, "source_level_db",
       "expected a number in [-1000, 1000], got nan"},
      {[](auto& o) { o.threshold_db = 80.0; }, "threshold_db", "expected at most source_level_db (70.000000), got 80.000000"},
      {[](auto& o) { o.source_level_db = 30.0; }, "threshold_db", "got 40.000000"},  // under the default threshold
      {[](auto& o) { o.max_range = -1.0; }, "max_range", "[0, 1e+06], got -1"},
      {[](auto& o) { o.speed_of_sound = 0.5; }, "speed_of_sound", "got 0.5"},
      {[](auto& o) { o.capture_margin_db = -1.0; }, "capture_margin_db", "got -1"},
      {[](auto& o) { o.direction_noise = 11.0; }, "direction_noise", "[0, 10], got 11"},
      {[](auto& o) { o.bit_rate = 0.5; }, "bit_rate", "[1, 100000], got 0.5"},
      {[](auto& o) { o.bit_rate = 100000.0; }, "bit_rate", "deaf_time"},  // a packet shorter than the MAC's deaf time
      {[](auto& o) {
         o.bit_rate = 300.0;
         o.profile = nava_modem::Profile::kRoom;
       },
       "bit_rate", "profile room has its own timing"},
      {[](auto& o) { o.seed = -1; }, "seed", "expected a whole number in [0, 2147483647], got -1"},
      {[](auto& o) { o.cache_size = 10000001; }, "cache_size", "got 10000001"},
      {[](auto& o) { o.decode_table = "table.yaml"; }, "decode_table", "only used by channel_model acoustic"},
      {[](auto& o) { o.delivery_map_robot = "robot_0"; }, "delivery_map_robot", "only used by channel_model acoustic"},
      {[](auto& o) { o.link_fate = true; }, "link_fate", "only used by channel_model acoustic"},
      {[](auto& o) { o.fate_distance = 0.0; }, "fate_distance", "expected a distance above 0 and at most 100 m"},
      {[](auto& o) { o.fate_distance = -0.1; }, "fate_distance", "got -0.1"},
      {[](auto& o) { o.world_file.clear(); }, "robots", "required"},
  };
  for (const Bad& b : bad) {
    SimulatedChannelOptions o = ThresholdRoom();
    b.set(o);
    ExpectCheckError(o, b.field, {b.words});
    ExpectBuildError(o, b.field, {b.words});  // the factory checks too
  }
}

}  // namespace
}  // namespace audio_propagation
