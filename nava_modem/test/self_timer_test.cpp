// A link times its own packets as its microphone hears them: on a device whose capture returns
// what it played some unknown time later (a sound card's loop), for both profiles; and the
// SelfTimer alone on silence, noise and a failure's gap.
#include "nava_modem/self_timer.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "nava_modem/first_arrival.h"
#include "nava_modem/nava_link.h"
#include "nava_modem/timing_reference.h"

namespace nava_modem {
namespace {

// Captures what it played `loop` samples before, quietly noisy; runs out after `seconds`.
class LoopbackDevice : public AudioDevice {
 public:
  LoopbackDevice(double rate, std::size_t loop, double seconds) : rate_(rate), loop_(loop), end_(static_cast<std::size_t>(seconds * rate)) {}
  double sample_rate() const override { return rate_; }
  bool Read(float* out, std::size_t count) override {
    if (read_ + count > end_) return false;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t n = read_ + k;
      out[k] = (n >= loop_ && n - loop_ < played_.size() ? played_[n - loop_] : 0.0f) + noise_(rng_);
    }
    read_ += count;
    return true;
  }
  void Write(const float* in, std::size_t count) override { played_.insert(played_.end(), in, in + count); }
  std::size_t PlaybackDelay() override { return 0; }
  std::size_t PlaybackRoom() override { return SIZE_MAX; }
  std::size_t CaptureLag() override { return 0; }
  void Reopen() override {}
  std::uint64_t overruns() const override { return 0; }
  std::uint64_t underruns() const override { return 0; }
  const std::vector<float>& played() const { return played_; }

