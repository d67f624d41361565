// The whole link on files: what it hears from a WAV, and what it plays into one.
#include "nava_modem/nava_link.h"

#include <unistd.h>

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "nava_modem/fsk_modulator.h"
#include "nava_modem/fsk_receiver.h"

#include "nava_modem/room_array.h"
#include "nava_modem/wav_device.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

std::string TempWav(const std::string& name) { return "/tmp/nava_link_" + std::to_string(getpid()) + "_" + name; }

LinkOptions Quick() {
  LinkOptions o;
  o.mac.calibration_time = 1.0;
  return o;
}

TEST(NavaLink, HearsAPacketAfterCalibratingAndReportsItOnce) {
  LinkOptions o = Quick();
  const FskModulator mod(o.modem);
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0.0f, 0.003f);
  std::vector<float> audio(static_cast<std::size_t>(1.5 * o.modem.sample_rate));  // quiet room
  const std::vector<float> burst = mod.ModulatePacket({7, 7, 7, 7});
  audio.insert(audio.end(), burst.begin(), burst.end());
  audio.resize(audio.size() + static_cast<std::size_t>(1.0 * o.modem.sample_rate));
  for (float& x : audio) x += g(rng);
  const std::string in = TempWav("in.wav");
  WriteWavFile(in, audio, o.modem.sample_rate);
  WavDevice device(in, "");
  NavaLink link(o, device);
  std::vector<RxEvent> events;
  bool carrier_seen = false;
  while (link.Tick(events)) carrier_seen = carrier_seen || link.carrier();
  std::remove(in.c_str());
  EXPECT_TRUE(carrier_seen);
  EXPECT_EQ(link.mac().state(), MacState::kWaiting);
  EXPECT_GT(link.mac().threshold_db(), -60.0);  // calibrated on the quiet room
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(events[0].data, std::vector<std::uint8_t>({7, 7, 7, 7}));
  EXPECT_NEAR(events[0].start, 1.5, 0.01);
}

TEST(NavaLink, PlaysWhatItSendsAndIsDeafToItsOwnEcho) {
  LinkOptions o = Quick();
  o.mac.fixed_threshold_db = -40.0;
  // Its own packet comes back 50 ms later, as a speaker next to the microphone would.
  const std::string silent = TempWav("silent.wav");
  WriteWavFile(silent, std::vector<float>(static_cast<std::size_t>(3.0 * o.modem.sample_rate)), o.modem.sample_rate);
  WavDevice dry(silent, "");
  NavaLink link(o, dry);
  ASSERT_TRUE(link.Send({1, 2, 3, 4}));
  EXPECT_THROW(link.Send({1, 2, 3}), std::invalid_argument);
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  EXPECT_EQ(link.packets_sent(), 1u);
  EXPECT_TRUE(events.empty());
  // What it played decodes as its packet.
  FskReceiver rx(o.modem, {});
  std::vector<RxEvent> heard;
  rx.Process(dry.played().data(), dry.played().size(), heard);
  rx.Flush(heard);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].data, std::vector<std::uint8_t>({1, 2, 3, 4}));
  // Played again into a link that is sending at the same moment: its echo is not heard.
  std::vector<float> echo(static_cast<std::size_t>(0.05 * o.modem.sample_rate), 0.0f);
  echo.insert(echo.end(), dry.played().begin(), dry.played().end());
  const std::string echo_file = TempWav("echo.wav");
  WriteWavFile(echo_file, echo, o.modem.sample_rate);
  WavDevice wet(echo_file, "");
  NavaLink again(o, wet);
  ASSERT_TRUE(again.Send({1, 2, 3, 4}));
  events.clear();
  while (again.Tick(events)) {
  }
  std::remove(silent.c_str());
  std::remove(echo_file.c_str());
  EXPECT_TRUE(events.empty()) << "heard its own echo";
}

