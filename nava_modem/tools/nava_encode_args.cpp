#include "nava_encode_args.h"

namespace nava_modem::tools {

NavaEncodeOptions ParseNavaEncodeArgs(const std::vector<std::string>& words) {
  const std::string usage = std::string("nava_encode --out FILE.wav [--gap 0.5] [--speed 0] ") + kModemUsage +
                            " HEX...\n       nava_encode --list-rates [--profile nava|room]";
  const multirobot_audio::tools::ToolArgs args("nava_encode", usage, words, {"--list-rates"});
  NavaEncodeOptions o;
  o.list_rates = args.Switch("--list-rates");
  o.out = o.list_rates ? args.String("--out", "") : args.Required("--out");
  o.gap = args.Double("--gap", 0.5, 0.0, 3600.0);
  o.modem = ProfileArgs(args);
  const FrameFormat format = ProfileFormat(o.modem.profile);
  o.speed = static_cast<int>(args.Int("--speed", 0, 0, format.rates - 1));
  const std::vector<std::string>& hex = args.positional();
  args.CheckAllUsed();
  if (o.list_rates) {
    if (!hex.empty()) args.Fail("--list-rates takes no HEX");
    return o;
  }
  const std::string lengths = format.min_bytes == format.max_bytes
                                  ? std::to_string(2 * format.min_bytes) + " hex digits (" + std::to_string(format.min_bytes) + " data bytes)"
                                  : std::to_string(2 * format.min_bytes) + " to " + std::to_string(2 * format.max_bytes) +
                                        " hex digits (" + std::to_string(format.min_bytes) + " to " +
                                        std::to_string(format.max_bytes) + " data bytes)";
  if (hex.empty()) args.Fail("no frames: give one HEX argument (" + lengths + ") per frame");
  for (const std::string& h : hex) {
    o.packets.push_back(ParseHexBytes(h));
    const std::size_t n = o.packets.back().size();
    if (n < format.min_bytes || n > format.max_bytes) {
      args.Fail("frame '" + h + "': expected " + lengths + " on profile " + ProfileName(o.modem.profile) + ", e.g. 0102a0ff");
    }
  }
  return o;
}

}  // namespace nava_modem::tools
