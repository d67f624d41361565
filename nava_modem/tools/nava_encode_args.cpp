#include "nava_encode_args.h"

namespace nava_modem::tools {

NavaEncodeOptions ParseNavaEncodeArgs(const std::vector<std::string>& words) {
  const std::string usage = std::string("nava_encode --out FILE.wav [--gap 0.5] ") + kModemUsage + " HEX...";
  const multirobot_audio::tools::ToolArgs args("nava_encode", usage, words);
  NavaEncodeOptions o;
  o.out = args.Required("--out");
  o.gap = args.Double("--gap", 0.5, 0.0, 3600.0);
  o.modem = ProfileArgs(args);
  const std::vector<std::string>& hex = args.positional();
  args.CheckAllUsed();
  if (hex.empty()) args.Fail("no packets: give one HEX argument (8 hex digits) per packet");
  for (const std::string& h : hex) {
    o.packets.push_back(ParseHexPacket(h));
    if (o.packets.back().empty()) args.Fail("packet '" + h + "': expected 8 hex digits (4 data bytes), e.g. 0102a0ff");
  }
  return o;
}

}  // namespace nava_modem::tools
