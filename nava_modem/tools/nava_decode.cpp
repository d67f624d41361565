// nava_decode: decodes the Nava packets in an audio file; one JSON line per event, e.g.
//   {"t": 1.234, "kind": "packet", "noise": "none", "data": "01020304", "level_db": -20.5, "quality": 0.83, ...}
// t is the end of the reception in seconds from the start of the file.
//
//   nava_decode [--threshold-db -40] [--max-fixed-bits 2] [modem options] FILE.wav
// --rate, if given, must be the file's rate.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "modem_args.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/wav_file.h"

int main(int argc, char** argv) {
  using namespace nava_modem;
  const std::string usage = std::string("nava_decode [--threshold-db -40] [--max-fixed-bits 2] ") + tools::kModemUsage + " FILE.wav";
  const multirobot_audio::tools::ToolArgs args("nava_decode", usage, argc, argv);
  const double threshold = args.Double("--threshold-db", -40.0, -200.0, 20.0);
  const int fixed = static_cast<int>(args.Int("--max-fixed-bits", 2, 0, 2));
  const std::string given_rate = args.String("--rate", "");
  const std::vector<std::string>& files = args.positional();
  if (files.size() != 1) args.Fail("expected one audio file");
  Audio audio;
  try {
    audio = ReadAudioFile(files[0]);
  } catch (const std::exception& e) {
    std::cerr << "nava_decode: " << e.what() << "\n";
    return 1;
  }
  tools::ToolModem modem = tools::ProfileArgs(args);
  ModemOptions& options = modem.options;
  if (!given_rate.empty() && std::abs(options.sample_rate - audio.sample_rate) > 0.5) {
    args.Fail("--rate " + given_rate + " Hz, but " + files[0] + " is sampled at " +
              std::to_string(static_cast<long>(audio.sample_rate)) + " Hz");
  }
  options.sample_rate = audio.sample_rate;
  args.CheckAllUsed();
  ReceiverOptions rx;
  rx.carrier_threshold_db = threshold;
  rx.max_fixed_bits = fixed;
  std::vector<RxEvent> events;
  try {
    const auto receiver = MakeProfile(modem.profile, options)->MakeReceiver(rx);
    receiver->Process(audio.samples.data(), audio.samples.size(), events);
    receiver->Flush(events);
  } catch (const std::exception& e) {
    std::cerr << "nava_decode: " << files[0] << ": " << e.what() << "\n";
    return 1;
  }
  for (const RxEvent& e : events) {
    std::printf("{\"t\": %.3f, \"kind\": \"%s\", \"noise\": \"%s\", \"data\": \"%s\", \"level_db\": %.1f, "
                "\"quality\": %.2f, \"start\": %.3f, \"fixed_bits\": %d, \"rate_error\": %.4f}\n",
                e.end, e.kind == RxEvent::Kind::kPacket ? "packet" : "noise", NoiseName(e.noise),
                tools::HexBytes(e.data).c_str(), e.level_db, e.quality, e.start, e.fixed_bits, e.rate_error);
  }
  return 0;
}
