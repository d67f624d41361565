// nava_decode: decodes the Nava packets in an audio file; one JSON line per event, e.g.
//   {"t": 1.234, "kind": "packet", "noise": "none", "data": "01020304", "level_db": -20.5, "quality": 0.83, ...}
// t is the end of the reception in seconds from the start of the file.
//
//   nava_decode [--threshold-db -40] [--max-fixed-bits 2] [--mics x1,y1,x2,y2,...] [modem options] FILE.wav
// --rate, if given, must be the file's rate. --mics: the file is a microphone array's recording,
// channel i from the microphone at (xi, yi) m in the robot's frame; each line then also gives
// "direction" (rad, CCW from the robot's +x, null when the array cannot tell) and
// "direction_confidence" (0..1), estimated from that event's samples on all channels.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "modem_args.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/room_phy.h"
#include "nava_modem/wav_file.h"

namespace {

using namespace nava_modem;

// The channel the receiver decodes. Not the sum: the microphones hear the sound at different
// delays, and with spacings of a few centimetres their sum comb-filters the modem's upper tones.
// The loudest channel is the microphone nearest the sender or least shadowed, with the best SNR.
std::size_t LoudestChannel(const MultiAudio& audio) {
  std::size_t best = 0;
  double loudest = -1.0;
  for (std::size_t c = 0; c < audio.channels.size(); ++c) {
    double energy = 0.0;
    for (float v : audio.channels[c]) energy += static_cast<double>(v) * v;
    if (energy > loudest) {
      loudest = energy;
      best = c;
    }
  }
  return best;
}

// The profile's band and how much of each event to use. nava: the whole packet, since it opens
// with a steady MARK tone (one frequency: its correlation repeats every 0.43 ms) and only the data
// bits' two tones pin the delay down. room: its first chirp, 0.12 s sweeping 600-5400 Hz, whose
// direct sound the reverberation has not yet caught up with.
DirectionOptions DirectionFor(Profile profile, const ModemOptions& modem, std::vector<Microphone2D> mics) {
  DirectionOptions o;
  o.mics = std::move(mics);
  o.sample_rate = modem.sample_rate;
  if (profile == Profile::kRoom) {
    o.low_hz = room_phy::kChirpLowHz;
    o.high_hz = room_phy::kChirpHighHz;
    o.max_seconds = room_phy::kChirpSeconds;
  } else {
    // The FSK's energy lies within about two bit rates of its tones.
    o.low_hz = std::max(0.0, std::min(modem.mark_hz, modem.space_hz) - 2.0 * modem.baud);
    o.high_hz = std::max(modem.mark_hz, modem.space_hz) + 2.0 * modem.baud;
    o.max_seconds = ProfileAirtime(profile, modem);
  }
  o.high_hz = std::min(o.high_hz, modem.sample_rate / 2.0);
  return o;
}

std::string DirectionJson(const Direction& d) {
  char text[80];
  if (std::isnan(d.bearing)) {
    std::snprintf(text, sizeof text, ", \"direction\": null, \"direction_confidence\": %.2f", d.confidence);
  } else {
    std::snprintf(text, sizeof text, ", \"direction\": %.4f, \"direction_confidence\": %.2f", d.bearing, d.confidence);
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nava_modem;
  const std::string usage = std::string("nava_decode [--threshold-db -40] [--max-fixed-bits 2] [--mics x1,y1,x2,y2,...] ") +
                            tools::kModemUsage + " FILE.wav";
  const multirobot_audio::tools::ToolArgs args("nava_decode", usage, argc, argv);
  const double threshold = args.Double("--threshold-db", -40.0, -200.0, 20.0);
  const int fixed = static_cast<int>(args.Int("--max-fixed-bits", 2, 0, 2));
  const std::string given_rate = args.String("--rate", "");
  std::optional<std::vector<Microphone2D>> mics;
  if (const std::string text = args.String("--mics", ""); !text.empty()) {
    try {
      mics = ParseMicPositions(text);
    } catch (const std::exception& e) {
      args.Fail(std::string("--mics: ") + e.what());
    }
  }
  const std::vector<std::string>& files = args.positional();
  if (files.size() != 1) args.Fail("expected one audio file");
  Audio audio;
  MultiAudio array;
  try {
    if (mics) {
      array = ReadAudioChannels(files[0]);
      if (array.channels.size() != mics->size()) {
        std::cerr << "nava_decode: " << files[0] << " has " << array.channels.size() << " channels, but --mics gives "
                  << mics->size() << " microphones\n";
        return 1;
      }
      audio.sample_rate = array.sample_rate;
      audio.samples = array.channels[LoudestChannel(array)];
    } else {
      audio = ReadAudioFile(files[0]);
    }
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
  std::vector<std::string> directions;
  try {
    const auto receiver = MakeProfile(modem.profile, options)->MakeReceiver(rx);
    receiver->Process(audio.samples.data(), audio.samples.size(), events);
    receiver->Flush(events);
    if (mics) {
      const DirectionEstimator estimator(DirectionFor(modem.profile, options, *mics));
      const std::size_t length = audio.samples.size();
      for (const RxEvent& e : events) {
        const auto sample = [&](double t) { return std::min(length, static_cast<std::size_t>(std::max(0.0, std::round(t * audio.sample_rate)))); };
        const std::size_t from = sample(e.start), to = std::max(from, sample(e.end));
        std::vector<const float*> channels;
        for (const auto& c : array.channels) channels.push_back(c.data() + from);
        directions.push_back(DirectionJson(estimator.Estimate(channels, to - from)));
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "nava_decode: " << files[0] << ": " << e.what() << "\n";
    return 1;
  }
  for (std::size_t k = 0; k < events.size(); ++k) {
    const RxEvent& e = events[k];
    std::printf("{\"t\": %.3f, \"kind\": \"%s\", \"noise\": \"%s\", \"data\": \"%s\", \"level_db\": %.1f, "
                "\"quality\": %.2f, \"start\": %.3f, \"fixed_bits\": %d, \"rate_error\": %.4f%s}\n",
                e.end, e.kind == RxEvent::Kind::kPacket ? "packet" : "noise", NoiseName(e.noise),
                tools::HexBytes(e.data).c_str(), e.level_db, e.quality, e.start, e.fixed_bits, e.rate_error,
                mics ? directions[k].c_str() : "");
  }
  return 0;
}
