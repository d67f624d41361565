// The channel's run depends on what it is handed and when that is stamped, not on how often its
// caller advances it: a node that advances it every simulation step and one that sleeps while
// the air is quiet (audio_propagation's ~update events) see the same receptions, carriers and
// noise. Scripted scenes: robots moving and standing, packets alone and colliding, long
// silences, both channel models.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "flat_table.h"

#include "nava_modem/csma_mac.h"

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/audio_channel.h"

namespace audio_propagation {
namespace {

using world_sim::Microphone;

constexpr double kStep = 0.02;       // s, world_sim's step
constexpr double kPosePeriod = 0.04;  // s, how often the world publishes a pose

struct ScriptedSend {
  double time;
  std::size_t robot;
  std::vector<std::uint8_t> data;
};

// Robots on a 45 x 5 m strip: some drive along it, some stand; packets come in bursts (several
// robots at once, so they collide) with seconds of silence between.
struct Scene {
  std::vector<double> x0, speed;
  std::vector<ScriptedSend> sends;
  double duration = 45.0;

  grid::Pose2D PoseAt(std::size_t k, double t) const {
    const double x = x0[k] + speed[k] * t;
    return {std::clamp(x, 0.5, 44.5), 2.5, speed[k] >= 0.0 ? 0.0 : M_PI};
  }
};

Scene MakeScene() {
  Scene s;
  s.x0 = {2.0, 8.0, 15.0, 24.0, 40.0};
  s.speed = {0.4, 0.0, -0.3, 0.0, -1.0};
  std::uint8_t n = 0;
  for (const double burst : {1.3, 4.07, 4.09, 9.5, 13.333, 25.0, 33.7, 41.0}) {
    for (std::size_t k = 0; k < s.x0.size(); ++k) {
      if ((k + static_cast<std::size_t>(burst)) % 2 == 0) s.sends.push_back({burst + 0.001 * k, k, {n++, 1, 2, 3}});
    }
  }
  // One robot fills its queue beyond what it holds.
  for (int k = 0; k < 20; ++k) s.sends.push_back({11.0, 1, {n++, 9, 9, 9}});
  std::stable_sort(s.sends.begin(), s.sends.end(), [](const ScriptedSend& a, const ScriptedSend& b) { return a.time < b.time; });
  return s;
}

PropagationOptions Options() {
  PropagationOptions o;
  o.source_level_db = 60.0;
  o.threshold_db = 20.0;
  o.threads = 1;
  return o;
}

// One of the two models over the strip.
struct Medium {
  PropagationModel model{grid::OccupancyMap(90, 10, 0.5), Options()};
  std::unique_ptr<AcousticModel> acoustic;

  explicit Medium(bool with_acoustics, std::size_t robots) {
    if (!with_acoustics) return;
    world_sim::Acoustics a;
    a.room.rt60 = 0.5;
    a.room.critical_distance = 3.0;
    a.ambient_db = 25.0;
    // A fan that switches on and off, and a loud vacuum cleaner riding on robot 4: the noise
    // each robot hears moves with the robots and the clock.
    world_sim::NoiseSourceSpec fan;
    fan.name = "fan";
    fan.x = 20.0;
    fan.y = 2.5;
    fan.level_db = 55.0;
    fan.duty = 0.5;
    fan.period = 3.0;
    world_sim::NoiseSourceSpec vacuum;
    vacuum.name = "vacuum";
    vacuum.robot = "robot_4";
    vacuum.level_db = 70.0;
    vacuum.duty = 0.3;
    vacuum.period = 7.0;
    vacuum.phase = 2.0;
    a.noise_sources = {fan, vacuum};
    std::vector<std::string> names;
    for (std::size_t k = 0; k < robots; ++k) names.push_back("robot_" + std::to_string(k));
    acoustic = std::make_unique<AcousticModel>(model, a, test::FlatTable("nava", 0.6), names);
  }
};

// Everything a run produced, one line per event, for comparing runs.
struct Record {
  std::vector<std::string> starts, receptions_seen;
  std::size_t receptions = 0, packets = 0, collisions = 0;
  std::size_t wakes = 0;  // steps at which the channel was advanced

