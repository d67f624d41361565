#pragma once

#include <string>

#include "nava_modem/audio_device.h"

typedef struct _snd_pcm snd_pcm_t;

namespace nava_modem {

struct AlsaOptions {
  std::string device = "default";  // an ALSA PCM name: default, pulse, plughw:1,0, ...
  double sample_rate = 48000.0;
  double latency = 0.05;  // s of buffering asked of each stream; the own echo comes this late
  int capture_channels = 1;  // microphones captured (interleaved); playback stays mono
};

// Throws std::invalid_argument naming the field, its value and what was expected: a device
// name, a sample rate the project runs at (ValidateSampleRate), latency above 0 and at most
// 2 s, 1 to 64 capture channels.
void ValidateAlsaOptions(const AlsaOptions& options);

// One capture and one playback stream on an ALSA device. Under- and overruns are recovered
// from and counted. The constructor throws std::runtime_error (DeviceFault) naming the device
// and what failed when a stream cannot be opened or refuses the rate, std::invalid_argument
// for impossible options; once open, a failure that cannot be recovered in place throws
// DeviceFault from Read or Write, and Reopen() tries again.
class AlsaDevice : public AudioDevice {
 public:
  explicit AlsaDevice(const AlsaOptions& options);
  ~AlsaDevice() override;
  AlsaDevice(const AlsaDevice&) = delete;
  AlsaDevice& operator=(const AlsaDevice&) = delete;

  double sample_rate() const override { return options_.sample_rate; }
  int capture_channels() const override { return options_.capture_channels; }
  bool Read(float* out, std::size_t count) override;
  void Write(const float* in, std::size_t count) override;
  std::size_t PlaybackDelay() override;
  std::size_t PlaybackRoom() override;
  std::size_t CaptureLag() override;
  void Reopen() override;
  std::uint64_t overruns() const override { return overruns_; }
  std::uint64_t underruns() const override { return underruns_; }

 private:
  void Open();
  void Close();
  template <typename Buffer, typename Io>
  void Transfer(snd_pcm_t* pcm, Buffer* data, std::size_t count, std::size_t width, Io io, const char* what,
                std::uint64_t& xruns);

  AlsaOptions options_;
  snd_pcm_t* capture_ = nullptr;
  snd_pcm_t* playback_ = nullptr;
  std::size_t written_since_start_ = 0;  // playback frames since the stream was last prepared
  std::uint64_t overruns_ = 0, underruns_ = 0;
};

}  // namespace nava_modem