 private:
  double rate_;
  std::size_t loop_, end_, read_ = 0;
  std::vector<float> played_;
  std::mt19937 rng_{4};
  std::normal_distribution<float> noise_{0.0f, 0.002f};
};

TEST(SelfTimerTest, ALinkTimesItsOwnPacketsThroughAnUnknownLoop) {
  for (Profile profile : {Profile::kNava, Profile::kRoom}) {
    LinkOptions o;
    o.profile = profile;
    o.mac.calibration_time = 0.5;
    o.mac.fixed_threshold_db = -30.0;
    const std::size_t loop = 4497;  // 94 ms
    LoopbackDevice device(o.modem.sample_rate, loop, 10.0);
    NavaLink link(o, device);
    ASSERT_TRUE(link.Send({1, 2, 3, 4}));
    ASSERT_TRUE(link.Send({5, 6, 7, 8}));
    std::vector<RxEvent> events;
    std::vector<OwnTiming> timings;
    while (link.Tick(events)) {
      for (OwnTiming& t : link.TakeOwnTimings()) timings.push_back(std::move(t));
    }
    ASSERT_EQ(timings.size(), 2u) << ProfileName(profile);
    // Where each packet's sound was played, timed the same way on what was played.
    const double rate = o.modem.sample_rate;
    std::size_t searched = 0;
    for (const OwnTiming& t : timings) {
      const TimingReference reference = PacketTimingReference(profile, o.modem);
      const std::size_t span = reference.sound.size() + static_cast<std::size_t>(2.5 * rate);
      ASSERT_LE(searched + span, device.played().size());
      const double played = static_cast<double>(searched) / rate - reference.offset / rate +
                            FirstArrival(device.played().data() + searched, span, reference.sound, rate);
      ASSERT_FALSE(std::isnan(t.arrival)) << ProfileName(profile);
      EXPECT_NEAR(t.arrival, played + static_cast<double>(loop) / rate, 2e-5) << ProfileName(profile);
      searched = static_cast<std::size_t>((played + link.profile().Airtime()) * rate);
    }
    EXPECT_EQ(link.own_timings_dropped(), 0u);
  }
}

// A sound card's loop can jump between packets (an underrun before a packet, a sound server
// settling after a restart, a link catching up): the packet is then not where the last one
// was. It is found over the whole loop again, never timed on the part of it that reached into
// the narrow search.
TEST(SelfTimerTest, ALoopThatJumpsBetweenPacketsIsFollowed) {
  const double rate = 48000.0;
  for (Profile profile : {Profile::kNava, Profile::kRoom}) {
    const std::unique_ptr<ModemProfile> p = MakeProfile(profile, ModemOptions{});
    const TimingReference reference = PacketTimingReference(profile, p->options());
    // Each packet: when it was sent, and its loop (s).
    const std::vector<std::pair<double, double>> packets = {
        {0.1, 0.040}, {2.6, 0.040}, {5.1, 0.061}, {7.6, 0.089}, {10.1, 0.052}, {12.6, 0.025}};
    std::vector<float> heard(static_cast<std::size_t>(15.5 * rate), 0.0f);
    std::mt19937 rng(2);
    std::normal_distribution<float> noise(0.0f, 0.002f);
    for (float& v : heard) v = noise(rng);
    std::vector<double> truth;
    for (std::size_t k = 0; k < packets.size(); ++k) {
      const std::vector<float> sound = p->ModulatePacket({static_cast<std::uint8_t>(k), 1, 2, 3});
      const std::size_t at = static_cast<std::size_t>(std::lround((packets[k].first + packets[k].second) * rate));
      for (std::size_t i = 0; i < sound.size(); ++i) heard[at + i] += sound[i];
      // The same definition on the packet alone: where its reference begins, plus the band's rise.
      std::vector<float> alone(reference.sound.size() + 4800, 0.0f);
      std::copy(sound.begin(), sound.begin() + static_cast<std::ptrdiff_t>(std::min(sound.size(), alone.size() - 2400)), alone.begin() + 2400);
      truth.push_back(static_cast<double>(at) / rate - 2400.0 / rate +
                      FirstArrival(alone.data(), alone.size(), reference.sound, rate) - reference.offset / rate);
    }
    SelfTimer timer(*p, 0.3);
    std::vector<OwnTiming> out;
    std::size_t fed = 0;
    // In blocks, as a link hears: the timer holds only a little more than a packet and a loop.
    const auto hear_until = [&](std::size_t until) {
      for (; fed < until; fed = std::min(until, fed + 1024)) timer.Heard(heard.data() + fed, std::min<std::size_t>(1024, until - fed), out);
    };
    for (std::size_t k = 0; k < packets.size(); ++k) {
      hear_until(static_cast<std::size_t>(packets[k].first * rate));
      timer.Sent({static_cast<std::uint8_t>(k), 1, 2, 3}, static_cast<double>(fed) / rate);
    }
    hear_until(heard.size());
    ASSERT_EQ(out.size(), packets.size()) << ProfileName(profile);
    for (std::size_t k = 0; k < out.size(); ++k) {
      EXPECT_EQ(out[k].data[0], k);
      EXPECT_NEAR(out[k].arrival, truth[k], 2e-5) << ProfileName(profile) << " packet " << k;
    }
  }
}

TEST(SelfTimerTest, NoiseAloneIsNotTakenForTheOwnPacket) {
  for (Profile profile : {Profile::kNava, Profile::kRoom}) {
    const std::unique_ptr<ModemProfile> p = MakeProfile(profile, ModemOptions{});
    for (unsigned seed = 1; seed <= 5; ++seed) {
      SelfTimer timer(*p, 0.5);
      timer.Sent({9, 9, 9, 9}, 0.0);
      std::mt19937 rng(seed);
      std::normal_distribution<float> noise(0.0f, 0.05f);
      std::vector<float> heard(static_cast<std::size_t>(2.0 * 48000.0));
      for (float& v : heard) v = noise(rng);
      std::vector<OwnTiming> out;
      timer.Heard(heard.data(), heard.size(), out);
      ASSERT_EQ(out.size(), 1u);
      EXPECT_TRUE(std::isnan(out[0].arrival)) << ProfileName(profile) << " seed " << seed;
    }
  }
}

TEST(SelfTimerTest, AnUnheardPacketIsReportedWithoutATime) {
  const std::unique_ptr<ModemProfile> room = MakeProfile(Profile::kRoom, ModemOptions{});
  SelfTimer timer(*room, 0.3);
  timer.Sent({9, 9, 9, 9}, 0.0);
  std::mt19937 rng(1);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<float> heard(static_cast<std::size_t>(1.0 * 48000.0));
  for (float& v : heard) v = noise(rng);
  std::vector<OwnTiming> out;
  timer.Heard(heard.data(), heard.size(), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].data, std::vector<std::uint8_t>({9, 9, 9, 9}));
  EXPECT_TRUE(std::isnan(out[0].arrival));
  // A failure's gap: what was pending is reported unheard, and the clock moves on.
  timer.Sent({1, 1, 1, 1}, timer.time());
  timer.Skip(2.0, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(std::isnan(out[1].arrival));
  EXPECT_NEAR(timer.time(), 3.0, 1e-9);
  EXPECT_EQ(timer.pending(), 0u);
  EXPECT_THROW(SelfTimer(*room, 0.0), std::invalid_argument);
  EXPECT_THROW(SelfTimer(*room, 11.0), std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
