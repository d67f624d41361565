#include "audio_propagation/scene_render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "grid/input_error.h"
#include "audio_propagation/arrival_errors_file.h"
#include "nava_modem/first_arrival.h"
#include "nava_modem/measured_like_response.h"
#include "nava_modem/moved_rooms.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"
#include "ranging/simulated_ranging.h"
#include "ranging/two_way_ranger.h"
#include "world_sim/world_file.h"

namespace audio_propagation {
namespace {

using test::FlatTable;

PropagationOptions Everywhere() {
  PropagationOptions o;
  o.threshold_db = 0.0;
  o.threads = 1;
  return o;
}

double Db(double power) { return 10.0 * std::log10(power); }

// A hall of RT60 0.7 s (critical distance 1.5 m) with a pink ambient at 20 dB.
world_sim::Acoustics HallOfRt60Of07() {
  world_sim::Acoustics acoustics;
  acoustics.room.rt60 = 0.7;
  acoustics.room.critical_distance = 1.5;
  acoustics.ambient_db = 20.0;
  acoustics.ambient_kind = world_sim::NoiseKind::kPink;
  return acoustics;
}

// How far from an impulse's sample LeadingEdge puts its arrival (s).
double LeadingEdgeRise() {
  std::vector<float> impulse(8000, 0.0f);
  impulse[2000] = 1.0f;
  return nava_modem::LeadingEdge(impulse, 48000.0) - 2000.0 / 48000.0;
}

// A room-profile scene of 3.5 s in which robot "a" sends one packet at 0.5 s, every robot resting.
Scene OnePacketFromA(const std::vector<std::string>& names, const std::vector<Eigen::Vector2d>& resting) {
  Scene scene;
  scene.profile = nava_modem::Profile::kRoom;
  scene.duration = 3.5;
  for (std::size_t k = 0; k < names.size(); ++k) scene.robots.push_back({names[k], {{0.0, resting[k].x(), resting[k].y(), 0.0}}});
  scene.packets.push_back({0.5, "a", {1, 2, 3, 4}});
  return scene;
}

// The packets the room profile's receiver decodes from a recording.
std::vector<nava_modem::RxEvent> RoomPackets(const std::vector<float>& mix) {
  const auto receiver = nava_modem::MakeProfile(nava_modem::Profile::kRoom, {})->MakeReceiver(nava_modem::ReceiverOptions{});
  std::vector<nava_modem::RxEvent> events, packets;
  receiver->Process(mix.data(), mix.size(), events);
  receiver->Flush(events);
  for (const nava_modem::RxEvent& e : events) {
    if (e.kind == nava_modem::RxEvent::Kind::kPacket) packets.push_back(e);
  }
  return packets;
}

double MeanSquare(const std::vector<float>& x, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(x[i]) * x[i];
  return sum / static_cast<double>(to - from);
}

// An open hall 20 x 6 m: robots a, b and c on its midline.
struct Hall {
  PropagationModel propagation{grid::OccupancyMap(400, 120, 0.05), Everywhere()};
  std::vector<std::string> names{"a", "b", "c"};
  std::vector<Eigen::Vector2d> resting{{2.0, 3.0}, {8.0, 3.0}, {4.0, 3.0}};
  std::unique_ptr<AcousticModel> model;
  explicit Hall(const world_sim::Acoustics& acoustics, nava_modem::Profile profile = nava_modem::Profile::kNava) {
    model = std::make_unique<AcousticModel>(propagation, acoustics, FlatTable(nava_modem::ProfileName(profile)), names);
  }
  // One packet from a at 0.5 s.
  Scene OnePacket(nava_modem::Profile profile = nava_modem::Profile::kNava) const {
    Scene s;
    s.profile = profile;
    s.start = 0.0;
    s.duration = profile == nava_modem::Profile::kNava ? 2.0 : 3.5;
    for (std::size_t k = 0; k < names.size(); ++k) s.robots.push_back({names[k], {{0.0, resting[k].x(), resting[k].y(), 0.0}}});
    s.packets.push_back({0.5, "a", {1, 2, 3, 4}});
    return s;
  }
};

world_sim::Acoustics Noisy() {
  world_sim::Acoustics a;
  a.room.rt60 = 0.4;
  a.room.critical_distance = 3.0;
  a.ambient_db = 40.0;
  a.ambient_kind = world_sim::NoiseKind::kWhite;
  world_sim::NoiseSourceSpec fan;
  fan.name = "fan";
  fan.x = 10.0, fan.y = 5.0;
  fan.level_db = 60.0;
  fan.kind = world_sim::NoiseKind::kPink;
  world_sim::NoiseSourceSpec motor = fan;
  motor.name = "motor";
  motor.x = 15.0, motor.y = 1.0;
  motor.level_db = 55.0;
  motor.kind = world_sim::NoiseKind::kWhine;
  motor.frequency = 3000.0;  // the table's whine: the model counts all its power
  a.noise_sources = {fan, motor};
  return a;
}

TEST(SceneRender, ThePacketOverTheNoiseIsTheModelsSnrAndArrivesAfterItsTravelTime) {
  // The room profile: its chirps pin the delay down (nava's tones correlate every period).
  const nava_modem::Profile room = nava_modem::Profile::kRoom;
  const Hall hall(Noisy(), room);
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  const Scene scene = hall.OnePacket(room);
  const SceneRendering r = renderer.Render(scene, {"b", "c"});
  ASSERT_EQ(r.listeners.size(), 2u);
  ASSERT_EQ(r.hearings.size(), 2u);

  nava_modem::ModemOptions modem;
  const std::vector<float> burst = nava_modem::MakeProfile(room, modem)->ModulatePacket({1, 2, 3, 4});
  const std::vector<bool> sounding = nava_modem::SoundingSamples(burst, 48000.0);
  for (std::size_t k = 0; k < 2; ++k) {
    const ListenerRecording& l = r.listeners[k];
    const PacketHearing& h = r.hearings[k];
    ASSERT_TRUE(h.reachable);
    EXPECT_EQ(h.listener, l.robot);
    // Where the packet must start: 0.5 s plus its distance at 343 m/s.
    const double distance = (hall.resting[k + 1] - hall.resting[0]).norm();
    const long expected = std::lround((0.5 + distance / 343.0) * 48000.0);
    // The lag at which the recording best matches the clean packet (the direct sound's).
    long best_lag = 0;
    double best = 0.0;
    for (long lag = expected - 200; lag <= expected + 200; ++lag) {
      double c = 0.0;
      for (std::size_t i = 0; i < burst.size(); ++i) c += burst[i] * l.packets[static_cast<std::size_t>(lag) + i];
      if (c > best) best = c, best_lag = lag;
    }
    EXPECT_NEAR(best_lag, expected, 1) << l.robot;
    EXPECT_NEAR(static_cast<double>(h.first_sample), expected, 1.0) << l.robot;

    // The signal power over the packet's sounding samples is the link's total level ...
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < burst.size(); ++i) {
      if (!sounding[i]) continue;
      sum += static_cast<double>(l.packets[h.first_sample + i]) * l.packets[h.first_sample + i];
      ++count;
    }
    const double signal_db = Db(sum / static_cast<double>(count)) + kReferenceDb;
    EXPECT_NEAR(signal_db, h.prediction.signal.total_db, 0.05) << l.robot;
    // ... and over the noise's power over the recording it is the model's SNR.
    const double noise_db = Db(MeanSquare(l.noise, 0, l.noise.size())) + kReferenceDb;
    EXPECT_NEAR(signal_db - noise_db, h.prediction.snr_db, 0.5) << l.robot;
    EXPECT_NEAR(noise_db, h.model_noise_db, 0.5) << l.robot;
    EXPECT_NEAR(Db(h.signal_power / h.noise_power), h.prediction.snr_db, 1.0) << l.robot;
  }
  // Nearer, louder and sooner.
  EXPECT_GT(r.hearings[1].prediction.signal.total_db, r.hearings[0].prediction.signal.total_db + 1.0);
  EXPECT_LT(r.hearings[1].first_sample, r.hearings[0].first_sample);
}

TEST(SceneRender, ARobotDoesNotHearItsOwnPacketsAndALevelOf100DbIsAMeanSquareOf1) {
  EXPECT_DOUBLE_EQ(LevelToPower(kReferenceDb), 1.0);
  EXPECT_NEAR(LevelToPower(70.0), 1e-3, 1e-15);
  const Hall hall(Noisy());
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  const SceneRendering r = renderer.Render(hall.OnePacket(), {"a"});
  ASSERT_EQ(r.listeners.size(), 1u);
  EXPECT_TRUE(r.hearings.empty());
  for (float v : r.listeners[0].packets) ASSERT_EQ(v, 0.0f);
  EXPECT_EQ(r.listeners[0].packets.size(), 96000u);
  EXPECT_THROW(renderer.Render(hall.OnePacket(), {"d"}), std::invalid_argument);
  // The model's table must be the scene's profile's.
  EXPECT_THROW(renderer.Render(hall.OnePacket(nava_modem::Profile::kRoom)), std::invalid_argument);
}

// For ranging: a robot hears its own packet through its speaker-to-microphone path, a sender's
// card plays late by its latency, and each card samples at its own rate (the packet arrives
// where the listener's clock puts it, stretched by the two rates' ratio).
TEST(SceneRender, OwnPacketsAndSoundCardsPlaceEveryArrivalOnTheListenersClock) {
  const nava_modem::Profile room = nava_modem::Profile::kRoom;
  const Hall hall(Noisy(), room);
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  Scene scene = hall.OnePacket(room);
  scene.own_packets = true;
  scene.self_distance = 0.2;
  scene.sound_cards["a"] = SceneSoundCard{80e-6, 0.0123};
  scene.sound_cards["b"] = SceneSoundCard{-90e-6, 0.0};
  const SceneRendering r = renderer.Render(scene, {"a", "b"});
  ASSERT_EQ(r.hearings.size(), 2u);
  const PacketHearing& own = r.hearings[0];
  const PacketHearing& far = r.hearings[1];
  ASSERT_EQ(own.listener, "a");
  ASSERT_TRUE(own.reachable);
  EXPECT_DOUBLE_EQ(own.path_length, 0.2);
  EXPECT_EQ(own.corners, 0);
  EXPECT_NEAR(own.arrival, 0.5 + 0.0123 + 0.2 / 343.0, 1e-9);
  EXPECT_NEAR(own.arrival_clock, own.arrival * (1.0 + 80e-6), 1e-9);
  EXPECT_GT(own.prediction.signal.total_db, far.prediction.signal.total_db + 10.0);  // its speaker is near
  EXPECT_NEAR(far.arrival, 0.5 + 0.0123 + 6.0 / 343.0, 1e-9);
  EXPECT_NEAR(far.arrival_clock, far.arrival * (1.0 - 90e-6), 1e-9);

  // The real receiver times each packet where the listener's clock puts it. By first_arrival.h's
  // definition an arrival is where the in-band envelope of the direct sound reaches half its
  // peak: some 130 us before the direct sound's sample, as for a bare impulse.
  const double rise = LeadingEdgeRise();
  EXPECT_LT(rise, -50e-6);
  for (std::size_t k = 0; k < 2; ++k) {
    const std::vector<float> mix = r.listeners[k].Mix();
    nava_modem::ModemOptions modem;
    const auto receiver = nava_modem::MakeProfile(room, modem)->MakeReceiver(nava_modem::ReceiverOptions{});
    std::vector<nava_modem::RxEvent> events;
    receiver->Process(mix.data(), mix.size(), events);
    receiver->Flush(events);
    ASSERT_EQ(events.size(), 1u) << r.listeners[k].robot;
    EXPECT_EQ(events[0].data, std::vector<std::uint8_t>({1, 2, 3, 4}));
    EXPECT_NEAR(events[0].arrival, r.hearings[k].arrival_clock + rise, 30e-6) << r.listeners[k].robot;
  }
}

// Round a corner, with the room table measured over measured-like rooms: the diffracted sound
// 25-35 dB under the reverberation is still timed where it arrives. The renderer once gave a
// measured-like room no distance round a corner: it took the DRR for distance, a listener up to
// 60 m down a hall whose reverberation built up over 80 ms, and the receiver timed that
// reverberation 1-60 ms late (ranging round corners 30 % long); and it left the response's
// 16-sample lead in (0.33 ms).
TEST(SceneRender, ASoundRoundACornerIsTimedWhereItArrivesWithAMeasuredLikeTable) {
  // 20 x 12 m, a wall across x = 10 from y = 0 to 9 m: a round b and c, its corner at (10, 9).
  grid::OccupancyMap map(200, 120, 0.1);
  for (int i = 100; i < 102; ++i) {
    for (int j = 0; j < 90; ++j) map.set(i, j, grid::Cell::kOccupied);
  }
  const PropagationModel propagation(map, Everywhere());
  const world_sim::Acoustics acoustics = HallOfRt60Of07();
  DecodeTable table = FlatTable("room");
  table.rooms = nava_modem::RoomOptions::Model::kMeasuredLike;
  const std::vector<std::string> names{"a", "b", "c"};
  const std::vector<Eigen::Vector2d> resting{{5.0, 2.0}, {15.0, 2.0}, {17.0, 5.0}};
  const AcousticModel model(propagation, acoustics, table, names);
  const double rise = LeadingEdgeRise();
  int round_corners = 0;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    SceneRenderOptions options;
    options.seed = seed;
    const SceneRenderer renderer(model, names, resting, options);
    const SceneRendering r = renderer.Render(OnePacketFromA(names, resting), {"b", "c"});
    for (std::size_t k = 0; k < r.hearings.size(); ++k) {
      const PacketHearing& h = r.hearings[k];
      ASSERT_TRUE(h.reachable);
      ASSERT_GT(h.corners, 0);
      ASSERT_LT(h.prediction.signal.drr_db, -20.0) << h.listener;
      ++round_corners;
      const std::vector<nava_modem::RxEvent> packets = RoomPackets(r.listeners[k].Mix());
      ASSERT_EQ(packets.size(), 1u) << h.listener << " seed " << seed;
      // Within 0.25 ms: 8.6 cm of a path of 17 m (the transducers spread a measured-like room's
      // direct sound over 0.2-1 ms; the fault was 0.4 to 60 ms).
      EXPECT_NEAR(packets[0].arrival, h.arrival_clock + rise, 2.5e-4)
          << h.listener << " seed " << seed << ", DRR " << h.prediction.signal.drr_db << " dB";
    }
  }
  EXPECT_EQ(round_corners, 6);
}

