// nava_encode: writes Nava packets to a WAV file, one per HEX argument (8 hex digits = the 4
// data bytes), with silence before, between and after them.
//
//   nava_encode --out FILE.wav [--gap SECONDS] [modem options] HEX...
#include <cmath>
#include <iostream>

#include "modem_args.h"
#include "nava_modem/wav_file.h"

int main(int argc, char** argv) {
  using namespace nava_modem;
  const std::string usage = std::string("nava_encode --out FILE.wav [--gap 0.5] ") + tools::kModemUsage + " HEX...";
  const multirobot_audio::tools::ToolArgs args("nava_encode", usage, argc, argv);
  const std::string out = args.Required("--out");
  const double gap = args.Double("--gap", 0.5, 0.0, 3600.0);
  const tools::ToolModem modem = tools::ProfileArgs(args);
  const ModemOptions& options = modem.options;
  const std::vector<std::string>& hex = args.positional();
  args.CheckAllUsed();
  if (hex.empty()) args.Fail("no packets: give one HEX argument (8 hex digits) per packet");

  const auto profile = MakeProfile(modem.profile, options);
  const std::size_t gap_samples = static_cast<std::size_t>(std::lround(gap * options.sample_rate));
  std::vector<float> audio(gap_samples, 0.0f);
  for (const std::string& h : hex) {
    const std::vector<std::uint8_t> data = tools::ParseHexPacket(h);
    if (data.empty()) args.Fail("packet '" + h + "': expected 8 hex digits (4 data bytes), e.g. 0102a0ff");
    const std::vector<float> burst = profile->ModulatePacket(data);
    audio.insert(audio.end(), burst.begin(), burst.end());
    audio.insert(audio.end(), gap_samples, 0.0f);
  }
  try {
    WriteWavFile(out, audio, options.sample_rate);
  } catch (const std::exception& e) {
    std::cerr << "nava_encode: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