  void Add(const AudioChannel::Events& e) {
    for (const Transmission& t : e.started) {
      std::ostringstream out;
      out.precision(17);
      out << "start " << t.sender << " " << t.start << " " << int(t.data[0]);
      for (const SoundPath& p : t.paths) out << " " << p.length;
      for (const double p : t.probability) out << " " << p;
      starts.push_back(out.str());
    }
    for (const Reception& r : e.received) {
      std::ostringstream out;
      out.precision(17);
      out << "rx " << r.receiver << " " << r.sender << " " << r.time << " " << int(r.kind) << " " << r.collision
          << " " << int(r.noise) << " " << r.probability << " " << r.level_db << " " << r.direction << " "
          << r.path_length << " " << r.data.size();
      receptions_seen.push_back(out.str());
      ++receptions;
      packets += r.kind == Reception::Kind::kPacket ? 1 : 0;
      collisions += r.collision ? 1 : 0;
    }
  }
  // The carriers as a node that wakes at `t` publishes them: when one changed since it last looked.
  void AddCarriers(const AudioChannel& c, double t) {
    std::ostringstream out;
    for (std::size_t k = 0; k < c.size(); ++k) out << c.Carrier(k);
    if (out.str() == last_carriers) return;
    last_carriers = out.str();
    carriers.push_back(std::to_string(t) + " " + last_carriers);
  }
  std::string last_carriers;
  std::vector<std::string> carriers;
};

// Runs the scene, waking at the step times `rest` chooses (given the channel after a wake and
// the step's time, it says until when to rest: no step before that time is woken unless a
// packet comes), as a node would: at each wake everything stamped up to then is handed over,
// then the channel advances.
Record Run(const Scene& scene, bool with_acoustics, const std::function<double(const AudioChannel&, double)>& rest,
           std::size_t* overflows) {
  const std::size_t n = scene.x0.size();
  Medium medium(with_acoustics, n);
  ChannelOptions o;
  o.seed = 7;
  o.direction_noise = 0.1;
  AudioChannel channel(medium.model, std::vector<Microphone>(n, Microphone::kOmni), o, medium.acoustic.get());
  for (std::size_t k = 0; k < n; ++k) channel.SetPose(k, scene.PoseAt(k, 0.0));
  Record record;
  std::size_t next_send = 0;
  double next_pose = kPosePeriod;
  const auto steps = static_cast<std::int64_t>(std::llround(scene.duration / kStep));
  double rest_until = 0.0;
  for (std::int64_t s = 1; s <= steps; ++s) {
    const double t = static_cast<double>(s) * kStep;
    // A packet handed to the node wakes it, as a message on a stream it listens to does.
    const bool message = next_send < scene.sends.size() && scene.sends[next_send].time <= t + 1e-9;
    if (t < rest_until - 1e-9 && !message && s != steps) continue;  // the run ends with everything worked out
    for (; next_send < scene.sends.size() && scene.sends[next_send].time <= t + 1e-9; ++next_send) {
      const ScriptedSend& send = scene.sends[next_send];
      // Stamped with the step it reached the node in, as a message is.
      channel.SendAt(send.robot, send.data, t);
    }
    for (; next_pose <= t + 1e-9; next_pose += kPosePeriod) {
      for (std::size_t k = 0; k < n; ++k) channel.SetPoseAt(k, scene.PoseAt(k, next_pose), next_pose);
    }
    ++record.wakes;
    record.Add(channel.AdvanceTo(t));
    record.AddCarriers(channel, t);
    rest_until = rest(channel, t);
  }
  if (overflows) *overflows = channel.send_overflows();
  return record;
}

void ExpectSameLines(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) ASSERT_EQ(a[i], b[i]) << "line " << i;
  ASSERT_EQ(a.size(), b.size());
}

void ExpectSameEvents(const Record& a, const Record& b) {
  ExpectSameLines(a.starts, b.starts);
  ExpectSameLines(a.receptions_seen, b.receptions_seen);
}

void ExpectSameRuns(bool with_acoustics) {
  const Scene scene = MakeScene();
  std::size_t overflows = 0;
  const Record every_step = Run(scene, with_acoustics, [](const AudioChannel&, double) { return 0.0; }, &overflows);
  // Asleep until the channel says something may happen (a packet coming wakes it too).
  std::size_t overflows_on_events = 0;
  const Record on_events = Run(
      scene, with_acoustics, [](const AudioChannel& c, double) { return c.NextEventTime() - 1e-6; },
      &overflows_on_events);
  EXPECT_EQ(overflows_on_events, overflows);
  // Asleep only while the air is quiet.
  const Record on_quiet = Run(
      scene, with_acoustics,
      [](const AudioChannel& c, double) { return c.Idle() ? std::numeric_limits<double>::infinity() : 0.0; },
      &overflows_on_events);
  // The scene is what it is meant to be: packets heard, collisions, a queue overflowing (one
  // more when a robot still holds a packet it waited with while the fan sounded), and most of
  // the run silent (with acoustics the fan, on 1.5 s of every 3, is a carrier to the robots by it
  // while it sounds: their floors follow its quiet halves).
  ASSERT_GT(every_step.packets, 10u);
  ASSERT_GT(every_step.collisions, 0u);
  EXPECT_GE(overflows, 20u - nava_modem::MacOptions().queue_capacity);
  EXPECT_LE(overflows, 20u - nava_modem::MacOptions().queue_capacity + 1);
  EXPECT_LT(on_quiet.wakes, every_step.wakes * 3 / 4);
  EXPECT_LT(on_events.wakes, on_quiet.wakes * 2 / 3);
  ExpectSameEvents(every_step, on_quiet);
  ExpectSameEvents(every_step, on_events);
  // Without an acoustic model the carriers move only where the channel foresees it. With one,
  // the noise may move a carrier while the air is otherwise quiet: the sleeper learns at its
  // next wake.
  if (!with_acoustics) {
    ExpectSameLines(every_step.carriers, on_quiet.carriers);
    ExpectSameLines(every_step.carriers, on_events.carriers);
  }
  // And advancing at odd moments, many steps at a time while packets are in the air, changes
  // nothing either.
  std::mt19937 rng(3);
  std::size_t overflows_ragged = 0;
  const Record ragged = Run(
      scene, with_acoustics,
      [&](const AudioChannel&, double t) { return t + kStep * std::uniform_int_distribution<int>(0, 30)(rng); },
      &overflows_ragged);
  EXPECT_EQ(overflows_ragged, overflows);
  ExpectSameEvents(every_step, ragged);
}

TEST(ChannelCadence, SleepingThroughQuietGivesTheSameRunAsEveryStep) { ExpectSameRuns(false); }

TEST(ChannelCadence, SleepingThroughQuietGivesTheSameRunAsEveryStepWithAcoustics) { ExpectSameRuns(true); }

// What is stamped for later takes effect then, not when it was handed over.
TEST(ChannelCadence, APacketStampedForLaterLeavesThenAndAPoseStampedForLaterMovesTheRobotThen) {
  Medium medium(false, 2);
  AudioChannel channel(medium.model, {Microphone::kOmni, Microphone::kOmni}, {});
  channel.SetPose(0, {2.0, 2.5, 0.0});
  channel.SetPose(1, {12.0, 2.5, 0.0});
  ASSERT_TRUE(channel.SendAt(0, {1, 2, 3, 4}, 1.0));
  channel.SetPoseAt(1, {22.0, 2.5, 0.0}, 0.5);
  EXPECT_FALSE(channel.Idle());  // a packet is still to be sent
  EXPECT_TRUE(channel.AdvanceTo(0.99).started.empty());
  const auto events = channel.AdvanceTo(3.0);
  ASSERT_EQ(events.started.size(), 1u);
  EXPECT_GE(events.started[0].start, 1.0 - 1e-9);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_NEAR(events.received[0].path_length, 20.0, 1e-9);
  EXPECT_TRUE(channel.Idle());
  // A time already passed takes effect at once.
  channel.SetPoseAt(1, {7.0, 2.5, 0.0}, 0.0);
  ASSERT_TRUE(channel.SendAt(0, {5, 6, 7, 8}, 0.0));
  const auto late = channel.AdvanceTo(5.0);
  ASSERT_EQ(late.received.size(), 1u);
  EXPECT_NEAR(late.received[0].path_length, 5.0, 1e-9);
}

}  // namespace
}  // namespace audio_propagation
