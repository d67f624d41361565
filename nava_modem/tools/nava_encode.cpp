// nava_encode: writes frames to a WAV file, one per HEX argument (its data bytes: 4 on the nava
// profile, 1 to 255 on room), at rate step --speed, with silence before, between and after them;
// or, with --list-rates, prints the profile's rates, one JSON line each.
//
//   nava_encode --out FILE.wav [--gap SECONDS] [--speed R] [modem options] HEX...
//   nava_encode --list-rates [--profile nava|room]
#include <algorithm>
#include <cmath>
#include <iostream>

#include "nava_encode_args.h"
#include "nava_modem/room_frame.h"
#include "tool_args/json_text.h"
#include "nava_modem/wav_file.h"

namespace {

// One JSON line per rate: its name, payload bits per second on 64-byte frames (on the profile's
// longest frame where it carries fewer), and the airtimes of 4- and 64-byte frames (null where
// the profile does not carry them).
void PrintRates(const nava_modem::ModemProfile& profile, std::ostream& out) {
  using multirobot_audio::tools::JsonNumber;
  const nava_modem::FrameFormat f = profile.Format();
  auto airtime = [&](std::size_t bytes, int rate) {
    return bytes >= f.min_bytes && bytes <= f.max_bytes ? JsonNumber(profile.Airtime(bytes, rate), 3) : std::string("null");
  };
  for (int rate = 0; rate < f.rates; ++rate) {
    const std::size_t longest = std::min<std::size_t>(64, f.max_bytes);
    const char* name = profile.profile() == nava_modem::Profile::kNava ? "nava" : nava_modem::room_frame::RateName(rate);
    out << "{\"profile\": \"" << nava_modem::ProfileName(profile.profile()) << "\", \"rate\": " << rate << ", \"name\": \""
        << name << "\", \"bit_rate\": " << JsonNumber(8.0 * longest / profile.Airtime(longest, rate), 1)
        << ", \"airtime_4\": " << airtime(4, rate) << ", \"airtime_64\": " << airtime(64, rate) << "}\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nava_modem;
  return multirobot_audio::tools::RunTool([&] {
    const tools::NavaEncodeOptions o = tools::ParseNavaEncodeArgs(multirobot_audio::tools::Words(argc, argv));
    const ModemOptions& options = o.modem.options;
    const auto profile = MakeProfile(o.modem.profile, options);
    if (o.list_rates) {
      PrintRates(*profile, std::cout);
      return 0;
    }
    const std::size_t gap_samples = static_cast<std::size_t>(std::lround(o.gap * options.sample_rate));
    std::vector<float> audio(gap_samples, 0.0f);
    for (const std::vector<std::uint8_t>& data : o.packets) {
      const std::vector<float> burst = profile->Modulate(data, o.speed);
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
