// nava_decode: decodes the Nava packets in an audio file; one JSON line per event, e.g.
//   {"t": 1.234, "kind": "packet", "noise": "none", "data": "01020304", "rate": 0, "level_db": -20.5, "quality": 0.83, ...}
// t is the end of the reception in seconds from the start of the file.
//
//   nava_decode [--threshold-db -40] [--max-fixed-bits 2] [--mics x1,y1,x2,y2,...] [--diagnostics FILE.json]
//               [modem options] FILE.wav
// --rate, if given, must be the file's rate. --mics: the file is a microphone array's recording,
// channel i from the microphone at (xi, yi) m in the robot's frame; each line then also gives
// "direction" (rad, CCW from the robot's +x, null when the array cannot tell) and
// "direction_confidence" (0..1), estimated from that event's samples on all channels.
// "arrival": when the packet's first sample, as sent, reached the microphone by the shortest way
// (s from the file's start, 6 decimals: the leading edge of its direct sound, first_arrival.h);
// null for noise and where the profile does not time packets.
// --diagnostics FILE.json (nava profile, one channel): FILE gets a JSON array with an object for
// each break the receiver examined: where the detector found it and where the packet's known bits
// settled it, the tone model, each clock tried with its reading and verdict, the equaliser's tries,
// the outcome (packet_on_clock, packet_by_equalizer, no_clock, not_read, superseded) and the event
// reported (as on stdout). What is decoded is the same with it or without.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include "nava_decode_args.h"
#include "nava_decode_json.h"
#include "nava_modem/array_decode.h"
#include "nava_modem/fsk_receiver.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/wav_file.h"

namespace {

using namespace nava_modem;

// --diagnostics: the receiver's traces as a JSON array, a break to a line.
bool WriteTraces(const std::vector<BreakTrace>& traces, std::ostream& out) {
  out << "[\n";
  for (std::size_t k = 0; k < traces.size(); ++k) out << tools::BreakTraceJson(traces[k]) << (k + 1 < traces.size() ? ",\n" : "\n");
  out << "]\n";
  out.flush();
  return static_cast<bool>(out);
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
    std::vector<BreakTrace> traces;
    std::ofstream diagnostics;
    if (!o.diagnostics.empty()) {
      // Opened before the decode, which can take a while, so that a path that cannot be written
      // fails at once.
      diagnostics.open(o.diagnostics);
      if (!diagnostics) {
        std::cerr << "nava_decode: --diagnostics " << o.diagnostics << ": cannot write it\n";
        return 1;
      }
    }
    try {
      const auto profile = MakeProfile(o.modem.profile, options);
      if (o.mics) {
        events = DecodeArray(*profile, rx, array.channels, *o.mics);
      } else {
        const auto receiver = profile->MakeReceiver(rx);
        if (!o.diagnostics.empty()) {
          // The parser allows --diagnostics with the nava profile only, whose receiver this is.
          auto* const fsk = dynamic_cast<FskReceiver*>(receiver.get());
          if (fsk == nullptr) throw std::logic_error("--diagnostics: the receiver is not the nava profile's");
          fsk->SetDiagnostics(&traces);
        }
        receiver->Process(audio.samples.data(), audio.samples.size(), events);
        receiver->Flush(events);
      }
    } catch (const std::exception& e) {
      std::cerr << "nava_decode: " << o.file << ": " << e.what() << "\n";
      return 1;
    }
    for (const RxEvent& e : events) std::printf("%s\n", tools::EventJson(e, o.mics.has_value()).c_str());
    if (!o.diagnostics.empty() && !WriteTraces(traces, diagnostics)) {
      std::cerr << "nava_decode: --diagnostics " << o.diagnostics << ": could not write all of it\n";
      return 1;
    }
    return 0;
  });
}