// The same link runs the room profile: it plays room packets and hears them, with the MAC
// timed by the profile.
TEST(NavaLink, RunsTheRoomProfile) {
  LinkOptions o = Quick();
  o.profile = Profile::kRoom;
  o.modem.sample_rate = 16000.0;
  o.mac.fixed_threshold_db = -40.0;
  const std::string silent = TempWav("room_silent.wav");
  WriteWavFile(silent, std::vector<float>(static_cast<std::size_t>(4.0 * o.modem.sample_rate)), o.modem.sample_rate);
  WavDevice dry(silent, "");
  NavaLink link(o, dry);
  EXPECT_NEAR(link.mac().packet_ticks() * link.mac().tick_seconds(), ProfileAirtime(Profile::kRoom), 1e-9);
  ASSERT_TRUE(link.Send({9, 8, 7, 6}));
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  std::remove(silent.c_str());
  EXPECT_EQ(link.packets_sent(), 1u);
  EXPECT_TRUE(events.empty()) << "deaf to itself";

  const std::string heard = TempWav("room_heard.wav");
  WriteWavFile(heard, dry.played(), o.modem.sample_rate);
  WavDevice device(heard, "");
  NavaLink listener(o, device);
  while (listener.Tick(events)) {
  }
  std::remove(heard.c_str());
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(events[0].data, std::vector<std::uint8_t>({9, 8, 7, 6}));
}

// Frames of any length on the room link: a 64-byte frame at the link's rate 1 and a 4-byte one
// at rate 2 named by Send() play for their own airtimes, one after the other, and a listening
// link hears both whole, each with its rate. A rate off the ladder is refused, named.
TEST(NavaLink, SendsAndHearsFramesOfAnyLengthAtEachRate) {
  LinkOptions o = Quick();
  o.profile = Profile::kRoom;
  o.modem.sample_rate = 16000.0;
  o.mac.fixed_threshold_db = -40.0;
  o.rate = 1;
  std::vector<std::uint8_t> long_frame(64);
  for (std::size_t k = 0; k < long_frame.size(); ++k) long_frame[k] = static_cast<std::uint8_t>(31 * k + 5);
  const double airtimes = FrameAirtime(Profile::kRoom, o.modem, 64, 1) + FrameAirtime(Profile::kRoom, o.modem, 4, 2);
  const std::string silent = TempWav("frames_silent.wav");
  WriteWavFile(silent, std::vector<float>(static_cast<std::size_t>((airtimes + 2.0) * o.modem.sample_rate)),
               o.modem.sample_rate);
  WavDevice dry(silent, "");
  NavaLink link(o, dry);
  ASSERT_TRUE(link.Send(long_frame));
  ASSERT_TRUE(link.Send({1, 2, 3, 4}, 2));
  EXPECT_THROW(link.Send({1, 2, 3, 4}, 3), std::invalid_argument);
  EXPECT_THROW(link.Send(std::vector<std::uint8_t>(256)), std::invalid_argument);
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  std::remove(silent.c_str());
  EXPECT_EQ(link.packets_sent(), 2u);

  const std::string heard = TempWav("frames_heard.wav");
  std::vector<float> played = dry.played();
  played.resize(played.size() + static_cast<std::size_t>(2.0 * o.modem.sample_rate));
  WriteWavFile(heard, played, o.modem.sample_rate);
  WavDevice device(heard, "");
  NavaLink listener(o, device);
  events.clear();
  while (listener.Tick(events)) {
  }
  std::remove(heard.c_str());
  std::vector<std::pair<std::vector<std::uint8_t>, int>> frames;
  for (const RxEvent& e : events) {
    if (e.kind == RxEvent::Kind::kPacket) frames.emplace_back(e.data, e.rate);
  }
  const std::vector<std::pair<std::vector<std::uint8_t>, int>> sent = {{long_frame, 1}, {{1, 2, 3, 4}, 2}};
  EXPECT_EQ(frames, sent);

  LinkOptions bad = o;
  bad.rate = 3;
  EXPECT_THROW(ValidateLinkOptions(bad), std::invalid_argument);
}

