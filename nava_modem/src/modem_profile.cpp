#include "nava_modem/modem_profile.h"

#include <cmath>
#include <string>

#include "nava_modem/chirp_detector.h"
#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/fsk_receiver.h"
#include "nava_modem/room_frame.h"
#include "nava_modem/room_modulator.h"
#include "nava_modem/room_phy.h"
#include "nava_modem/room_receiver.h"

namespace nava_modem {
namespace {

// A profile from its modulator and receiver classes (each built from the modem options).
template <Profile kKind, typename Modulator, typename Receiver>
class ProfileOf : public ModemProfile {
 public:
  explicit ProfileOf(const ModemOptions& options) : ModemProfile(options), modulator_(options) {}
  Profile profile() const override { return kKind; }
  FrameFormat Format() const override { return ProfileFormat(kKind); }
  std::vector<float> Modulate(const std::vector<std::uint8_t>& data, int rate) const override {
    CheckFrame(data.size(), rate);
    if constexpr (kKind == Profile::kRoom) {
      return modulator_.Modulate(data, rate);
    } else {
      return modulator_.ModulatePacket(data);
    }
  }
  // Each receiver validates its options before it builds anything from them.
  std::unique_ptr<PacketReceiver> MakeReceiver(const ReceiverOptions& options) const override {
    return std::make_unique<Receiver>(options_, options);
  }
  double Airtime(std::size_t data_bytes, int rate) const override {
    CheckFrame(data_bytes, rate);
    return FrameAirtime(kKind, options_, data_bytes, rate);
  }
  MacTiming Timing() const override { return ProfileTiming(kKind, options_); }

 private:
  Modulator modulator_;
};

}  // namespace

std::optional<Profile> ParseProfile(const std::string& name) {
  if (name == "nava") return Profile::kNava;
  if (name == "room") return Profile::kRoom;
  return std::nullopt;
}

void ModemProfile::CheckFrame(std::size_t data_bytes, int rate) const {
  const FrameFormat f = Format();
  if (data_bytes < f.min_bytes || data_bytes > f.max_bytes) {
    const std::string carried = f.min_bytes == f.max_bytes ? std::to_string(f.min_bytes)
                                                           : std::to_string(f.min_bytes) + " to " + std::to_string(f.max_bytes);
    throw std::invalid_argument(std::string("a ") + ProfileName(profile()) + " frame carries " + carried + " data bytes, got " +
                                std::to_string(data_bytes));
  }
  if (rate < 0 || rate >= f.rates) {
    throw std::invalid_argument(std::string("rate ") + std::to_string(rate) + ": the " + ProfileName(profile()) +
                                " profile has rates 0 to " + std::to_string(f.rates - 1));
  }
}

FrameFormat ProfileFormat(Profile profile) {
  if (profile == Profile::kNava) return FrameFormat{};
  return FrameFormat{room_frame::kMinBytes, room_frame::kMaxBytes, room_frame::kRates};
}

const char* ProfileName(Profile profile) { return profile == Profile::kNava ? "nava" : "room"; }

void ValidateProfileOptions(Profile profile, const ModemOptions& options) {
  if (profile == Profile::kNava) {
    ValidateModemOptions(options);
    return;
  }
  ValidateRoomRate(options.sample_rate);
  ValidateAmplitude(options.amplitude);
}

std::unique_ptr<ModemProfile> MakeProfile(Profile profile, const ModemOptions& options) {
  if (profile == Profile::kNava) return std::make_unique<ProfileOf<Profile::kNava, FskModulator, FskReceiver>>(options);
  return std::make_unique<ProfileOf<Profile::kRoom, RoomModulator, RoomReceiver>>(options);
}

MacTiming ProfileTiming(Profile profile, const ModemOptions& options) {
  if (profile == Profile::kNava) return MacTiming{options.baud, kPacketBits};
  const double slot = 0.010;
  return MacTiming{1.0 / slot, static_cast<int>(std::ceil(room_phy::kPacketSeconds / slot - 1e-9))};
}

void UseProfileTiming(Profile profile, const ModemOptions& options, MacOptions& mac) {
  const MacTiming timing = ProfileTiming(profile, options);
  mac.bit_rate = timing.bit_rate;
  mac.packet_bits = timing.packet_bits;
}

double ProfileAirtime(Profile profile, const ModemOptions& options) { return FrameAirtime(profile, options, kDataBytes, 0); }

double FrameAirtime(Profile profile, const ModemOptions& options, std::size_t data_bytes, int rate) {
  if (profile == Profile::kNava) return kPacketBits / options.baud;
  return room_frame::FrameSeconds(static_cast<int>(data_bytes), rate);
}

double WhineSettleSeconds(Profile profile) {
  if (profile == Profile::kNava) return 0.0;
  const ChirpDetectorOptions detector;  // the room receiver's own
  return detector.whitening_seconds + detector.background_seconds + detector.guard_seconds;
}

}  // namespace nava_modem
