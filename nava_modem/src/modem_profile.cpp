#include "nava_modem/modem_profile.h"

#include <cmath>

#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/fsk_receiver.h"
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
  std::vector<float> ModulatePacket(const std::vector<std::uint8_t>& data) const override {
    return modulator_.ModulatePacket(data);
  }
  // Each receiver validates its options before it builds anything from them.
  std::unique_ptr<PacketReceiver> MakeReceiver(const ReceiverOptions& options) const override {
    return std::make_unique<Receiver>(options_, options);
  }
  double Airtime() const override { return ProfileAirtime(kKind, options_); }
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

double ProfileAirtime(Profile profile, const ModemOptions& options) {
  if (profile == Profile::kNava) return kPacketBits / options.baud;
  return room_phy::kPacketSeconds;
}

}  // namespace nava_modem
