#include "audio_propagation/acoustic_model.h"

#include <cmath>
#include <functional>
#include <map>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "run_channel.h"

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/carrier_share.h"
#include "audio_propagation/delivery_map.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/wav_file.h"

namespace audio_propagation {
namespace {

using world_sim::Microphone;

// A made-up table that is easy to reason about: delivery rises linearly from 0 at SNR -10 dB to
// 1 at +10 dB, whatever the kind, halved at DRR -20 dB; of the failures a quarter are
// zero_byte and a quarter one_byte, the rest unheard.
DecodeTable LinearTable() {
  DecodeTable t = test::FlatTable("nava");
  t.packets = 100;
  t.snr_db = {-10.0, 10.0};
  t.drr_db = {-20.0, 0.0};
  t.rt60 = {0.5};
  t.Resize();
  for (std::size_t k = 0; k < kInterferenceCount; ++k) {
    for (std::size_t d = 0; d < 2; ++d) {
      for (std::size_t s = 0; s < 2; ++s) {
        DecodeOutcome& o = t.At(static_cast<Interference>(k), 0, d, s);
        o.packet = (s == 1 ? 1.0 : 0.0) * (d == 0 ? 0.5 : 1.0);
        o.zero_byte = 0.25 * (1.0 - o.packet);
        o.one_byte = 0.25 * (1.0 - o.packet);
      }
    }
  }
  return t;
}

world_sim::Acoustics Quiet() {
  world_sim::Acoustics a;
  a.room.rt60 = 0.5;
  a.room.critical_distance = 2.0;
  a.ambient_db = 20.0;
  return a;
}

PropagationOptions Options() {
  PropagationOptions o;
  o.threshold_db = 0.0;  // every path is computed; the acoustic model decides
  o.threads = 1;
  return o;
}

// An open strip 45 x 5 m.
struct Strip {
  PropagationModel model{grid::OccupancyMap(90, 10, 0.5), Options()};
  SoundPath Path(double x0, double x1) const { return model.Path({x0, 2.5}, {x1, 2.5}); }
};

TEST(AcousticThreshold, TheModelJudgesEveryPathDownTo30DbUnderTheAmbientAndNoHearingRangeUnlessKept) {
  PropagationOptions o;
  o.max_range = 15.0;
  o.threshold_db = 20.0;
  world_sim::Acoustics a = Quiet();  // ambient 20 dB
  UseAcousticPropagation(o, a, true);
  EXPECT_EQ(o.max_range, 15.0);
  EXPECT_EQ(o.threshold_db, -10.0);
  a.ambient_db = 50.0;  // a louder world never raises the threshold another world lowered
  UseAcousticPropagation(o, a);
  EXPECT_EQ(o.max_range, 0.0);
  EXPECT_EQ(o.threshold_db, -10.0);
}

TEST(TeamAcousticModel, NoneWithoutATableAndAWorldWithoutAcousticsIsRefused) {
  const Strip strip;
  world_sim::WorldConfig world;
  world.robots.resize(2);
  world.robots[0].name = "a";
  world.robots[1].name = "b";
  const auto table = std::make_shared<const DecodeTable>(test::FlatTable("nava", 1.0));
  EXPECT_EQ(TeamAcousticModel(strip.model, world, nullptr), nullptr);
  EXPECT_THROW(TeamAcousticModel(strip.model, world, table), std::invalid_argument);
  world.acoustics = Quiet();
  // A noise source riding on robot b: the model knows the world's robots by name.
  world.acoustics->noise_sources.push_back({});
  world.acoustics->noise_sources.back().name = "motor";
  world.acoustics->noise_sources.back().robot = "b";
  const auto model = TeamAcousticModel(strip.model, world, table);
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->table().profile, "nava");
  world.acoustics->noise_sources.back().robot = "c";
  EXPECT_THROW(TeamAcousticModel(strip.model, world, table), std::invalid_argument);
}

// A recording of `hz` (a steady tone, 1 s at 48 kHz) written for a recorded noise source.
std::string ToneFile(const std::string& name, double hz) {
  std::vector<float> x(48000);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = static_cast<float>(0.3 * std::sin(2.0 * std::acos(-1.0) * hz * k / 48000.0));
  const std::string path = ::testing::TempDir() + "/acoustic_model_" + name + ".wav";
  nava_modem::WriteWavFile(path, x, 48000.0);
  return path;
}

TEST(RecordedNoise, ARecordingCountsAsWhiteNoiseWithItsPowerWhereTheReceiverListens) {
  const Strip strip;
  world_sim::Acoustics a = Quiet();
  a.ambient_db = -50.0;  // only the source is heard
  world_sim::NoiseSourceSpec source;
  source.name = "source";
  source.x = 20.0, source.y = 2.5;
  source.level_db = 60.0;
  source.kind = world_sim::NoiseKind::kWhite;
  const auto snr = [&](const world_sim::NoiseSourceSpec& s) {
    world_sim::Acoustics with = a;
    with.noise_sources = {s};
    const AcousticModel model(strip.model, with, test::FlatTable("nava", 1.0), {});
    const Eigen::Vector2d listener(10.0, 2.5);
    return model.Predict(strip.Path(5.0, 10.0), listener, model.NoiseAt(listener, 0.0, {})).snr_db;
  };
  const double white = snr(source);
  world_sim::NoiseSourceSpec recorded = source;
  recorded.kind = world_sim::NoiseKind::kRecording;
  // On nava's mark all its power is where nava listens: 600 of 24000 Hz, 16 dB worse than white.
  recorded.file = ToneFile("mark", 2300.0);
  EXPECT_NEAR(snr(recorded), white - 16.02, 0.2);
  // Between the tones, next to nothing.
  recorded.file = ToneFile("between", 3000.0);
  EXPECT_GT(snr(recorded), white + 25.0);
  // A recording that is none is refused, naming the source and the file.
  recorded.file = ::testing::TempDir() + "/acoustic_model_missing.wav";
  world_sim::Acoustics bad = a;
  bad.noise_sources = {recorded};
  try {
    AcousticModel model(strip.model, bad, test::FlatTable("nava", 1.0), {});
    ADD_FAILURE() << "a missing recording was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("noise source 'source' (" + recorded.file + ")"), std::string::npos) << e.what();
  }
}

TEST(RecordedNoise, ARecordingThatComesAndGoesHarmsRoomLessThanSteadyNoiseOfItsPower) {
  // The room profile's code rides over the cells a noise spares (nava_modem::RecordingWeight):
  // running water, dishes, speech. A table whose packets go from none at -30 dB to all at 0 dB.
  DecodeTable table = test::FlatTable("room", 0.0);
  table.snr_db = {-30.0, 0.0};
  table.Resize();
  for (std::size_t k = 0; k < kInterferenceCount; ++k) table.At(static_cast<Interference>(k), 0, 0, 1).packet = 1.0;
  const Strip strip;
  world_sim::Acoustics a = Quiet();
  a.ambient_db = -50.0;
  world_sim::NoiseSourceSpec source;
  source.name = "tap";
  source.x = 20.0, source.y = 2.5;
  source.level_db = 90.0;  // the link at about -15 dB, half way up the table
  source.kind = world_sim::NoiseKind::kRecording;
  const auto predict = [&](const std::vector<float>& x, const std::string& name) {
    const std::string path = ::testing::TempDir() + "/acoustic_model_" + name + ".wav";
    nava_modem::WriteWavFile(path, x, 48000.0);
    world_sim::Acoustics with = a;
    source.file = path;
    with.noise_sources = {source};
    const AcousticModel model(strip.model, with, table, {});
    const Eigen::Vector2d listener(10.0, 2.5);
    return model.Predict(strip.Path(5.0, 10.0), listener, model.NoiseAt(listener, 0.0, {}));
  };
  std::vector<double> white = nava_modem::WhiteNoise(48000 * 8, 4);
  std::vector<float> steady(white.begin(), white.end()), bursts = steady;
  // On for 0.1 s in 0.5 s, 40 dB down between, at the same mean power as the steady noise.
  double power = 0.0;
  for (std::size_t k = 0; k < bursts.size(); ++k) {
    if (std::fmod(k / 48000.0, 0.5) >= 0.1) bursts[k] *= 0.01f;
    power += static_cast<double>(bursts[k]) * bursts[k] / static_cast<double>(bursts.size());
  }
  for (float& x : bursts) x = static_cast<float>(x / std::sqrt(power));
  const LinkPrediction flat = predict(steady, "steady"), coming = predict(bursts, "bursts");
  ASSERT_NEAR(flat.snr_db, coming.snr_db, 0.3);  // the same power where room listens
  ASSERT_GT(flat.probability, 0.05);
  ASSERT_LT(flat.probability, 0.95);
  EXPECT_GT(coming.probability, flat.probability + 0.05) << "at " << flat.snr_db << " dB";
}

TEST(LinkBudget, DirectAndReverberantMeetAtTheCriticalDistanceAndCornersCostTheDirectSound) {
  world_sim::RoomAcoustics room;
  room.rt60 = 1.0;
  room.critical_distance = 4.0;
  const LinkLevels at_rc = LinkBudget(70.0, 1.0, 4.0, 0, 6.0, room);
  EXPECT_NEAR(at_rc.direct_db, 70.0 - 20.0 * std::log10(4.0), 1e-9);
  // Equal but for the slow decay of the reverberant field along the path (0.174 dB/m/s).
  EXPECT_NEAR(at_rc.drr_db, 0.174 * 4.0, 1e-9);
  EXPECT_NEAR(at_rc.total_db, 10.0 * std::log10(std::pow(10.0, at_rc.direct_db / 10) + std::pow(10.0, at_rc.reverberant_db / 10)), 1e-9);
  const LinkLevels round_two = LinkBudget(70.0, 1.0, 4.0, 2, 6.0, room);
  EXPECT_NEAR(round_two.direct_db, at_rc.direct_db - 12.0, 1e-9);
  EXPECT_NEAR(round_two.reverberant_db, at_rc.reverberant_db, 1e-9);
  // Sabine: a 1000 m^3 room with RT60 1 s has its critical distance near 1.8 m.
  world_sim::RoomAcoustics hall;
  hall.rt60 = 1.0;
  hall.volume = 1000.0;
  EXPECT_NEAR(world_sim::CriticalDistance(hall), 1.79, 0.01);
}

TEST(AcousticModel, DeliveryFallsWithDistanceAsTheDirectSoundDrownsInTheRoom) {
  Strip strip;
  world_sim::Acoustics a = Quiet();
  a.ambient_db = 45.0;
  const AcousticModel model(strip.model, a, LinearTable(), {});
  double last = 2.0;
  for (double d : {1.0, 3.0, 8.0, 15.0, 30.0}) {
    const Eigen::Vector2d at(1.0 + d, 2.5);
    const LinkPrediction p = model.Predict(strip.Path(1.0, 1.0 + d), at, model.NoiseAt(at, 0.0, {}));
    EXPECT_LT(p.probability, last) << d << " m";
    EXPECT_LT(p.signal.drr_db, d < 2.0 ? 100.0 : 0.0) << d << " m: beyond the critical distance the room is louder";
    last = p.probability;
  }
  EXPECT_GT(last, -1e-12);
}

// The quiet room with a radio at (12, 2.5) talking for 0-5 s of every 10.
world_sim::Acoustics QuietWithRadio() {
  world_sim::Acoustics a = Quiet();
  world_sim::NoiseSourceSpec radio;
  radio.name = "radio";
  radio.x = 12.0;
  radio.y = 2.5;
  radio.kind = world_sim::NoiseKind::kSpeech;
  radio.level_db = 66.0;
  radio.duty = 0.5;
  radio.period = 10.0;
  a.noise_sources.push_back(radio);
  return a;
}

TEST(AcousticModel, ANoiseSourceByTheListenerHurtsWhileItSoundsAndOnlyThen) {
  Strip strip;
  const AcousticModel model(strip.model, QuietWithRadio(), LinearTable(), {});
  const Eigen::Vector2d listener(11.0, 2.5);
  const SoundPath path = strip.Path(5.0, 11.0);
  const LinkPrediction on = model.Predict(path, listener, model.NoiseAt(listener, 2.0, {}));
  const LinkPrediction off = model.Predict(path, listener, model.NoiseAt(listener, 7.0, {}));
  EXPECT_EQ(on.kind, Interference::kSpeech);
  EXPECT_EQ(off.kind, Interference::kPink);  // only the ambient sound is left
  EXPECT_LT(on.snr_db, off.snr_db - 10.0);
  EXPECT_LT(on.probability, off.probability);
  // Far from the radio a listener hardly minds it.
  const Eigen::Vector2d far(40.0, 2.5);
  const LinkPrediction far_on = model.Predict(strip.Path(34.0, 40.0), far, model.NoiseAt(far, 2.0, {}));
  EXPECT_GT(far_on.probability, on.probability);
}

TEST(AcousticModel, OverAPacketANoiseSourceCountsForTheShareOfItThatItSounds) {
  world_sim::NoiseSourceSpec s;
  s.duty = 0.5;
  s.period = 10.0;
  s.phase = 2.0;  // on from 2 to 7 s, 12 to 17 s, ...
  EXPECT_DOUBLE_EQ(world_sim::SoundingFraction(s, 2.5, 6.5), 1.0);
  EXPECT_DOUBLE_EQ(world_sim::SoundingFraction(s, 7.0, 12.0), 0.0);
  EXPECT_NEAR(world_sim::SoundingFraction(s, 6.0, 8.0), 0.5, 1e-12);
  EXPECT_NEAR(world_sim::SoundingFraction(s, 1.0, 21.0), 0.5, 1e-12);
  EXPECT_NEAR(world_sim::SoundingFraction(s, -4.0, -2.0), 0.5, 1e-12);  // on from -8 to -3 s
  EXPECT_DOUBLE_EQ(world_sim::SoundingFraction(s, 3.0, 3.0), 1.0);      // a moment: Sounding
  EXPECT_DOUBLE_EQ(world_sim::SoundingFraction(s, 8.0, 8.0), 0.0);
  // The fraction and Sounding agree moment by moment (they drifted apart once, when the phase
  // turned round in one and not the other).
  for (double t0 = -10.0; t0 < 10.0; t0 += 0.37) {
    int on = 0;
    for (int k = 0; k < 1000; ++k) on += world_sim::Sounding(s, t0 + (k + 0.5) * 0.003);
    EXPECT_NEAR(world_sim::SoundingFraction(s, t0, t0 + 3.0), on / 1000.0, 0.002) << t0;
  }
  s.duty = 1.0;
  EXPECT_DOUBLE_EQ(world_sim::SoundingFraction(s, 14.0, 15.0), 1.0);

  Strip strip;
  const AcousticModel model(strip.model, QuietWithRadio(), LinearTable(), {});
  const Eigen::Vector2d listener(11.0, 2.5);
  const std::vector<Disturbance> at = model.NoiseAt(listener, 4.0, {});
  const std::vector<Disturbance> over = model.NoiseDuring(listener, 4.0, 6.0, {});  // half of it on
  ASSERT_EQ(at.size(), 2u);
  ASSERT_EQ(over.size(), 2u);
  EXPECT_DOUBLE_EQ(over[0].power, at[0].power);  // the ambient sound is always there
  EXPECT_NEAR(over[1].power, 0.5 * at[1].power, 1e-9 * at[1].power);
  EXPECT_EQ(model.NoiseDuring(listener, 5.5, 9.5, {}).size(), 1u);  // off all the while
}

TEST(AcousticModel, ASourceCountsHowLongItHasSoundedSinceItStarted) {
  world_sim::NoiseSourceSpec s;
  s.duty = 0.5;
  s.period = 10.0;
  s.phase = 2.0;  // on from 2 to 7 s, 12 to 17 s, ...
  EXPECT_NEAR(world_sim::SoundingFor(s, 2.5), 0.5, 1e-12);
  EXPECT_NEAR(world_sim::SoundingFor(s, 16.0), 4.0, 1e-12);
  EXPECT_NEAR(world_sim::SoundingFor(s, -5.0), 3.0, 1e-12);  // on from -8 to -3 s
  EXPECT_DOUBLE_EQ(world_sim::SoundingFor(s, 8.0), 0.0);     // silent
  s.duty = 1.0;
  EXPECT_TRUE(std::isinf(world_sim::SoundingFor(s, 8.0)));
}

// The radio's place, level and duty, as a pump's whine on from 0 to 10 s of every 20.
world_sim::Acoustics QuietWithPump() {
  world_sim::Acoustics a = QuietWithRadio();
  world_sim::NoiseSourceSpec& pump = a.noise_sources.at(0);
  pump.name = "pump";
  pump.kind = world_sim::NoiseKind::kWhine;
  pump.frequency = 900.0;
  pump.period = 20.0;
  return a;
}

TEST(AcousticModel, AWhineTheRoomReceiverHasNotYetWhitenedCountsAsWhiteNoise) {
  Strip strip;
  DecodeTable room_table = LinearTable();
  room_table.profile = "room";
  const Eigen::Vector2d listener(11.0, 2.5);
  const double settle = nava_modem::WhineSettleSeconds(nava_modem::Profile::kRoom);
  EXPECT_GT(settle, 3.0);  // the chirp detector's whitening window and its CFAR background
  EXPECT_LT(settle, 4.0);
  EXPECT_DOUBLE_EQ(nava_modem::WhineSettleSeconds(nava_modem::Profile::kNava), 0.0);

  const AcousticModel room(strip.model, QuietWithPump(), room_table, {});
  const std::vector<Disturbance> steady = room.NoiseDuring(listener, settle + 1.0, settle + 3.0, {});
  const std::vector<Disturbance> fresh = room.NoiseDuring(listener, settle - 1.0, settle + 1.0, {});
  const std::vector<Disturbance> starting = room.NoiseDuring(listener, 19.0, 21.0, {});  // half of it on
  ASSERT_EQ(steady.size(), 2u);
  ASSERT_EQ(fresh.size(), 2u);
  ASSERT_EQ(starting.size(), 2u);
  EXPECT_EQ(steady[1].kind, Interference::kWhine);
  EXPECT_EQ(fresh[1].kind, Interference::kWhite);
  EXPECT_EQ(starting[1].kind, Interference::kWhite);
  EXPECT_DOUBLE_EQ(fresh[1].power, steady[1].power);
  EXPECT_NEAR(starting[1].power, 0.5 * steady[1].power, 1e-9 * steady[1].power);
  // At the power of its harmonics in the band (900, 1800 and 2700 Hz: all of it), where the
  // tables count white noise by its full-band power.
  EXPECT_GT(fresh[1].listened, 0.9);
  EXPECT_LE(fresh[1].listened, 1.0);
  world_sim::Acoustics hum = QuietWithPump();
  hum.noise_sources[0].frequency = 150.0;  // 150, 300, 450 Hz: under room's band
  const AcousticModel hummed(strip.model, hum, room_table, {});
  EXPECT_LT(hummed.NoiseDuring(listener, 1.0, 2.0, {})[1].listened, 0.01);
  // The model judges it on the white cells, at an SNR that much lower.
  const SoundPath path = strip.Path(1.0, 11.0);
  EXPECT_EQ(room.Predict(path, listener, fresh).kind, Interference::kWhite);
  EXPECT_EQ(room.Predict(path, listener, steady).kind, Interference::kWhine);

  // nava does not whiten: a whine is a whine from its first moment.
  const AcousticModel nava(strip.model, QuietWithPump(), LinearTable(), {});
  EXPECT_EQ(nava.NoiseDuring(listener, 0.5, 2.5, {})[1].kind, Interference::kWhine);
}

TEST(AcousticModel, AWhineCountsByItsHarmonicsInTheBandAndHowCloseTheyComeToNavasTones) {
  Strip strip;
  const AcousticModel model(strip.model, Quiet(), LinearTable(), {});  // nava: tones 2300, 3700 Hz
  // The table's whine, between the tones: its fundamental counts at the -10 dB floor.
  const double between = 0.1 / 1.3125;
  Disturbance table{Interference::kWhine, 1.0, 3000.0};
  Disturbance low{Interference::kWhine, 1.0, 200.0};      // harmonics at 400 and 600 Hz: all below
  Disturbance on_tone{Interference::kWhine, 1.0, 2300.0};  // fundamental on MARK, 4600 Hz out of band
  Disturbance near{Interference::kWhine, 1.0, 1200.0};     // 2400 and 3600 Hz: 100 Hz from a tone
  EXPECT_NEAR(model.EffectivePower(table), 1.0, 1e-12);
  EXPECT_NEAR(model.EffectivePower(low), 0.01 / between, 1e-9);  // leaks at -20 dB
  EXPECT_NEAR(model.EffectivePower(on_tone), (1.0 / 1.3125) / between, 1e-9);  // 10 dB worse
  EXPECT_NEAR(model.EffectivePower(near), (0.3125 / 1.3125) / between, 1e-9);
  EXPECT_GT(model.EffectivePower(near), model.EffectivePower(table));
  EXPECT_NEAR(model.EffectivePower({Interference::kSpeech, 2.5, 0.0}), 2.5, 1e-12);  // others as they are
}

TEST(AcousticModel, AWhineCountsByTheTablesMeasuredHarmCurveWhereItHasOne) {
  DecodeTable table = LinearTable();
  table.whine_harm_hz = {1000.0, 1200.0, 3000.0};
  table.whine_harm_db = {-7.0, 8.0, 0.0};
  Strip strip;
  const AcousticModel model(strip.model, Quiet(), table, {});
  EXPECT_NEAR(model.EffectivePower({Interference::kWhine, 2.0, 1200.0}), 2.0 * std::pow(10.0, 0.8), 1e-9);
  EXPECT_NEAR(model.EffectivePower({Interference::kWhine, 1.0, 1100.0}), std::pow(10.0, 0.05), 1e-9);
  EXPECT_NEAR(model.EffectivePower({Interference::kWhine, 1.0, 3000.0}), 1.0, 1e-12);
  EXPECT_NEAR(model.EffectivePower({Interference::kWhite, 2.5, 0.0}), 2.5, 1e-12);  // others as they are
}

TEST(AcousticModel, BelowTheTablesQuietestSnrWhatTheReceiverStillDecodesFadesOut) {
  DecodeTable table = LinearTable();
  for (DecodeOutcome& o : table.cells) o = {0.6, 0.2, 0.1, 0.0};  // flat: the table cannot tell
  Strip strip;
  world_sim::Acoustics a = Quiet();
  const AcousticModel model(strip.model, a, table, {});
  const SoundPath path = strip.Path(2.0, 7.0);
  auto at = [&](double snr_db) {
    const double signal = model.Levels(path, {7.0, 2.5}).total_db;
    return model.Predict(path, {7.0, 2.5}, {{Interference::kWhite, std::pow(10.0, (signal - snr_db) / 10.0), 0.0}});
  };
  EXPECT_NEAR(at(-10.0).probability, 0.6, 1e-9);  // the axis' lowest SNR
  EXPECT_NEAR(at(-15.0).probability, 0.3, 1e-9);
  EXPECT_NEAR(at(-15.0).outcome.zero_byte, 0.1, 1e-9);
  EXPECT_NEAR(at(-20.0).probability, 0.0, 1e-9);
  EXPECT_NEAR(at(-40.0).outcome.Nothing(), 1.0, 1e-9);
}

TEST(AcousticModel, NoiseSourcesMustStandInFreeSpaceOrRideOnATeamRobot) {
  Strip strip;
  world_sim::Acoustics a = Quiet();
  world_sim::NoiseSourceSpec s;
  s.name = "fan";
  s.x = 100.0;
  a.noise_sources = {s};
  EXPECT_THROW(AcousticModel(strip.model, a, LinearTable(), {}), std::invalid_argument);
  a.noise_sources[0].robot = "robot_9";
  try {
    AcousticModel(strip.model, a, LinearTable(), {"robot_0"});
    FAIL() << "a source on a robot not in the team was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("robot_9"), std::string::npos) << e.what();
  }
  a.noise_sources.clear();
  a.room.rt60 = 0.0;
  EXPECT_THROW(AcousticModel(strip.model, a, LinearTable(), {}), std::invalid_argument);
}

// Channels over the strip with the acoustic model.
struct AcousticTeam {
  Strip strip;
  std::unique_ptr<AcousticModel> model;
  std::unique_ptr<AudioChannel> channel;

