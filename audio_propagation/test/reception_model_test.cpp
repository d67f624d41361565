// The channel's reception models alone (ThresholdReception, AcousticReception), and the channel
// run over each: what every model must give the channel (a sender does not hear itself, nothing
// is heard while sending, the run is the same for a seed, a model of one's own plugs in).
#include "audio_propagation/reception_model.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "run_channel.h"

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/acoustic_reception.h"
#include "audio_propagation/audio_channel.h"
#include "audio_propagation/threshold_reception.h"

namespace audio_propagation {
namespace {

using world_sim::Microphone;

using test::Loud;

// A draw that must not be asked for.
double NoDraw() {
  ADD_FAILURE() << "the model drew where nothing is left to chance";
  return 0.0;
}

TEST(ThresholdReception, APacketSurvivesOnlyOverlapsWeakerByTheCaptureMargin) {
  const ThresholdReception model(30.0, 10.0, 0.0);
  const SoundPath path;
  const std::vector<Eigen::Vector2d> at(2, Eigen::Vector2d::Zero());
  EXPECT_TRUE(model.Decide(path, 1, 50.0, 0.0, 1.0, {}, at, NoDraw).packet);
  EXPECT_TRUE(model.Decide(path, 1, 50.0, 0.0, 1.0, {{40.0, 1e4}, {35.0, 1e3}}, at, NoDraw).packet);
  const Decision lost = model.Decide(path, 1, 50.0, 0.0, 1.0, {{35.0, 1e3}, {40.1, 1e4}}, at, NoDraw);
  EXPECT_FALSE(lost.packet);
  EXPECT_TRUE(lost.collision);
  EXPECT_TRUE(lost.heard);  // noise the receiver reports
}

TEST(ThresholdReception, HearsOnlyAudiblePathsAtTheirLevelInSilentAir) {
  const ThresholdReception model(30.0, 10.0, 5.0);
  SoundPath path;
  path.reachable = true;
  path.level_db = 42.0;
  path.audible = true;
  const std::vector<Eigen::Vector2d> at(2, Eigen::Vector2d::Zero());
  const ArrivalSound heard = model.Arrive(path, 1, at, 0.0);
  ASSERT_TRUE(heard.level_db);
  EXPECT_EQ(*heard.level_db, 42.0);
  EXPECT_FALSE(heard.probability);
  path.audible = false;
  EXPECT_FALSE(model.Arrive(path, 1, at, 0.0).level_db);
  EXPECT_EQ(model.LevelDb(0.0), 5.0);
  EXPECT_EQ(model.LevelDb(1.0), 5.0);  // 0 dB reads as the floor
  EXPECT_NEAR(model.LevelDb(1e3), 30.0, 1e-12);
  EXPECT_EQ(model.CarrierThresholdDb(), 30.0);
  EXPECT_EQ(model.BackgroundSeconds(), 0.0);
}

TEST(ThresholdReception, RefusesImpossibleOptionsByName) {
  try {
    ThresholdReception(30.0, -1.0, 0.0);
    FAIL() << "a negative capture margin was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("capture_margin_db"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ThresholdReception(30.0, 10.0, std::nan("")), std::invalid_argument);
}

// Two robots 10 m apart in an open room; the acoustic model with a table that decodes with
// probability `delivered` everywhere.
struct Room {
  PropagationModel model{grid::OccupancyMap(90, 10, 0.5), Loud()};
  std::unique_ptr<AcousticModel> acoustic;
  explicit Room(double delivered) {
    world_sim::Acoustics a;
    a.room.rt60 = 0.5;
    a.room.critical_distance = 3.0;
    a.ambient_db = 25.0;
    acoustic = std::make_unique<AcousticModel>(model, a, test::FlatTable("nava", delivered),
                                               std::vector<std::string>{"robot_0", "robot_1"});
  }
};

TEST(AcousticReception, TheDrawDecidesAgainstTheTable) {
  Room room(0.6);
  const AcousticReception model(*room.acoustic, 0.0);
  const std::vector<Eigen::Vector2d> at = {{2.0, 2.5}, {12.0, 2.5}};
  const SoundPath path = room.model.Path(at[0], at[1]);
  const ArrivalSound sound = model.Arrive(path, 1, at, 0.0);
  ASSERT_TRUE(sound.probability);
  EXPECT_NEAR(*sound.probability, 0.6, 1e-9);
  ASSERT_TRUE(sound.level_db);
  int draws = 0;
  const Decision kept = model.Decide(path, 1, *sound.level_db, 0.0, 0.4, {}, at, [&] { return ++draws, 0.59; });
  EXPECT_EQ(draws, 1);
  EXPECT_TRUE(kept.packet);
  EXPECT_NEAR(kept.probability, 0.6, 1e-9);
  // The flat table gives its failures no noise class: a receiver would not notice them.
  const Decision lost = model.Decide(path, 1, *sound.level_db, 0.0, 0.4, {}, at, [] { return 0.61; });
  EXPECT_FALSE(lost.packet);
  EXPECT_FALSE(lost.heard);
}

TEST(AcousticReception, AnOverlappingPacketIsTheDisturbance) {
  Room room(0.6);
  const AcousticReception model(*room.acoustic, 0.0);
  const std::vector<Eigen::Vector2d> at = {{2.0, 2.5}, {12.0, 2.5}};
  const SoundPath path = room.model.Path(at[0], at[1]);
  const double level = *model.Arrive(path, 1, at, 0.0).level_db;
  // As loud as the packet itself, over all of it: far below the table's SNR the chance fades.
  const Decision d = model.Decide(path, 1, level, 0.0, 0.4, {{level, std::pow(10.0, level / 10.0)}}, at, [] { return 0.0; });
  EXPECT_TRUE(d.collision);
  EXPECT_LT(d.probability, 0.6);
}

// The channel over either model.
class ChannelOverEachModel : public ::testing::TestWithParam<bool> {
 protected:
  Room room{1.0};
  std::unique_ptr<AudioChannel> Channel(std::size_t robots, const std::vector<double>& xs, std::uint32_t seed = 1) {
    ChannelOptions options;
    options.seed = seed;
    // A fixed carrier threshold under both models, so that neither calibrates first.
    options.mac.fixed_threshold_db = 30.0;
    auto channel = std::make_unique<AudioChannel>(room.model, std::vector<Microphone>(robots, Microphone::kOmni), options,
                                                  GetParam() ? room.acoustic.get() : nullptr);
    for (std::size_t k = 0; k < robots; ++k) channel->SetPose(k, {xs[k], 2.5, 0.0});
    return channel;
  }
};

TEST_P(ChannelOverEachModel, ALonePacketReachesItsNeighbourAndNotItsSender) {
  auto channel = Channel(2, {2.0, 12.0});
  EXPECT_EQ(channel->acoustic() != nullptr, GetParam());
  ASSERT_TRUE(channel->Send(0, {1, 2, 3, 4}));
  const AudioChannel::Events events = test::RunFor(*channel, 2.0);
  ASSERT_EQ(events.started.size(), 1u);
  EXPECT_EQ(events.started[0].probability.size(), GetParam() ? 2u : 0u);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_EQ(events.received[0].receiver, 1u);
  EXPECT_EQ(events.received[0].kind, Reception::Kind::kPacket);
  EXPECT_EQ(events.received[0].data, std::vector<std::uint8_t>({1, 2, 3, 4}));
}

TEST_P(ChannelOverEachModel, NothingIsHeardWhileSending) {
  auto channel = Channel(2, {2.0, 12.0});
  // Both at once: each is sending while the other's packet arrives.
  ASSERT_TRUE(channel->SendAt(0, {1, 1, 1, 1}, 0.5));
  ASSERT_TRUE(channel->SendAt(1, {2, 2, 2, 2}, 0.5));
  const AudioChannel::Events events = test::RunFor(*channel, 3.0);
  EXPECT_EQ(events.started.size(), 2u);
  EXPECT_TRUE(events.received.empty());
  EXPECT_EQ(channel->missed_while_sending(), 2u);
}

TEST_P(ChannelOverEachModel, TheSameSeedGivesTheSameRun) {
  auto run = [&](std::uint32_t seed) {
    auto channel = Channel(4, {2.0, 6.0, 10.0, 14.0}, seed);
    for (std::size_t k = 0; k < 4; ++k) channel->SendAt(k, {static_cast<std::uint8_t>(k), 0, 0, 0}, 0.1 * static_cast<double>(k));
    std::string record;
    for (const Reception& r : test::RunFor(*channel, 8.0).received) {
      record += std::to_string(r.receiver) + "<" + std::to_string(r.sender) + "@" + std::to_string(r.time) +
                (r.kind == Reception::Kind::kPacket ? "P " : "N ");
    }
    return record;
  };
  const std::string a = run(7);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, run(7));
}

INSTANTIATE_TEST_SUITE_P(Models, ChannelOverEachModel, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "Acoustic" : "Threshold"; });

// A reception model of one's own: here every packet is lost to noise of one class, which the
// channel reports as the model says.
class AlwaysBadCrc : public ThresholdReception {
 public:
  AlwaysBadCrc() : ThresholdReception(30.0, 10.0, 0.0) {}
  Decision Decide(const SoundPath&, std::size_t, double, double, double, const std::vector<Overlap>&,
                  const std::vector<Eigen::Vector2d>&, const std::function<double()>&) const override {
    Decision d;
    d.noise = nava_modem::RxEvent::Noise::kBadCrc;
    d.probability = 0.0;
    return d;
  }
};

TEST(AudioChannelReception, AModelOfOnesOwnDecides) {
  PropagationModel model(grid::OccupancyMap(90, 10, 0.5), Loud());
  AudioChannel channel(model, std::vector<Microphone>(2, Microphone::kOmni), ChannelOptions{}, std::make_unique<AlwaysBadCrc>());
  channel.SetPose(0, {2.0, 2.5, 0.0});
  channel.SetPose(1, {12.0, 2.5, 0.0});
  ASSERT_TRUE(channel.Send(0, {1, 2, 3, 4}));
  const AudioChannel::Events events = test::RunFor(channel, 2.0);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_EQ(events.received[0].kind, Reception::Kind::kNoise);
  EXPECT_EQ(events.received[0].noise, nava_modem::RxEvent::Noise::kBadCrc);
  EXPECT_TRUE(events.received[0].data.empty());
  EXPECT_THROW(AudioChannel(model, {}, ChannelOptions{}, std::unique_ptr<ReceptionModel>()), std::invalid_argument);
}

}  // namespace
}  // namespace audio_propagation
