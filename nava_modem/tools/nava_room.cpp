// nava_room: what a robot's microphone in a real room hears of a clean modem WAV (clock offset,
// spectral tilt, reverberation, noise, an interferer, a motor's whine); see room_channel.h for
// the model and the level definitions. With --mics, what each microphone of an array hears of a
// source at --bearing and --distance, one channel per microphone (room_array.h). With --rir,
// through a measured impulse response instead of the statistical room (channel K of the file,
// resampled to the input's rate, its own delay kept); with --response measured-like, through a
// room like measured ones (measured_like_response.h) of the RT60 and DRR given.
//
//   nava_room --in CLEAN.wav --out ROOM.wav [--rt60 S --drr DB [--response statistical|measured-like]
//             | --rir FILE.wav [--channel K]]
//             [--tilt DB] [--tilt-band LO,HI]
//             [--clock PERCENT] [--noise white|pink] [--snr DB] [--interferer FILE] [--sir DB]
//             [--whine HZ] [--whine-sir DB] [--whine-am HZ] [--seed N]
//             [--mics X1,Y1,X2,Y2,... [--bearing DEG] [--distance M]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

#include "nava_modem/direction_estimator.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/room_array.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"
#include "nava_room_args.h"

namespace {

std::string Fixed(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v == 0.0 ? 0.0 : v);
  return std::string(text) == "-0.00" ? "0.00" : text;
}

std::string Db(double gain) { return Fixed(20.0 * std::log10(gain)) + " dB"; }

// "lo..hi" of f over the channels, or one value when they agree to the precision shown.
template <typename F>
std::string Range(const nava_modem::ArrayRenderInfo& info, F f) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto& channel : info.channels) lo = std::min(lo, f(channel)), hi = std::max(hi, f(channel));
  return Fixed(lo) == Fixed(hi) ? Fixed(lo) : Fixed(lo) + ".." + Fixed(hi);
}

double Degrees(double radians) { return radians * 180.0 / 3.141592653589793; }

// The array render's one summary line: what RenderRoomArray did, the per-channel values as ranges.
std::string ArraySummary(const nava_modem::Audio& clean, std::size_t frames, const nava_modem::RoomOptions& o,
                         const std::string& noise, bool interferer, const nava_modem::ArraySource& source,
                         const nava_modem::ArrayRenderInfo& info) {
  using nava_modem::ArrayChannelInfo;
  std::ostringstream s;
  s.precision(4);
  s << "nava_room: " << clean.samples.size() / clean.sample_rate << " s in, " << frames / clean.sample_rate << " s out at "
    << std::lround(clean.sample_rate) << " Hz, " << source.mics.size() << " channels; source at bearing "
    << Degrees(source.bearing) << " deg, " << source.distance << " m: direct sound at "
    << Range(info, [](const ArrayChannelInfo& c) { return 1000.0 * c.direct_delay_s; }) << " ms, level "
    << Range(info, [](const ArrayChannelInfo& c) { return 20.0 * std::log10(c.direct_gain); }) << " dB (1/r);";
  if (o.rt60 > 0.0) {
    s << " room rt60 " << o.rt60 << " s, DRR " << Fixed(o.drr_db) << " dB at the origin, "
      << Range(info, [](const ArrayChannelInfo& c) { return c.drr_db; }) << " dB per channel;";
  }
  if (o.tilt_db != 0.0) s << " tilt " << o.tilt_db << " dB over " << o.tilt_low_hz << "-" << o.tilt_high_hz << " Hz;";
  if (o.clock_offset != 0.0) s << " clock " << 100.0 * o.clock_offset << " %;";
  s << " signal RMS " << Range(info, [](const ArrayChannelInfo& c) { return 20.0 * std::log10(std::sqrt(c.signal_power)); })
    << " dB (before the output gain) over " << 100.0 * info.sounding_fraction << " % sounding;";
  if (o.noise != nava_modem::RoomOptions::Noise::kNone) {
    s << " " << noise << " noise, independent per channel (SNR " << o.snr_db << " dB);";
  }
  if (interferer) s << " interferer from " << Fixed(Degrees(info.interferer_bearing)) << " deg (SIR " << o.sir_db << " dB);";
  if (o.whine_hz > 0.0) s << " whine from " << Fixed(Degrees(info.whine_bearing)) << " deg (SIR " << o.whine_sir_db << " dB);";
  s << " output gain " << Db(info.output_gain) << " (loudest peak 0.9)";
  return s.str();
}