  AcousticTeam(const std::vector<double>& xs, world_sim::Acoustics a, std::uint32_t seed = 1, bool link_fate = false) {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < xs.size(); ++k) names.push_back("robot_" + std::to_string(k));
    model = std::make_unique<AcousticModel>(strip.model, a, LinearTable(), names);
    ChannelOptions o;
    o.seed = seed;
    o.link_fate = link_fate;
    channel = std::make_unique<AudioChannel>(strip.model, std::vector<Microphone>(xs.size(), Microphone::kOmni), o,
                                             model.get());
    for (std::size_t k = 0; k < xs.size(); ++k) channel->SetPose(k, {xs[k], 2.5, 0.0});
    Run(nava_modem::MacOptions().calibration_time);  // every robot calibrates on the room's noise
  }
  AudioChannel::Events Run(double seconds) { return test::RunFor(*channel, seconds); }
};

TEST(AcousticChannel, PacketsAreDecodedAndFailuresReportedAtTheTablesRates) {
  // 20 m apart in a quiet room the link sits mid-table: about half the packets get through.
  world_sim::Acoustics a = Quiet();
  a.ambient_db = 38.0;
  AcousticTeam team({2.0, 22.0}, a);
  const LinkPrediction expected =
      team.model->Predict(team.strip.Path(2.0, 22.0), {22.0, 2.5}, team.model->NoiseAt({22.0, 2.5}, 0.0, {}));
  ASSERT_GT(expected.probability, 0.2);
  ASSERT_LT(expected.probability, 0.8);
  const int sent = 400;
  std::map<int, int> classes;  // -1 packet, else the noise class
  for (int k = 0; k < sent; ++k) {
    ASSERT_TRUE(team.channel->Send(0, {1, 2, 3, static_cast<std::uint8_t>(k)}));
    for (const Reception& rx : team.Run(1.0).received) {
      EXPECT_EQ(rx.receiver, 1u);
      EXPECT_NEAR(rx.probability, expected.probability, 1e-9);
      ++classes[rx.kind == Reception::Kind::kPacket ? -1 : static_cast<int>(rx.noise)];
    }
  }
  const double p = expected.probability, fail = 1.0 - p;
  // Binomial: 4 standard deviations of 400 draws.
  auto near = [&](int count, double rate) { EXPECT_NEAR(count, sent * rate, 4.0 * std::sqrt(sent * rate * (1 - rate)) + 1); };
  near(classes[-1], p);
  near(classes[static_cast<int>(nava_modem::RxEvent::Noise::kZeroByte)], 0.25 * fail);
  near(classes[static_cast<int>(nava_modem::RxEvent::Noise::kOneByte)], 0.25 * fail);
  EXPECT_EQ(classes[static_cast<int>(nava_modem::RxEvent::Noise::kBadCrc)], 0);
  // The rest went unheard, as the real receiver would miss them.
  EXPECT_EQ(team.channel->unheard(), static_cast<std::uint64_t>(sent - classes[-1] - classes[1] - classes[2]));
}