// A table measured over measured rooms: each link hears one of them moved to its RT60 and DRR,
// whose direct sound lies where it was measured (here some 1000 samples in, as a file keeps the
// sound's flight): taken back as the measured-like room's lead is, so that the packet is timed
// where it arrives. Stand-ins for measured rooms: the renderer's, of a slower decay, moved. In
// line of sight 3 and 5 m apart in a hall of RT60 0.7 s.
TEST(SceneRender, APacketIsTimedWhereItArrivesWithATableOverMeasuredRooms) {
  std::vector<nava_modem::MovableRoom> rooms;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    nava_modem::MovableRoom room;
    room.name = "room " + std::to_string(seed);
    room.response.assign(1000 - nava_modem::kMeasuredLikeDelay, 0.0f);
    const std::vector<float> h = nava_modem::MeasuredLikeResponse(1.4, 2.0 * seed - 4.0, 48000.0, seed);
    room.response.insert(room.response.end(), h.begin(), h.end());
    rooms.push_back(std::move(room));
  }
  const auto measured = std::make_shared<const nava_modem::MovedRooms>(std::move(rooms), 48000.0);
  ASSERT_GE(measured->rooms()[0].figures.peak, 1000u);  // the transducers' colouring delays the in-band peak a little
  const PropagationModel propagation(grid::OccupancyMap(200, 120, 0.1), Everywhere());
  const world_sim::Acoustics acoustics = HallOfRt60Of07();
  DecodeTable table = FlatTable("room");
  table.rooms = nava_modem::RoomOptions::Model::kMeasured;
  const std::vector<std::string> names{"a", "b", "c"};
  const std::vector<Eigen::Vector2d> resting{{5.0, 6.0}, {8.0, 6.0}, {10.0, 6.0}};
  const AcousticModel model(propagation, acoustics, table, names);
  const double rise = LeadingEdgeRise();
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    SceneRenderOptions options;
    options.seed = seed;
    options.measured_rooms = measured;
    const SceneRenderer renderer(model, names, resting, options);
    const SceneRendering r = renderer.Render(OnePacketFromA(names, resting), {"b", "c"});
    ASSERT_EQ(r.hearings.size(), 2u);
    for (std::size_t k = 0; k < r.hearings.size(); ++k) {
      const PacketHearing& h = r.hearings[k];
      const std::vector<nava_modem::RxEvent> packets = RoomPackets(r.listeners[k].Mix());
      ASSERT_EQ(packets.size(), 1u) << h.listener << " seed " << seed;
      EXPECT_NEAR(packets[0].arrival, h.arrival_clock + rise, 2.5e-4)
          << h.listener << " seed " << seed << ", DRR " << h.prediction.signal.drr_db << " dB";
    }
  }
}

