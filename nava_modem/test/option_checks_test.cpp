// The options checks beside each options struct of the link: a wrong value is refused with a
// message naming the field and the value; the defaults pass.
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/alsa_device.h"
#include "nava_modem/chirp_detector.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/nava_link.h"
#include "nava_modem/room_modulator.h"
#include "nava_modem/room_receiver.h"

namespace nava_modem {
namespace {

// What `check` throws (std::invalid_argument), or "accepted".
std::string Refusal(const std::function<void()>& check) {
  try {
    check();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

void ExpectRefused(const std::function<void()>& check, const std::string& words) {
  const std::string message = Refusal(check);
  EXPECT_NE(message.find(words), std::string::npos) << "expected '" << words << "' in: " << message;
}

TEST(ReceiverOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal([] { ValidateReceiverOptions({}); }), "accepted");
  auto with = [](const std::function<void(ReceiverOptions&)>& change) {
    ReceiverOptions o;
    change(o);
    return [o] { ValidateReceiverOptions(o); };
  };
  ExpectRefused(with([](ReceiverOptions& o) { o.detect_threshold = 0.0; }), "detect_threshold 0: expected 0.05 to 1");
  ExpectRefused(with([](ReceiverOptions& o) { o.detect_threshold = 1.5; }), "detect_threshold 1.5");
  ExpectRefused(with([](ReceiverOptions& o) { o.max_rate_error = 0.25; }), "max_rate_error 0.25");
  ExpectRefused(with([](ReceiverOptions& o) { o.max_rate_error = std::nan(""); }), "max_rate_error nan");
  ExpectRefused(with([](ReceiverOptions& o) { o.max_fixed_bits = 3; }), "max_fixed_bits 3: expected 0, 1 or 2");
  ExpectRefused(with([](ReceiverOptions& o) { o.carrier_threshold_db = std::numeric_limits<double>::infinity(); }),
                "carrier_threshold_db inf");
}

TEST(ReceiverOptions, EveryProfilesReceiverChecksThem) {
  ReceiverOptions wrong;
  wrong.max_fixed_bits = -1;
  for (Profile p : {Profile::kNava, Profile::kRoom}) {
    const auto profile = MakeProfile(p, ModemOptions{});
    ExpectRefused([&] { profile->MakeReceiver(wrong); }, "max_fixed_bits -1");
  }
}

TEST(ReceiverOptions, TheRoomReceiverTakesTheOneRange) {
  ReceiverOptions wide;
  wide.max_rate_error = 0.2;
  ExpectRefused([&] { RoomReceiver(ModemOptions{}, wide); }, "receiver max_rate_error 0.2: expected above 0 and below 0.2");
}

TEST(DirectionOptions, ImpossibleValuesAreNamed) {
  DirectionOptions o;
  o.mics = {{0.1, 0.0}, {-0.1, 0.0}};
  EXPECT_EQ(Refusal([&] { ValidateDirectionOptions(o); }), "accepted");
  o.max_seconds = 0.0;
  ExpectRefused([&] { ValidateDirectionOptions(o); }, "DirectionOptions: max_seconds 0 s; expected above 0");
  o.max_seconds = 0.2;
  o.low_hz = 5990.0;
  ExpectRefused([&] { DirectionEstimator{o}; }, "DirectionOptions: band 5990-6000 Hz; expected at least");
}

TEST(ChirpDetectorOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal([] { ValidateChirpDetectorOptions({}); }), "accepted");
  ChirpDetectorOptions o;
  o.threshold = 1.0;
  ExpectRefused([&] { ValidateChirpDetectorOptions(o); }, "chirp detector threshold 1: expected a finite factor above 1");
  o = {};
  o.guard_seconds = -0.01;
  ExpectRefused([&] { ChirpDetector(std::vector<float>(64, 0.5f), 48000.0, o); }, "chirp detector guard_seconds -0.01");
  ExpectRefused([] { ChirpDetector(std::vector<float>(64, 0.5f), 1000.0, {}); },
                "chirp detector sample rate 1000 Hz: expected 4000 to 384000");
}

TEST(SampleRate, OneRangeForEveryProfileAndDevice) {
  EXPECT_EQ(Refusal([] { ValidateSampleRate("sample rate", kMinSampleRate); }), "accepted");
  EXPECT_EQ(Refusal([] { ValidateSampleRate("sample rate", kMaxSampleRate); }), "accepted");
  ExpectRefused([] { ValidateSampleRate("sample rate", 2000.0); }, "sample rate 2000 Hz: expected 4000 to 384000");
  ExpectRefused([] { ValidateRoomRate(400000.0); }, "profile room: sample rate 400000 Hz: expected 4000 to 384000");
  ExpectRefused([] { ValidateRoomRate(8000.0); }, "cannot carry its band");
  ModemOptions fast;
  fast.sample_rate = 500000.0;
  ExpectRefused([&] { ValidateModemOptions(fast); }, "sample rate 500000 Hz");
  ModemOptions loud;
  loud.amplitude = 2.0;
  ExpectRefused([&] { RoomModulator{loud}; }, "amplitude 2: expected above 0 and at most 1");
}

TEST(AlsaOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal([] { ValidateAlsaOptions({}); }), "accepted");
  AlsaOptions o;
  o.sample_rate = 1000.0;
  ExpectRefused([&] { ValidateAlsaOptions(o); }, "ALSA sample rate 1000 Hz");
  o = {};
  o.device.clear();
  ExpectRefused([&] { ValidateAlsaOptions(o); }, "ALSA device");
  o = {};
  o.capture_channels = 0;
  ExpectRefused([&] { AlsaDevice{o}; }, "ALSA capture channels 0");
}

TEST(LinkOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal([] { ValidateLinkOptions({}); }), "accepted");
  LinkOptions o;
  o.receiver.detect_threshold = -1.0;
  ExpectRefused([&] { ValidateLinkOptions(o); }, "detect_threshold -1");
  o = {};
  o.max_capture_lag = 0.0;
  ExpectRefused([&] { ValidateLinkOptions(o); }, "max capture lag 0");
}

}  // namespace
}  // namespace nava_modem
