#include "nava_modem/wav_file.h"

#include <cmath>
#include <stdexcept>

#include <sndfile.h>

namespace nava_modem {
namespace {

// Closes a libsndfile handle however the function leaves.
struct SndFile {
  SNDFILE* handle = nullptr;
  ~SndFile() {
    if (handle) sf_close(handle);
  }
};

}  // namespace

Audio ReadAudioFile(const std::string& path) {
  SF_INFO info{};
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_READ, &info);
  if (!file.handle) {
    throw std::runtime_error(path + ": not a readable audio file (" + sf_strerror(nullptr) + ")");
  }
  if (info.channels < 1 || info.samplerate <= 0) {
    throw std::runtime_error(path + ": no audio channels or no sample rate");
  }
  std::vector<float> interleaved(static_cast<std::size_t>(info.frames) * info.channels);
  const sf_count_t got = sf_readf_float(file.handle, interleaved.data(), info.frames);
  Audio audio;
  audio.sample_rate = info.samplerate;
  audio.samples.resize(static_cast<std::size_t>(got));
  for (sf_count_t f = 0; f < got; ++f) {
    float sum = 0.0f;
    for (int c = 0; c < info.channels; ++c) sum += interleaved[f * info.channels + c];
    audio.samples[f] = sum / info.channels;
  }
  return audio;
}

void WriteWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file.handle) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  sf_command(file.handle, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  if (sf_writef_float(file.handle, samples.data(), static_cast<sf_count_t>(samples.size())) !=
      static_cast<sf_count_t>(samples.size())) {
    throw std::runtime_error(path + ": write failed (" + sf_strerror(file.handle) + ")");
  }
}

MultiAudio ReadAudioChannels(const std::string& path) {
  SF_INFO info{};
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_READ, &info);
  if (!file.handle) {
    throw std::runtime_error(path + ": not a readable audio file (" + sf_strerror(nullptr) + ")");
  }
  if (info.channels < 1 || info.samplerate <= 0) {
    throw std::runtime_error(path + ": no audio channels or no sample rate");
  }
  const std::size_t channels = static_cast<std::size_t>(info.channels);
  std::vector<float> interleaved(static_cast<std::size_t>(info.frames) * channels);
  const std::size_t got = static_cast<std::size_t>(sf_readf_float(file.handle, interleaved.data(), info.frames));
  MultiAudio audio;
  audio.sample_rate = info.samplerate;
  audio.channels.assign(channels, std::vector<float>(got));
  for (std::size_t f = 0; f < got; ++f) {
    for (std::size_t c = 0; c < channels; ++c) audio.channels[c][f] = interleaved[f * channels + c];
  }
  return audio;
}

}  // namespace nava_modem
