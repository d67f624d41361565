#include "nava_modem/wav_file.h"

#include <cmath>
#include <stdexcept>
#include <string>

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
  const MultiAudio multi = ReadAudioChannels(path);
  Audio audio;
  audio.sample_rate = multi.sample_rate;
  audio.samples.assign(multi.channels[0].size(), 0.0f);
  const float share = 1.0f / static_cast<float>(multi.channels.size());
  for (const std::vector<float>& channel : multi.channels) {
    for (std::size_t k = 0; k < channel.size(); ++k) audio.samples[k] += share * channel[k];
  }
  return audio;
}

namespace {

void WriteMono(const std::string& path, const std::vector<float>& samples, double sample_rate, int subformat) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | subformat;
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file.handle) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  if (subformat == SF_FORMAT_PCM_16) sf_command(file.handle, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  if (sf_writef_float(file.handle, samples.data(), static_cast<sf_count_t>(samples.size())) !=
      static_cast<sf_count_t>(samples.size())) {
    throw std::runtime_error(path + ": write failed (" + sf_strerror(file.handle) + ")");
  }
}

}  // namespace

void WriteWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  WriteMono(path, samples, sample_rate, SF_FORMAT_PCM_16);
}

void WriteFloatWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  WriteMono(path, samples, sample_rate, SF_FORMAT_FLOAT);
}

void WriteWavChannels(const std::string& path, const std::vector<std::vector<float>>& channels, double sample_rate) {
  if (channels.empty()) throw std::runtime_error(path + ": no channels to write");
  const std::size_t frames = channels[0].size();
  for (std::size_t c = 1; c < channels.size(); ++c) {
    if (channels[c].size() != frames) {
      throw std::runtime_error(path + ": channel " + std::to_string(c + 1) + " has " + std::to_string(channels[c].size()) +
                               " samples, channel 1 has " + std::to_string(frames) + ": expected the same length");
    }
  }
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate));
  info.channels = static_cast<int>(channels.size());
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file.handle) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  sf_command(file.handle, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  std::vector<float> interleaved(frames * channels.size());
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t c = 0; c < channels.size(); ++c) interleaved[f * channels.size() + c] = channels[c][f];
  }
  if (sf_writef_float(file.handle, interleaved.data(), static_cast<sf_count_t>(frames)) != static_cast<sf_count_t>(frames)) {
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
