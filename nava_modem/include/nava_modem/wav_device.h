#pragma once

#include <string>
#include <vector>

#include "nava_modem/audio_device.h"

namespace nava_modem {

// Files in place of a sound card, for offline work and tests: capture reads an audio file
// (every channel of it, as an array's microphones; then ends), playback is gathered and written
// as a WAV file by Save() (or on destruction).
class WavDevice : public AudioDevice {
 public:
  // `input`: the file to hear (its rate is the device's); `output`: where to write what was
  // played ("" to keep it in memory only). Throws std::runtime_error naming a bad input file.
  WavDevice(const std::string& input, const std::string& output);
  ~WavDevice() override;

  double sample_rate() const override { return rate_; }
  int capture_channels() const override { return channels_; }
  bool Read(float* out, std::size_t count) override;
  void Write(const float* in, std::size_t count) override;
  // A file takes what is written at once, and never fails.
  std::size_t PlaybackDelay() override { return 0; }
  std::size_t PlaybackRoom() override { return SIZE_MAX; }
  std::size_t CaptureLag() override { return 0; }
  void Reopen() override {}
  std::uint64_t overruns() const override { return 0; }
  std::uint64_t underruns() const override { return 0; }

  const std::vector<float>& played() const { return played_; }
  void Save();

 private:
  double rate_;
  int channels_ = 1;
  std::vector<float> input_, played_;  // input_: interleaved
  std::size_t read_ = 0;
  std::string output_;
  bool saved_ = false;
};

}  // namespace nava_modem