TEST(SceneRender, ATableOverMeasuredRoomsNeedsThemAtTheRendersRate) {
  const PropagationModel propagation(grid::OccupancyMap(20, 20, 0.5), Everywhere());
  world_sim::Acoustics acoustics;
  acoustics.room.rt60 = 0.7;
  acoustics.room.critical_distance = 1.5;
  DecodeTable table = FlatTable("room");
  table.rooms = nava_modem::RoomOptions::Model::kMeasured;
  const AcousticModel model(propagation, acoustics, table, {"a"});
  try {
    SceneRenderer(model, {"a"}, {{1.0, 1.0}}, SceneRenderOptions{});
    ADD_FAILURE() << "accepted a measured table without its rooms";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("measured rooms"), std::string::npos) << e.what();
  }
  std::vector<nava_modem::MovableRoom> rooms(1);
  rooms[0].name = "one";
  rooms[0].response = nava_modem::MeasuredLikeResponse(1.0, 0.0, 44100.0, 1);
  SceneRenderOptions options;
  options.measured_rooms = std::make_shared<const nava_modem::MovedRooms>(rooms, 44100.0);
  EXPECT_THROW(SceneRenderer(model, {"a"}, {{1.0, 1.0}}, options), std::invalid_argument);
}

// The simulation's ranging (audio_propagation's: SimulatedRanging with the real receiver's
// errors through measured rooms) against the real ranging on the same rendered scene (the room
// receiver decoding and timing every robot's own recording, own packets included, on sound
// cards of their own; one TwoWayRanger per robot): a range shows up for the same pairs after
// the same packets (only after an exchange both ways), and the ranges are as close to the
// truth in both.
TEST(SceneRender, SimulatedRangingHasTheRealRangingsAvailabilityAndErrors) {
  const nava_modem::Profile room = nava_modem::Profile::kRoom;
  const Hall hall(Noisy(), room);
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  Scene scene = hall.OnePacket(room);
  scene.packets.clear();
  scene.own_packets = true;
  scene.self_distance = 0.15;
  scene.sound_cards["a"] = SceneSoundCard{80e-6, 0.0123};
  scene.sound_cards["b"] = SceneSoundCard{-90e-6, 0.031};
  scene.sound_cards["c"] = SceneSoundCard{25e-6, 0.0047};
  const double period = 2.3;
  for (std::uint8_t round = 0; round < 2; ++round) {
    for (std::uint8_t s = 0; s < 3; ++s) {
      scene.packets.push_back({0.3 + period * (3 * round + s), hall.names[s], {s, round, 7, 9}});
    }
  }
  scene.duration = 0.3 + period * 6 + 0.5;
  const SceneRendering r = renderer.Render(scene, hall.names);

  // Every robot's recording through the real receiver.
  std::vector<std::vector<nava_modem::RxEvent>> heard(3);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::vector<float> mix = r.listeners[k].Mix();
    const auto receiver = nava_modem::MakeProfile(room, nava_modem::ModemOptions{})->MakeReceiver(nava_modem::ReceiverOptions{});
    receiver->Process(mix.data(), mix.size(), heard[k]);
    receiver->Flush(heard[k]);
    ASSERT_EQ(heard[k].size(), scene.packets.size()) << hall.names[k];
  }
  ranging::RangerOptions real_options;
  real_options.offset = scene.self_distance;  // a robot's calibration of its own speaker-to-microphone way
  std::vector<ranging::TwoWayRanger> real;
  for (const std::string& name : hall.names) real.emplace_back(name, hall.names, real_options);
  ranging::SimulatedRangingOptions sim_options;
  sim_options.errors = LoadArrivalErrors(ShippedArrivalErrors("room"), "room");
  sim_options.rate_report_std = 30e-6;
  ranging::SimulatedRanging sim(hall.names, sim_options);

  std::vector<double> real_errors, sim_errors;
  for (std::size_t p = 0; p < scene.packets.size(); ++p) {
    const ScenePacket& packet = scene.packets[p];
    const std::vector<std::uint8_t> data(packet.data.begin(), packet.data.end());
    const std::size_t sender = packet.data[0];
    sim.Sent(sender, data, packet.time + scene.sound_cards.at(packet.sender).latency);
    double latest = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const nava_modem::RxEvent& e = heard[k][p];
      ASSERT_EQ(e.data, data) << hall.names[k] << " packet " << p;
      ranging::Timing t;
      t.sender = packet.sender;
      t.listener = hall.names[k];
      t.data = data;
      t.arrival = e.arrival;
      t.rate_error = k == sender ? 0.0 : e.rate_error;
      for (ranging::TwoWayRanger& ranger : real) ranger.Add(t);
      const PacketHearing* hearing = nullptr;
      for (const PacketHearing& h : r.hearings) {
        if (h.packet == p && h.listener == hall.names[k]) hearing = &h;
      }
      ASSERT_NE(hearing, nullptr);
      latest = std::max(latest, hearing->arrival);
      if (k != sender) sim.Heard(k, sender, data, hearing->path_length, hearing->arrival);
    }
    // The same pairs are ranged after every packet.
    for (std::size_t a = 0; a < 3; ++a) {
      for (std::size_t b = 0; b < 3; ++b) {
        if (a == b) continue;
        // Each on its own robot's clock (the renderer's sound card; the simulation's own).
        const double real_now = (latest - scene.start) * (1.0 + scene.sound_cards.at(hall.names[a]).rate_error);
        const auto real_range = real[a].RangeTo(hall.names[b], real_now);
        const auto sim_range = sim.RangeTo(a, b, latest);
        ASSERT_EQ(real_range.has_value(), sim_range.has_value()) << hall.names[a] << " -> " << hall.names[b] << " after packet " << p;
        if (!real_range) continue;
        const double truth = (hall.resting[a] - hall.resting[b]).norm();
        if (p + 1 == scene.packets.size()) {
          real_errors.push_back(real_range->range - truth);
          sim_errors.push_back(sim_range->range - truth);
        }
      }
    }
  }
  ASSERT_EQ(real_errors.size(), 6u);  // every pair ranged by the end
  // Line of sight in a hall: both within the line-of-sight target, and alike.
  const auto median_abs = [](std::vector<double> v) {
    for (double& x : v) x = std::abs(x);
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_LT(std::abs(real_errors[k]), 0.03) << "real pair " << k;
    EXPECT_LT(std::abs(sim_errors[k]), 0.03) << "simulated pair " << k;
  }
  EXPECT_NEAR(median_abs(real_errors), median_abs(sim_errors), 0.01);
}

