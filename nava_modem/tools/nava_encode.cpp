// nava_encode: writes Nava packets to a WAV file, one per HEX argument (8 hex digits = the 4
// data bytes), with silence before, between and after them.
//
//   nava_encode --out FILE.wav [--gap SECONDS] [modem options] HEX...
#include <cmath>
#include <iostream>

#include "nava_encode_args.h"
#include "nava_modem/wav_file.h"

int main(int argc, char** argv) {
  using namespace nava_modem;
  return multirobot_audio::tools::RunTool([&] {
    const tools::NavaEncodeOptions o = tools::ParseNavaEncodeArgs(multirobot_audio::tools::Words(argc, argv));
    const ModemOptions& options = o.modem.options;
    const auto profile = MakeProfile(o.modem.profile, options);
    const std::size_t gap_samples = static_cast<std::size_t>(std::lround(o.gap * options.sample_rate));
    std::vector<float> audio(gap_samples, 0.0f);
    for (const std::vector<std::uint8_t>& data : o.packets) {
      const std::vector<float> burst = profile->ModulatePacket(data);
      audio.insert(audio.end(), burst.begin(), burst.end());
      audio.insert(audio.end(), gap_samples, 0.0f);
    }
    try {
      WriteWavFile(o.out, audio, options.sample_rate);
    } catch (const std::exception& e) {
      std::cerr << "nava_encode: " << e.what() << "\n";
      return 1;
    }
    return 0;
  });
}