// A link 20 m long in a quiet room that the table gives about half its packets (as above).
world_sim::Acoustics HalfwayRoom() {
  world_sim::Acoustics a = Quiet();
  a.ambient_db = 38.0;
  return a;
}

// Packets robot 0 sends robot 1, one a second, robot 1 at `listener_x(k)` for packet k: how
// many were decoded.
int Delivered(AcousticTeam& team, int sent, const std::function<double(int)>& listener_x) {
  int delivered = 0;
  for (int k = 0; k < sent; ++k) {
    team.channel->SetPose(1, {listener_x(k), 2.5, 0.0});
    EXPECT_TRUE(team.channel->Send(0, {1, 2, 3, static_cast<std::uint8_t>(k)}));
    for (const Reception& rx : team.Run(1.0).received) delivered += rx.kind == Reception::Kind::kPacket;
  }
  return delivered;
}

TEST(AcousticChannel, AStaticLinkKeepsItsFateAndOverManyLinksDeliveryFollowsTheTable) {
  const double p = [] {
    AcousticTeam team({2.0, 22.0}, HalfwayRoom());
    return team.model->Predict(team.strip.Path(2.0, 22.0), {22.0, 2.5}, team.model->NoiseAt({22.0, 2.5}, 0.0, {})).probability;
  }();
  ASSERT_GT(p, 0.2);
  ASSERT_LT(p, 0.8);
  const int links = 60, sent = 20;
  int all = 0, none = 0, mixed_without_fate = 0;
  for (int link = 1; link <= links; ++link) {
    AcousticTeam kept({2.0, 22.0}, HalfwayRoom(), static_cast<std::uint32_t>(link), true);
    const int n = Delivered(kept, sent, [](int) { return 22.0; });
    all += n == sent;
    none += n == 0;
    AcousticTeam drawn({2.0, 22.0}, HalfwayRoom(), static_cast<std::uint32_t>(link), false);
    const int m = Delivered(drawn, sent, [](int) { return 22.0; });
    mixed_without_fate += m > 0 && m < sent;
  }
  EXPECT_EQ(all + none, links);  // every static link all or nothing
  EXPECT_NEAR(all, links * p, 4.0 * std::sqrt(links * p * (1 - p)) + 1);
  EXPECT_GE(mixed_without_fate, links - 2);  // drawn anew, 20 packets at p are almost never unanimous
}

