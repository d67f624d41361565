#pragma once

// The options every nava_modem tool takes, like the node's parameters:
// --profile nava|room --mark HZ --space HZ --baud BPS --rate HZ --amplitude A --crc ccitt-false|xmodem
// (--mark, --space and --baud set the nava profile's FSK and are refused with --profile room).
#include <cstdint>
#include <string>
#include <vector>

#include "nava_modem/modem_options.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"
#include "tool_args/tool_args.h"

namespace nava_modem::tools {

inline const char* kModemUsage =
    "[--profile nava|room] [--mark 2300] [--space 3700] [--baud 300] [--rate 48000] [--amplitude 0.5] "
    "[--crc ccitt-false|xmodem]";

struct ToolModem {
  Profile profile = Profile::kNava;
  ModemOptions options;
};

inline ModemOptions ModemArgs(const multirobot_audio::tools::ToolArgs& args);

// The profile and its options; a profile that cannot run with them (say, room at 8000 Hz) is
// refused here, by name.
inline ToolModem ProfileArgs(const multirobot_audio::tools::ToolArgs& args) {
  ToolModem m;
  const std::string name = args.String("--profile", "nava");
  const auto profile = ParseProfile(name);
  if (!profile) args.Fail(std::string("--profile: expected ") + kProfileNames + ", got " + name);
  m.profile = *profile;
  if (m.profile != Profile::kNava) {
    for (const char* flag : {"--mark", "--space", "--baud"}) {
      if (!args.String(flag, "").empty()) args.Fail(std::string(flag) + " sets the nava profile's FSK; the " + name + " profile has its own tones");
    }
  }
  m.options = ModemArgs(args);
  try {
    MakeProfile(m.profile, m.options);
  } catch (const std::exception& e) {
    args.Fail(e.what());
  }
  return m;
}

// --response: the room model by name (ParseRoomModel), `fallback` when not given; refused
// through `args`, naming the flag and the names, when unknown, and for "measured": these tools
// draw a room from its RT60 and DRR (a measured one is given with --rir or --rir-dir).
inline RoomOptions::Model RoomModelArg(const multirobot_audio::tools::ToolArgs& args, RoomOptions::Model fallback) {
  const std::string model = args.String("--response", RoomModelName(fallback));
  const auto parsed = ParseRoomModel(model);
  if (!parsed || *parsed == RoomOptions::Model::kMeasured) {
    args.Fail("--response " + model + ": expected statistical or measured-like (a measured room: --rir or --rir-dir)");
  }
  return *parsed;
}

inline ModemOptions ModemArgs(const multirobot_audio::tools::ToolArgs& args) {
  ModemOptions o;
  o.mark_hz = args.Double("--mark", o.mark_hz, 1.0, 1e6);
  o.space_hz = args.Double("--space", o.space_hz, 1.0, 1e6);
  o.baud = args.Double("--baud", o.baud, 1.0, 1e6);
  o.sample_rate = args.Double("--rate", o.sample_rate, 1.0, 1e7);
  o.amplitude = args.Double("--amplitude", o.amplitude, 1e-6, 1.0);
  const std::string crc = args.String("--crc", "ccitt-false");
  const auto variant = ParseCrcVariant(crc);
  if (!variant) args.Fail("--crc: expected ccitt-false or xmodem, got " + crc);
  o.crc = *variant;
  try {
    ValidateModemOptions(o);
  } catch (const std::exception& e) {
    args.Fail(e.what());
  }
  return o;
}

// "0a0b0c" -> {0x0a, 0x0b, 0x0c}; empty when it is not a whole number of bytes in hex digits.
inline std::vector<std::uint8_t> ParseHexBytes(const std::string& hex) {
  if (hex.empty() || hex.size() % 2 || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return {};
  std::vector<std::uint8_t> out;
  for (std::size_t k = 0; k < hex.size(); k += 2) out.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(k, 2), nullptr, 16)));
  return out;
}

inline std::string HexBytes(const std::vector<std::uint8_t>& data) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (std::uint8_t b : data) {
    out += digits[b >> 4];
    out += digits[b & 15];
  }
  return out;
}

}  // namespace nava_modem::tools
