#include "nava_decode_args.h"

#include "nava_modem/direction_estimator.h"

namespace nava_modem::tools {

NavaDecodeOptions ParseNavaDecodeArgs(const std::vector<std::string>& words) {
  const std::string usage = std::string("nava_decode [--threshold-db -40] [--max-fixed-bits 2] [--mics x1,y1,x2,y2,...] ") +
                            "[--diagnostics FILE.json] " + kModemUsage + " FILE.wav";
  const multirobot_audio::tools::ToolArgs args("nava_decode", usage, words);
  NavaDecodeOptions o;
  o.usage = args.tool_usage();
  o.threshold_db = args.Double("--threshold-db", kToolCarrierThresholdDb, -200.0, 20.0);
  o.max_fixed_bits = static_cast<int>(args.Int("--max-fixed-bits", 2, 0, 2));
  o.given_rate = args.String("--rate", "");
  if (const std::string text = args.String("--mics", ""); !text.empty()) {
    try {
      o.mics = ParseMicPositions(text);
    } catch (const std::exception& e) {
      args.Fail(std::string("--mics: ") + e.what());
    }
  }
  const std::vector<std::string>& files = args.positional();
  if (files.size() != 1) args.Fail("expected one audio file");
  o.file = files[0];
  o.modem = ProfileArgs(args);
  // Only the nava profile's receiver keeps a trace of its stages, and only on one channel.
  o.diagnostics = args.String("--diagnostics", "");
  if (args.given().count("--diagnostics")) {
    if (o.diagnostics.empty()) args.Fail("--diagnostics: expected a file to write the JSON to");
    if (o.modem.profile != Profile::kNava) {
      args.Fail(std::string("--diagnostics: only the nava profile's receiver keeps diagnostics, not the ") + ProfileName(o.modem.profile) +
                " profile's");
    }
    if (o.mics) args.Fail("--diagnostics: not with --mics (diagnostics trace one channel's receiver)");
  }
  args.CheckAllUsed();
  return o;
}

}  // namespace nava_modem::tools