TEST(AcousticChannel, ALinkDrawsItsFateAgainWhenARobotMovesFartherThanTheFateDistance) {
  // Stepping 5 cm to and fro (within 7.5 cm of where the draw was made): the fate holds.
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    AcousticTeam team({2.0, 22.0}, HalfwayRoom(), seed, true);
    const int n = Delivered(team, 20, [](int k) { return k % 2 ? 22.05 : 22.0; });
    EXPECT_TRUE(n == 0 || n == 20) << n;
  }
  // Stepping 10 cm each packet: every packet meets a new fate, and delivery is the table's.
  AcousticTeam team({2.0, 22.0}, HalfwayRoom(), 7, true);
  const double p =
      team.model->Predict(team.strip.Path(2.0, 22.0), {22.0, 2.5}, team.model->NoiseAt({22.0, 2.5}, 0.0, {})).probability;
  const int sent = 400;
  const int n = Delivered(team, sent, [](int k) { return k % 2 ? 22.1 : 22.0; });
  EXPECT_NEAR(n, sent * p, 4.0 * std::sqrt(sent * p * (1 - p)) + 1);
  EXPECT_GT(n, 0);
  EXPECT_LT(n, sent);
}

TEST(AcousticChannel, RefusesAFateDistanceThatIsNotAboveZero) {
  ChannelOptions o;
  for (double d : {0.0, -0.1, std::nan("")}) {
    o.fate_distance = d;
    try {
      ValidateOptions(o);
      ADD_FAILURE() << d << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("fate_distance"), std::string::npos) << e.what();
    }
  }
}