// A microphone array on the link: each reception comes with its direction, from its own
// samples on every channel (a four-microphone square hearing a room packet from 60 degrees in a
// reverberant room, rendered by nava_room's array renderer).
TEST(NavaLink, GivesEachReceptionItsDirection) {
  LinkOptions o = Quick();
  o.profile = Profile::kRoom;
  o.modem.sample_rate = 16000.0;
  o.mac.fixed_threshold_db = -40.0;
  const double half = 0.1 / std::sqrt(2.0);
  o.microphones = {{half, half}, {-half, half}, {-half, -half}, {half, -half}};
  const auto profile = MakeProfile(Profile::kRoom, o.modem);
  std::vector<float> clean(static_cast<std::size_t>(1.0 * o.modem.sample_rate), 0.0f);
  const std::vector<float> burst = profile->ModulatePacket({5, 6, 7, 8});
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.resize(clean.size() + static_cast<std::size_t>(3.0 * o.modem.sample_rate), 0.0f);
  RoomOptions room;
  room.rt60 = 0.5;
  room.drr_db = 0.0;
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = 20.0;
  ArraySource source;
  source.mics = o.microphones;
  source.bearing = M_PI / 3.0;
  const std::string file = TempWav("array.wav");
  WriteWavChannels(file, RenderRoomArray(clean, o.modem.sample_rate, room, source), o.modem.sample_rate);
  WavDevice device(file, "");
  std::remove(file.c_str());
  EXPECT_EQ(device.capture_channels(), 4);
  NavaLink link(o, device);
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].data, std::vector<std::uint8_t>({5, 6, 7, 8}));
  ASSERT_TRUE(std::isfinite(events[0].direction));
  EXPECT_NEAR(std::remainder(events[0].direction - M_PI / 3.0, 2.0 * M_PI), 0.0, 5.0 * M_PI / 180.0);
  EXPECT_GT(events[0].direction_confidence, 0.0);

  // Positions that do not match the device's channels are refused.
  const std::string mono_file = TempWav("mono.wav");
  WriteWavFile(mono_file, std::vector<float>(1600), o.modem.sample_rate);
  WavDevice mono(mono_file, "");
  std::remove(mono_file.c_str());
  EXPECT_THROW(NavaLink(o, mono), std::invalid_argument);
}

// Silence in, and an underrun reported by the device at chosen points of playback.
class UnderrunningDevice : public AudioDevice {
 public:
  UnderrunningDevice(double rate, std::vector<std::size_t> underrun_at) : rate_(rate), at_(std::move(underrun_at)) {}
  double sample_rate() const override { return rate_; }
  bool Read(float* out, std::size_t count) override {
    if (read_ + count > static_cast<std::size_t>(3.0 * rate_)) return false;
    std::fill(out, out + count, 0.0f);
    read_ += count;
    return true;
  }
  void Write(const float*, std::size_t count) override {
    for (std::size_t s : at_) underruns_ += s >= played_ && s < played_ + count;
    played_ += count;
  }
  std::size_t PlaybackDelay() override { return 0; }
  std::size_t PlaybackRoom() override { return SIZE_MAX; }
  std::size_t CaptureLag() override { return 0; }
  void Reopen() override {}
  std::uint64_t overruns() const override { return 0; }
  std::uint64_t underruns() const override { return underruns_; }

 private:
  double rate_;
  std::vector<std::size_t> at_;
  std::size_t read_ = 0, played_ = 0;
  std::uint64_t underruns_ = 0;
};

TEST(NavaLink, CountsAPacketCutByAnUnderrunOnce) {
  LinkOptions o = Quick();
  o.mac.fixed_threshold_db = -40.0;
  o.mac.backoff_min_bits = o.mac.backoff_max_bits = 0.0;
  const double rate = o.modem.sample_rate;
  const auto at = [rate](double seconds) { return static_cast<std::size_t>(seconds * rate); };
  // The packet goes out at once and lasts 0.37 s: two underruns inside it count once; one long
  // after it, or in the very first write (a gap before the packet's first sound), not at all.
  for (const auto& [underruns, cut] : std::vector<std::pair<std::vector<std::size_t>, std::uint64_t>>{
           {{at(0.1), at(0.2), at(2.0)}, 1u}, {{at(2.0)}, 0u}, {{0}, 0u}}) {
    UnderrunningDevice device(rate, underruns);
    NavaLink link(o, device);
    ASSERT_TRUE(link.Send({1, 2, 3, 4}));
    std::vector<RxEvent> events;
    while (link.Tick(events)) {
    }
    EXPECT_EQ(link.packets_sent(), 1u);
    EXPECT_EQ(link.underruns(), underruns.size());
    EXPECT_EQ(link.packets_cut(), cut) << underruns.size() << " underruns";
  }
}

TEST(NavaLink, RejectsADeviceAtAnotherRate) {
  LinkOptions o = Quick();
  const std::string file = TempWav("rate.wav");
  WriteWavFile(file, std::vector<float>(1000), 16000.0);
  WavDevice device(file, "");
  std::remove(file.c_str());
  EXPECT_THROW(NavaLink(o, device), std::invalid_argument);
  EXPECT_THROW(WavDevice("/nonexistent/x.wav", ""), std::runtime_error);
}

}  // namespace
}  // namespace nava_modem