TEST(SceneRender, ANoiseSourceSoundsAtItsLevelWhileOnAndNotWhileOff) {
  world_sim::Acoustics a = Noisy();
  a.noise_sources.resize(1);
  a.noise_sources[0].duty = 0.5;  // on for the first 1 s of every 2 s
  a.noise_sources[0].period = 2.0;
  const Hall hall(a);
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  const SceneRendering r = renderer.Render(hall.OnePacket(), {"b"});
  const std::vector<float>& noise = r.listeners[0].noise;
  const std::vector<Eigen::Vector2d> at = hall.resting;
  const double fan_db = *hall.model->SourceLevelDb(0, at[1], at);
  const double on = Db(LevelToPower(fan_db) + LevelToPower(a.ambient_db)) + kReferenceDb;
  EXPECT_NEAR(Db(MeanSquare(noise, 0, 48000)) + kReferenceDb, on, 0.3);
  EXPECT_NEAR(Db(MeanSquare(noise, 48000, 96000)) + kReferenceDb, a.ambient_db, 0.3);
  // The model heard the fan in the middle of the packet's arrival (0.5 s + 0.2 s: on).
  EXPECT_NEAR(r.hearings[0].model_noise_db, on, 1e-6);
}

TEST(SceneRender, ARecordedNoiseSourcePlaysItsRecordingAtItsLevel) {
  // A recording of a 1 kHz tone: the listener's noise is that tone, at the source's level.
  std::vector<float> tone(24000);
  for (std::size_t k = 0; k < tone.size(); ++k) tone[k] = static_cast<float>(0.2 * std::sin(2.0 * std::acos(-1.0) * 1000.0 * k / 24000.0));
  const std::string file = ::testing::TempDir() + "/scene_render_tone.wav";
  nava_modem::WriteWavFile(file, tone, 24000.0);  // another rate: resampled to the scene's
  world_sim::Acoustics a = Noisy();
  a.ambient_db = -20.0;
  a.noise_sources.resize(1);
  a.noise_sources[0].kind = world_sim::NoiseKind::kRecording;
  a.noise_sources[0].file = file;
  const Hall hall(a);
  const SceneRenderer renderer(*hall.model, hall.names, hall.resting, {});
  const SceneRendering r = renderer.Render(hall.OnePacket(), {"b"});
  const std::vector<float>& noise = r.listeners[0].noise;
  const std::vector<Eigen::Vector2d> at = hall.resting;
  EXPECT_NEAR(Db(MeanSquare(noise, 0, 48000)) + kReferenceDb, *hall.model->SourceLevelDb(0, at[1], at), 0.3);
  // A tone: half a period (24 samples at 48 kHz) later it is its own negative.
  double same = 0.0, half = 0.0;
  for (std::size_t k = 1000; k < 40000; ++k) {
    same += static_cast<double>(noise[k]) * noise[k];
    half += static_cast<double>(noise[k]) * noise[k + 24];
  }
  EXPECT_LT(half / same, -0.95);
}