TEST(AcousticChannel, TwoRobotsTalkingAtOnceGiveNoiseWhenEvenAndCaptureWhenOneIsFarLouder) {
  // Listener at 10; a near sender at 9 and a far one at 40 (silent room, no ambient to speak of).
  world_sim::Acoustics a = Quiet();
  a.ambient_db = -40.0;
  a.room.critical_distance = 20.0;  // a dry room: the direct sound rules
  int captured = 0, even_heard = 0;
  for (std::uint32_t seed = 1; seed <= 30; ++seed) {
    AcousticTeam far({10.0, 9.0, 40.0}, a, seed);
    far.channel->Send(1, {1, 1, 1, 1});
    far.channel->Send(2, {2, 2, 2, 2});
    for (const Reception& rx : far.Run(2.0).received) {
      if (rx.receiver == 0 && rx.kind == Reception::Kind::kPacket && rx.data[0] == 1) ++captured;
    }
    AcousticTeam even({10.0, 5.0, 15.0}, a, seed);
    even.channel->Send(1, {1, 1, 1, 1});
    even.channel->Send(2, {2, 2, 2, 2});
    for (const Reception& rx : even.Run(2.0).received) {
      if (rx.receiver == 0 && rx.kind == Reception::Kind::kPacket) ++even_heard;
      if (rx.receiver == 0) {
        EXPECT_TRUE(rx.collision || rx.kind == Reception::Kind::kPacket);
      }
    }
  }
  // CSMA spreads some pairs apart (then both are heard); those that overlap decide the rest.
  EXPECT_GE(captured, 25);
  EXPECT_LT(even_heard, 2 * 30);
}

