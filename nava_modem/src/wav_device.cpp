#include "nava_modem/wav_device.h"

#include <algorithm>
#include <iostream>

#include "nava_modem/wav_file.h"

namespace nava_modem {

WavDevice::WavDevice(const std::string& input, const std::string& output) : output_(output) {
  Audio audio = ReadAudioFile(input);
  rate_ = audio.sample_rate;
  input_ = std::move(audio.samples);
}

WavDevice::~WavDevice() {
  try {
    Save();
  } catch (const std::exception& e) {
    std::cerr << "nava_modem: " << e.what() << "\n";  // a destructor must not throw
  }
}

bool WavDevice::Read(float* out, std::size_t count) {
  if (read_ + count > input_.size()) return false;
  std::copy(input_.begin() + read_, input_.begin() + read_ + count, out);
  read_ += count;
  return true;
}

void WavDevice::Write(const float* in, std::size_t count) { played_.insert(played_.end(), in, in + count); }

void WavDevice::Save() {
  if (saved_ || output_.empty()) return;
  saved_ = true;
  WriteWavFile(output_, played_, rate_);
}

}  // namespace nava_modem