TEST(SceneRender, RobotsMoveLinearlyBetweenKeyframesAndTurnTheShortWay) {
  const SceneRobot r{"r", {{1.0, 0.0, 0.0, 3.0}, {3.0, 2.0, 4.0, -3.0}}};
  const grid::Pose2D before = PoseAt(r, 0.0), mid = PoseAt(r, 2.0), after = PoseAt(r, 9.0);
  EXPECT_DOUBLE_EQ(before.x, 0.0);
  EXPECT_DOUBLE_EQ(mid.x, 1.0);
  EXPECT_DOUBLE_EQ(mid.y, 2.0);
  EXPECT_NEAR(std::fabs(mid.yaw), M_PI, 1e-9);  // through pi, not through 0
  EXPECT_DOUBLE_EQ(after.y, 4.0);
}

// A temporary scene file.
std::string SceneFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

const std::string kWorld = std::string(MULTIROBOT_AUDIO_MAPS_DIR) + "/test_room_acoustic_world.yaml";

TEST(SceneRender, AScenesPacketsAreDecodedFromTheWrittenRecordings) {
  const world_sim::LoadedWorld world = world_sim::LoadWorldFile(kWorld);
  ASSERT_TRUE(world.config.acoustics.has_value());
  // The room profile (nava's FSK does not survive this room's reverberation at 2 m, DRR +1 dB).
  const std::string file = SceneFile("round_trip", R"(
profile: room
duration: 5.5
robots:
  robot_0: [[0.0, 1.5, 1.0, 0.0]]
  robot_1: [[0.0, 1.5, 3.0, 0.0], [2.0, 2.0, 3.0, 0.0]]
packets:
  - {time: 0.3, sender: robot_0, data: [1, 2, 3, 4]}
  - {time: 2.8, sender: robot_1, data: [250, 6, 7, 8]}
)");
  const Scene scene = LoadScene(file);
  std::vector<std::string> names;
  std::vector<Eigen::Vector2d> resting;
  for (const world_sim::RobotSpec& r : world.config.robots) names.push_back(r.name), resting.push_back(r.start.position());
  CheckScene(file, scene, names, world.map);
  const PropagationModel propagation(world.map, Everywhere());
  const AcousticModel model(propagation, *world.config.acoustics, FlatTable("room"), names);
  const SceneRenderer renderer(model, names, resting, {});
  const SceneRendering r = renderer.Render(scene);
  ASSERT_EQ(r.listeners.size(), 2u);
  ASSERT_EQ(r.hearings.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const ListenerRecording& l = r.listeners[k];
    const std::string wav = ::testing::TempDir() + "/" + l.robot + ".wav";
    nava_modem::WriteFloatWavFile(wav, l.Mix(), r.sample_rate);
    const nava_modem::Audio audio = nava_modem::ReadAudioFile(wav);
    ASSERT_EQ(audio.samples.size(), 264000u);
    // Float WAV keeps the absolute level: no clipping, no scaling.
    EXPECT_NEAR(audio.samples[1000], l.Mix()[1000], 1e-9);
    const auto receiver = nava_modem::MakeProfile(nava_modem::Profile::kRoom, {})->MakeReceiver({});
    std::vector<nava_modem::RxEvent> events;
    receiver->Process(audio.samples.data(), audio.samples.size(), events);
    receiver->Flush(events);
    // Each robot hears the other's packet, and when it arrives.
    const ScenePacket& sent = scene.packets[k == 0 ? 1 : 0];
    const PacketHearing& h = r.hearings[k == 0 ? 1 : 0];
    EXPECT_EQ(h.listener, l.robot);
    int right = 0;
    for (const nava_modem::RxEvent& e : events) {
      if (e.kind != nava_modem::RxEvent::Kind::kPacket) continue;
      EXPECT_EQ(e.data, std::vector<std::uint8_t>(sent.data.begin(), sent.data.end())) << l.robot;
      EXPECT_NEAR(e.start, h.arrival, 0.05) << l.robot;
      ++right;
    }
    EXPECT_EQ(right, 1) << l.robot;
  }
}

