#pragma once

// Speech as an interferer for the benches: made at run time by make_speech.sh (espeak-ng, so
// nothing is downloaded), and a different stretch of it for each room or packet.
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "bench_support.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"

namespace nava_modem::tools {

// 240 s of speech at `rate`, made in `dir` with `seed`; exits with a message when it cannot.
inline std::vector<float> Speech(const std::string& dir, double rate, unsigned seed) {
  const std::string file = dir + "/speech.wav";
  const RunResult r = Run({"bash", NAVA_SPEECH_SCRIPT, file, "240", std::to_string(seed)});
  if (r.status != 0) {
    std::cerr << "nava_bench: " << NAVA_SPEECH_SCRIPT << " could not make speech (is espeak-ng installed?)\n";
    std::exit(1);
  }
  const Audio speech = ReadAudioFile(file);
  return Resample(speech.samples, rate / speech.sample_rate);
}

// The speech from sample `shift` (modulo its length) on, wrapping round to its start.
inline std::vector<float> SpeechFrom(const std::vector<float>& speech, std::size_t shift) {
  shift %= speech.size();
  std::vector<float> talk(speech.begin() + static_cast<std::ptrdiff_t>(shift), speech.end());
  talk.insert(talk.end(), speech.begin(), speech.begin() + static_cast<std::ptrdiff_t>(shift));
  return talk;
}

}  // namespace nava_modem::tools