TEST(AcousticChannel, TheCarrierThresholdSitsAboveTheRoomsNoiseAsACalibratedRobotsWould) {
  world_sim::Acoustics a = Quiet();
  a.ambient_db = 40.0;
  AcousticTeam team({2.0, 6.0}, a);
  team.Run(0.5);
  // The level meter hears the pink noise's share in nava's bands, as a robot's receiver does.
  const double heard = 40.0 + 10.0 * std::log10(CarrierShare(a.ambient_kind, 0.0, nava_modem::Profile::kNava,
                                                             kTableSampleRate));
  EXPECT_LT(heard, 40.0 - 10.0);
  EXPECT_NEAR(team.channel->mac(0).threshold_db(), heard + nava_modem::MacOptions().threshold_margin_db, 1e-9);
  EXPECT_NEAR(team.channel->Level(1), heard, 1e-6);
  EXPECT_FALSE(team.channel->Carrier(1));
  team.channel->Send(0, {1, 2, 3, 4});
  bool carrier = false;
  for (int k = 0; k < 20 && !carrier; ++k) {
    team.channel->AdvanceTo(team.channel->time() + 0.05);
    carrier = team.channel->Carrier(1);
  }
  EXPECT_TRUE(carrier);
}

TEST(AcousticChannel, ANoiseOutsideTheProfilesBandsRaisesNeitherTheThresholdNorTheCarrier) {
  // A compressor's 300 Hz hum (harmonics 600 and 900 Hz), 70 dB at 1 m beside robot 1: nava's
  // tone filters hear none of it, so robot 1 still calibrates on the room and still hears robot 0
  // 4 m off. White noise as loud raises its threshold by its share in the bands.
  const auto threshold_with = [](world_sim::NoiseKind kind) {
    world_sim::Acoustics a = Quiet();
    world_sim::NoiseSourceSpec s;
    s.name = "hum";
    s.x = 7.0, s.y = 2.5;
    s.level_db = 70.0;
    s.kind = kind;
    s.frequency = 300.0;
    a.noise_sources = {s};
    AcousticTeam team({2.0, 6.0}, a);
    return team.channel->mac(1).threshold_db();
  };
  const double margin = nava_modem::MacOptions().threshold_margin_db;
  const double quiet = 20.0 + 10.0 * std::log10(CarrierShare(world_sim::NoiseKind::kPink, 0.0,
                                                              nava_modem::Profile::kNava, kTableSampleRate));
  EXPECT_LT(threshold_with(world_sim::NoiseKind::kWhine), quiet + margin + 1.0);
  EXPECT_GT(threshold_with(world_sim::NoiseKind::kWhine), quiet + margin - 1e-6);
  // At 1 m the white source is 70 dB; the meter hears 2.5 % of it, 16 dB less.
  EXPECT_NEAR(threshold_with(world_sim::NoiseKind::kWhite), 70.0 - 16.0 + margin, 1.5);
}

TEST(DeliveryMap, NearCellsHearBetterThanFarOnesAndWallsHaveNoValue) {
  grid::OccupancyMap map(90, 10, 0.5);
  for (int i = 40; i < 42; ++i)
    for (int j = 0; j < 2; ++j) map.set(i, j, grid::Cell::kOccupied);  // a pillar at (20-21, 0-1) m
  const PropagationModel propagation(map, Options());
  world_sim::Acoustics a = Quiet();
  a.ambient_db = 45.0;
  const AcousticModel model(propagation, a, LinearTable(), {});
  const DeliveryMap d = MapDelivery(model, {2.0, 2.5}, 0.0, {}, 1.0);
  ASSERT_EQ(d.width, 45);
  ASSERT_EQ(d.height, 5);
  auto at = [&](int i, int j) { return d.probability[static_cast<std::size_t>(j) * d.width + i]; };
  EXPECT_GT(at(3, 2), at(30, 2));
  EXPECT_TRUE(std::isnan(at(20, 0)));  // the wall's cell
  EXPECT_THROW(MapDelivery(model, {2.0, 2.5}, 0.0, {}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace audio_propagation
