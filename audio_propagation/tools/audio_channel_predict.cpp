// audio_channel_predict: what the acoustic channel model predicts for one link through a room
// whose impulse response was measured, so that anyone can hold the model against a response
// measured in their own building.
//
//   audio_channel_predict --profile nava|room --rir FILE.wav [--channel K]
//                         --noise white|pink|speech|NOISE.wav --snr-db X [--table FILE]
//
// It reads the response's RT60 and DRR as ../shared/realrooms/README.md defines them (600-5400
// Hz; T30; the energy within 2.5 ms of the direct peak over the energy after it), and looks the
// packet up in the profile's decode table at that SNR (as nava_room --snr means it: the received
// packet's power, direct and reverberant, over the noise's, both over the recording's whole
// band). A recorded noise is weighed by its power in the bands the profile's receiver listens
// to, against the white noise the table was measured with (nava_modem/recorded_noise.h). Prints
// one JSON line: the response's figures, "probability" of a packet and the noise classes (the
// fractions the receiver reports as a carrier with no byte, a byte, a bad CRC; the rest unheard).
// Bad input (an unreadable, silent or too short response, one with no direct peak, a noise that
// is no recording) exits 1 with one line naming the file.
#include <cstdio>
#include <iostream>
#include <string>

#include "acoustic_world.h"
#include "audio_propagation/acoustic_model.h"
#include "audio_propagation_args.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/recorded_noise.h"
#include "nava_modem/wav_file.h"
#include "tool_args/json_text.h"

namespace {

using multirobot_audio::tools::JsonNumber;
using multirobot_audio::tools::JsonString;
constexpr const char* kProgram = "audio_channel_predict";

int Run(const audio_propagation::tools::PredictArgs& a) {
  using audio_propagation::tools::Fail;
  const audio_propagation::DecodeTable table = audio_propagation::tools::LoadTable(kProgram, a.profile, a.table_file);
  // The response is read at the rate the tables were rendered at.
  constexpr double kRate = audio_propagation::kTableSampleRate;
  nava_modem::ResponseMeasures room;
  try {
    room = nava_modem::MeasureResponse(nava_modem::LoadImpulseResponse(a.rir_file, a.channel, kRate), kRate);
  } catch (const std::exception& e) {
    Fail(kProgram, std::string(e.what()).rfind(a.rir_file, 0) == 0 ? e.what() : a.rir_file + ": " + e.what());
  }
  if (const auto problem = nava_modem::ResponseProblem(room)) Fail(kProgram, a.rir_file + ": " + *problem);

  audio_propagation::Interference kind = audio_propagation::Interference::kWhite;
  double snr = a.snr_db;
  std::vector<double> packet_snrs;  // a recording's, one per packet place (RecordingWeight)
  std::string noise_figures;
  if (const auto named = audio_propagation::ParseInterference(a.noise);
      named && *named != audio_propagation::Interference::kWhine && *named != audio_propagation::Interference::kPacket) {
    kind = *named;
  } else {
    // A recording: read as white noise with the same power where the receiver listens (for room,
    // more for what its code gains from a noise that comes and goes: RecordingWeight).
    nava_modem::Audio audio;
    try {
      audio = nava_modem::ReadAudioFile(a.noise);
    } catch (const std::exception& e) {
      Fail(kProgram, std::string(e.what()) + " (--noise: expected white, pink, speech or a recording)");
    }
    try {
      const nava_modem::RecordingWeight weight(audio.samples, audio.sample_rate, a.profile, kRate);
      snr += weight.in_band_offset_db();
      packet_snrs = weight.TableSnrsDb(snr);
      double gain = 0.0;
      for (double p : packet_snrs) gain += (p - snr) / static_cast<double>(packet_snrs.size());
      noise_figures = ", \"noise_in_band_fraction\": " + JsonNumber(weight.in_band_fraction(), 4) +
                      ", \"white_equivalent_offset_db\": " + JsonNumber(weight.in_band_offset_db(), 2) +
                      ", \"cell_gain_db\": " + JsonNumber(gain, 2);
    } catch (const std::invalid_argument& e) {
      Fail(kProgram, a.noise + ": " + e.what());
    }
  }
  const audio_propagation::DecodeOutcome o =
      audio_propagation::PredictOutcome(table, kind, packet_snrs.empty() ? std::vector<double>{snr} : packet_snrs,
                                        room.drr_db, room.rt60_s);
  const double unheard = std::max(0.0, 1.0 - o.packet - o.zero_byte - o.one_byte - o.bad_crc);
  std::printf("{\"rir\": %s, \"channel\": %s, \"profile\": %s, \"rt60_s\": %s, \"drr_db\": %s, \"noise\": %s, "
              "\"snr_db\": %s, \"table_kind\": %s, \"table_snr_db\": %s%s, \"probability\": %s, "
              "\"zero_byte\": %s, \"one_byte\": %s, \"bad_crc\": %s, \"unheard\": %s}\n",
              JsonString(a.rir_file).c_str(), a.channel ? std::to_string(*a.channel).c_str() : "null",
              JsonString(nava_modem::ProfileName(a.profile)).c_str(), JsonNumber(room.rt60_s, 3).c_str(),
              JsonNumber(room.drr_db, 2).c_str(), JsonString(a.noise).c_str(), JsonNumber(a.snr_db, 2).c_str(),
              JsonString(audio_propagation::InterferenceName(kind)).c_str(), JsonNumber(snr, 2).c_str(),
              noise_figures.c_str(), JsonNumber(o.packet, 4).c_str(), JsonNumber(o.zero_byte, 4).c_str(),
              JsonNumber(o.one_byte, 4).c_str(), JsonNumber(o.bad_crc, 4).c_str(), JsonNumber(unheard, 4).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    return Run(audio_propagation::tools::ParsePredictArgs(multirobot_audio::tools::Words(argc, argv)));
  });
}
