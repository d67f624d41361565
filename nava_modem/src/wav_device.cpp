#include "nava_modem/wav_device.h"

#include <algorithm>
#include <iostream>

#include "nava_modem/wav_file.h"

namespace nava_modem {

WavDevice::WavDevice(const std::string& input, const std::string& output) : output_(output) {
  // Every channel, interleaved as a sound card captures them (one per microphone).
  const MultiAudio audio = ReadAudioChannels(input);
  rate_ = audio.sample_rate;
  channels_ = static_cast<int>(audio.channels.size());
  const std::size_t frames = audio.channels[0].size();
  input_.resize(frames * audio.channels.size());
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t c = 0; c < audio.channels.size(); ++c) input_[f * audio.channels.size() + c] = audio.channels[c][f];
  }
}

WavDevice::~WavDevice() {
  try {
    Save();
  } catch (const std::exception& e) {
    std::cerr << "nava_modem: " << e.what() << "\n";  // a destructor must not throw
  }
}

bool WavDevice::Read(float* out, std::size_t count) {
  const std::size_t samples = count * static_cast<std::size_t>(channels_);
  if (read_ + samples > input_.size()) return false;
  std::copy(input_.begin() + read_, input_.begin() + read_ + samples, out);
  read_ += samples;
  return true;
}

void WavDevice::Write(const float* in, std::size_t count) { played_.insert(played_.end(), in, in + count); }

void WavDevice::Save() {
  if (saved_ || output_.empty()) return;
  saved_ = true;
  WriteWavFile(output_, played_, rate_);
}

}  // namespace nava_modem
