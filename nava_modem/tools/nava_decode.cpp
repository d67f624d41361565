// nava_decode: decodes the Nava packets in an audio file; one JSON line per event, e.g.
//   {"t": 1.234, "kind": "packet", "noise": "none", "data": "01020304", "level_db": -20.5, "quality": 0.83, ...}
// t is the end of the reception in seconds from the start of the file.
//
//   nava_decode [--threshold-db -40] [--max-fixed-bits 2] [--mics x1,y1,x2,y2,...] [modem options] FILE.wav
// --rate, if given, must be the file's rate. --mics: the file is a microphone array's recording,
// channel i from the microphone at (xi, yi) m in the robot's frame; each line then also gives
// "direction" (rad, CCW from the robot's +x, null when the array cannot tell) and
// "direction_confidence" (0..1), estimated from that event's samples on all channels.
// "arrival": when the packet's first sample, as sent, reached the microphone by the shortest way
// (s from the file's start, 6 decimals: the leading edge of its direct sound, first_arrival.h);
// null for noise and where the profile does not time packets.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "nava_decode_args.h"
#include "nava_modem/array_decode.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/wav_file.h"

namespace {

using namespace nava_modem;

// JSON has no NaN: a direction the array cannot tell is null.
std::string DirectionJson(const RxEvent& e) {
  char text[80];
  if (std::isnan(e.direction)) {
    std::snprintf(text, sizeof text, ", \"direction\": null, \"direction_confidence\": %.2f", e.direction_confidence);
  } else {
    std::snprintf(text, sizeof text, ", \"direction\": %.4f, \"direction_confidence\": %.2f", e.direction, e.direction_confidence);
  }
  return text;
}

// The packet's first arrival, 6 decimals (a microsecond); null where it was not timed.
std::string ArrivalJson(const RxEvent& e) {
  if (std::isnan(e.arrival)) return ", \"arrival\": null";
  char text[48];
  std::snprintf(text, sizeof text, ", \"arrival\": %.6f", e.arrival);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nava_modem;
  return multirobot_audio::tools::RunTool([&] {
    tools::NavaDecodeOptions o = tools::ParseNavaDecodeArgs(multirobot_audio::tools::Words(argc, argv));
    Audio audio;
    MultiAudio array;
    try {
      if (o.mics) {
        array = ReadAudioChannels(o.file);
        if (array.channels.size() != o.mics->size()) {
          std::cerr << "nava_decode: " << o.file << " has " << array.channels.size() << " channels, but --mics gives "
                    << o.mics->size() << " microphones\n";
          return 1;
        }
        audio.sample_rate = array.sample_rate;
      } else {
        audio = ReadAudioFile(o.file);
      }
    } catch (const std::exception& e) {
      std::cerr << "nava_decode: " << e.what() << "\n";
      return 1;
    }
    ModemOptions& options = o.modem.options;
    if (!o.given_rate.empty() && std::abs(options.sample_rate - audio.sample_rate) > 0.5) {
      o.usage.Fail("--rate " + o.given_rate + " Hz, but " + o.file + " is sampled at " +
                   std::to_string(static_cast<long>(audio.sample_rate)) + " Hz");
    }
    options.sample_rate = audio.sample_rate;
    ReceiverOptions rx;
    rx.carrier_threshold_db = o.threshold_db;
    rx.max_fixed_bits = o.max_fixed_bits;
    std::vector<RxEvent> events;
    try {
      const auto profile = MakeProfile(o.modem.profile, options);
      if (o.mics) {
        events = DecodeArray(*profile, rx, array.channels, *o.mics);
      } else {
        const auto receiver = profile->MakeReceiver(rx);
        receiver->Process(audio.samples.data(), audio.samples.size(), events);
        receiver->Flush(events);
      }
    } catch (const std::exception& e) {
      std::cerr << "nava_decode: " << o.file << ": " << e.what() << "\n";
      return 1;
    }
    for (std::size_t k = 0; k < events.size(); ++k) {
      const RxEvent& e = events[k];
      std::printf("{\"t\": %.3f, \"kind\": \"%s\", \"noise\": \"%s\", \"data\": \"%s\", \"level_db\": %.1f, "
                  "\"quality\": %.2f, \"start\": %.3f, \"fixed_bits\": %d, \"rate_error\": %.4f%s%s}\n",
                  e.end, e.kind == RxEvent::Kind::kPacket ? "packet" : "noise", NoiseName(e.noise),
                  tools::HexBytes(e.data).c_str(), e.level_db, e.quality, e.start, e.fixed_bits, e.rate_error,
                  ArrivalJson(e).c_str(), o.mics ? DirectionJson(e).c_str() : "");
    }
    return 0;
  });
}