// The message of the InputError `load` throws.
template <class F>
std::string ErrorOf(F load) {
  try {
    load();
  } catch (const grid::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneRender, BadScenesAreRefusedWithTheFileFieldAndValue) {
  const world_sim::LoadedWorld world = world_sim::LoadWorldFile(kWorld);
  const std::vector<std::string> names = {"robot_0", "robot_1", "robot_2"};
  const std::string head = "duration: 2\nrobots:\n  robot_0: [[0, 1.5, 1.0, 0]]\n";
  auto load = [&](const std::string& name, const std::string& text) {
    const std::string file = SceneFile(name, text);
    return ErrorOf([&] { CheckScene(file, LoadScene(file), names, world.map); });
  };
  std::string e = load("short_data", head + "packets:\n  - {time: 0.5, sender: robot_0, data: [1, 2, 3]}\n");
  EXPECT_NE(e.find("short_data.yaml: packets[0].data: expected 4 bytes"), std::string::npos) << e;
  EXPECT_NE(e.find("[1, 2, 3]"), std::string::npos) << e;
  e = load("big_byte", head + "packets:\n  - {time: 0.5, sender: robot_0, data: [1, 2, 3, 256]}\n");
  EXPECT_NE(e.find("packets[0].data"), std::string::npos) << e;
  EXPECT_NE(e.find("256"), std::string::npos) << e;
  e = load("profile", "profile: fast\n" + head);
  EXPECT_NE(e.find("profile.yaml: profile: expected nava or room, got 'fast'"), std::string::npos) << e;
  e = load("stranger", head + "  robot_9: [[0, 1.5, 3.0, 0]]\n");
  EXPECT_NE(e.find("stranger.yaml: robots.robot_9: no robot named 'robot_9'"), std::string::npos) << e;
  e = load("in_wall", "duration: 2\nrobots:\n  robot_0: [[0, 1.5, 1.0, 0], [1, 3.07, 1.0, 0]]\n");
  EXPECT_NE(e.find("in_wall.yaml: robots.robot_0[1]: (3.07, 1) is not in the map's free space"), std::string::npos) << e;
  e = load("order", "duration: 2\nrobots:\n  robot_0: [[1, 1.5, 1.0, 0], [0.5, 1.5, 2.0, 0]]\n");
  EXPECT_NE(e.find("robots.robot_0[1]: keyframe time 0.5 s"), std::string::npos) << e;
  e = load("sender", head + "packets:\n  - {time: 0.5, sender: robot_1, data: [1, 2, 3, 4]}\n");
  EXPECT_NE(e.find("packets[0].sender: 'robot_1' is not one of the scene's robots"), std::string::npos) << e;
  e = load("late", head + "packets:\n  - {time: 2.5, sender: robot_0, data: [1, 2, 3, 4]}\n");
  EXPECT_NE(e.find("packets[0].time: 2.5 s"), std::string::npos) << e;
  e = load("card", head + "sound_cards:\n  robot_0: {rate_ppm: 5000}\n");
  EXPECT_NE(e.find("card.yaml: sound_cards.robot_0.rate_ppm: expected -1000 to 1000 ppm, got 5000"), std::string::npos) << e;
  e = load("card_owner", head + "sound_cards:\n  robot_1: {latency: 0.01}\n");
  EXPECT_NE(e.find("sound_cards.robot_1: 'robot_1' is not one of the scene's robots"), std::string::npos) << e;
  e = load("latency", head + "sound_cards:\n  robot_0: {latency: -0.01}\n");
  EXPECT_NE(e.find("sound_cards.robot_0.latency: expected 0 to 1 s"), std::string::npos) << e;
  e = load("own", head + "own_packets: perhaps\n");
  EXPECT_NE(e.find("own.yaml: own_packets: expected true or false"), std::string::npos) << e;
  e = load("self", head + "self_distance: 5\n");
  EXPECT_NE(e.find("self_distance: expected 0.01 to 2 m, got 5"), std::string::npos) << e;
  e = ErrorOf([] { LoadScene("/nonexistent/scene.yaml"); });
  EXPECT_NE(e.find("/nonexistent/scene.yaml: scene file not found"), std::string::npos) << e;
}

}  // namespace
}  // namespace audio_propagation