// Renders the room (or the array) and writes the output; an input file that does not fit the
// options is refused in the parser's words.
int Run(const nava_modem::tools::NavaRoomOptions& r) {
  using namespace nava_modem;
  RoomOptions o = r.room;
  const ArraySource& source = r.source;
  const std::string& noise = r.noise;
  const std::string& interferer_path = r.interferer_path;
  const std::string& out = r.out;
  // Reads a file named by `flag`, naming both in the error.
  auto read = [&r](const std::string& flag, const std::string& path) {
    try {
      return ReadAudioFile(path);
    } catch (const std::exception& e) {
      r.usage.Fail(flag + " " + e.what());
    }
  };
  try {
    const Audio clean = read("--in", r.in);
    if (!r.rir_path.empty()) {
      try {
        o.response = LoadImpulseResponse(r.rir_path, r.rir_channel, clean.sample_rate);
      } catch (const ResponseFileError& e) {
        r.usage.Fail(std::string("--rir ") + e.what());
      }
    }
    try {
      ValidateRoomOptions(o, clean.sample_rate);
    } catch (const RoomOptionError& e) {
      r.usage.Fail(tools::NavaRoomFlag(e.field()) + ": " + e.what());
    }
    std::vector<float> interferer;
    if (!interferer_path.empty()) {
      const Audio audio = read("--interferer", interferer_path);
      interferer = audio.samples;
      if (audio.sample_rate != clean.sample_rate) {
        std::cerr << "nava_room: resampling the interferer " << interferer_path << " from " << std::lround(audio.sample_rate)
                  << " Hz to " << std::lround(clean.sample_rate) << " Hz\n";
        interferer = Resample(interferer, clean.sample_rate / audio.sample_rate);
      }
      if (interferer.empty()) r.usage.Fail("--interferer " + interferer_path + ": no samples");
    }
    if (!source.mics.empty()) {
      ArrayRenderInfo info;
      const auto channels = RenderRoomArray(clean.samples, clean.sample_rate, o, source, interferer, &info);
      WriteWavChannels(out, channels, clean.sample_rate);
      std::cerr << ArraySummary(clean, channels[0].size(), o, noise, !interferer.empty(), source, info) << "\n";
      return 0;
    }
    RoomRenderInfo info;
    const std::vector<float> mic = RenderRoom(clean.samples, clean.sample_rate, o, interferer, &info);
    WriteWavFile(out, mic, clean.sample_rate);

    std::ostringstream s;
    s.precision(4);
    s << "nava_room: " << clean.samples.size() / clean.sample_rate << " s in, " << mic.size() / clean.sample_rate
      << " s out at " << std::lround(clean.sample_rate) << " Hz;";
    if (o.rt60 > 0.0) s << " room rt60 " << o.rt60 << " s, measured DRR " << Fixed(info.measured_drr_db) << " dB;";
    if (!o.response.empty()) {
      s << " measured response " << r.rir_path;
      if (r.rir_channel) s << " channel " << *r.rir_channel;
      s << " (" << o.response.size() << " samples), DRR " << Fixed(info.measured_drr_db) << " dB in 600-5400 Hz;";
    }
    if (o.tilt_db != 0.0) s << " tilt " << o.tilt_db << " dB over " << o.tilt_low_hz << "-" << o.tilt_high_hz << " Hz;";
    if (o.clock_offset != 0.0) s << " clock " << 100.0 * o.clock_offset << " %;";
    s << " signal RMS " << std::sqrt(info.signal_power) << " over " << 100.0 * info.sounding_fraction << " % sounding;";
    if (o.noise != RoomOptions::Noise::kNone) s << " " << noise << " noise RMS " << info.noise_rms << " (SNR " << o.snr_db << " dB);";
    if (!interferer.empty()) s << " interferer gain " << Db(info.interferer_gain) << " (SIR " << o.sir_db << " dB);";
    if (o.whine_hz > 0.0) s << " whine RMS " << info.whine_rms << " (SIR " << o.whine_sir_db << " dB);";
    s << " output gain " << Db(info.output_gain) << " (peak 0.9)";
    std::cerr << s.str() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "nava_room: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(nava_modem::tools::ParseNavaRoomArgs(multirobot_audio::tools::Words(argc, argv))); });
}
