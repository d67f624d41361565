#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nava_modem/csma_mac.h"
#include "nava_modem/frame.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/packet_receiver.h"

namespace nava_modem {

// The physical layers a link can run. Everything above (the 4-byte payload, its CRC, the
// CSMA-CA MAC, the noise classes, the ROS topics) is the same for all of them.
enum class Profile {
  kNava,  // the thesis's 300 bits/s FSK, 2300/3700 Hz, 110-bit packets; bit-exact, minimodem-compatible
  kRoom,  // chirp-synchronised hopping 16-FSK with a rate-1/3 convolutional code, for reverberant rooms
};
std::optional<Profile> ParseProfile(const std::string& name);  // nava | room
const char* ProfileName(Profile profile);
inline const char* kProfileNames = "nava or room";

// How the MAC counts time for a profile: its "bit" (the unit of back-off and of carrier
// release) and the packet's length in those bits. For nava a bit is a bit; for room, whose
// bits are coded and spread, it is 10 ms: the default back-off of 2 to 30 such bits (20 to
// 300 ms) then spreads senders well past the ~10 ms its carrier sense takes to react.
struct MacTiming {
  double bit_rate = 300.0;
  int packet_bits = 110;
};

// The frames a profile carries: how many data bytes, and at how many rates. A rate is a step of
// the profile's ladder, 0 the slowest and most robust; a receiver decodes every step without
// being told which, and reports the one it found (RxEvent::rate). `nava` carries the thesis's
// 4-byte packet; `room` frames of 1 to 255 bytes (room_frame.h), its 4-byte frame at rate 0 being
// today's packet.
struct FrameFormat {
  std::size_t min_bytes = kDataBytes, max_bytes = kDataBytes;
  int rates = 1;
};

// One profile's modulator, receiver and timing behind one interface.
class ModemProfile {
 public:
  virtual ~ModemProfile() = default;
  virtual Profile profile() const = 0;
  virtual FrameFormat Format() const = 0;
  // Throws std::invalid_argument naming the length or rate and what the profile carries.
  void CheckFrame(std::size_t data_bytes, int rate = 0) const;
  // The samples of one frame carrying `data` at rate step `rate` (CheckFrame's errors).
  virtual std::vector<float> Modulate(const std::vector<std::uint8_t>& data, int rate = 0) const = 0;
  // Seconds a frame of `data_bytes` lasts on the air at `rate` (CheckFrame's errors).
  virtual double Airtime(std::size_t data_bytes, int rate = 0) const = 0;
  // Today's packet: 4 data bytes at the slowest rate.
  std::vector<float> ModulatePacket(const std::vector<std::uint8_t>& data) const { return Modulate(data, 0); }
  double Airtime() const { return Airtime(kDataBytes, 0); }
  // Throws std::invalid_argument for impossible options (ValidateReceiverOptions).
  virtual std::unique_ptr<PacketReceiver> MakeReceiver(const ReceiverOptions& options) const = 0;
  virtual MacTiming Timing() const = 0;
  const ModemOptions& options() const { return options_; }

 protected:
  explicit ModemProfile(const ModemOptions& options) : options_(options) {}
  ModemOptions options_;
};

// Throws std::invalid_argument naming what of `options` the profile cannot use (what MakeProfile
// refuses): for nava its tones and bit rate (ValidateModemOptions), for room a sample rate its
// band fits (ValidateRoomRate); the amplitude for both.
void ValidateProfileOptions(Profile profile, const ModemOptions& options);

// A profile over the given options (sample rate, amplitude and CRC for every profile; tones
// and bit rate for nava only). Throws std::invalid_argument naming what does not fit.
std::unique_ptr<ModemProfile> MakeProfile(Profile profile, const ModemOptions& options);

// Timing without a sample rate (for the simulated channel); the airtime of today's packet.
MacTiming ProfileTiming(Profile profile, const ModemOptions& options = {});
double ProfileAirtime(Profile profile, const ModemOptions& options = {});
// The airtime of a frame of `data_bytes` at `rate`, for lengths and rates the profile carries
// (ModemProfile::CheckFrame judges them).
double FrameAirtime(Profile profile, const ModemOptions& options, std::size_t data_bytes, int rate);
// The frames a profile carries, without building it.
FrameFormat ProfileFormat(Profile profile);
// How long a steady tone must have sounded before the profile's receiver has whitened it away.
// room whitens by the least power at each frequency over its chirp detector's window, and its
// CFAR background then still holds the blocks from before: a whine that starts after quiet is
// whitened once both have forgotten the quiet (measured: 3 to 3.5 s). Until then it harms a
// packet as a tone the receiver has not notched. nava does not whiten: 0.
double WhineSettleSeconds(Profile profile);
// Sets the MAC's bit rate and packet length to the profile's.
void UseProfileTiming(Profile profile, const ModemOptions& options, MacOptions& mac);

}  // namespace nava_modem
