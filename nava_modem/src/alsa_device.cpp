#include "nava_modem/alsa_device.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <alsa/asoundlib.h>

namespace nava_modem {
namespace {

snd_pcm_t* Open(const AlsaOptions& o, snd_pcm_stream_t stream) {
  const bool capture = stream == SND_PCM_STREAM_CAPTURE;
  const char* what = capture ? "capture" : "playback";
  const int channels = capture ? o.capture_channels : 1;
  snd_pcm_t* pcm = nullptr;
  int err = snd_pcm_open(&pcm, o.device.c_str(), stream, 0);
  if (err < 0) {
    throw std::runtime_error("ALSA device '" + o.device + "': cannot open for " + what + ": " + snd_strerror(err));
  }
  // No resampling by ALSA: a device that cannot run at the rate must say so.
  err = snd_pcm_set_params(pcm, SND_PCM_FORMAT_FLOAT_LE, SND_PCM_ACCESS_RW_INTERLEAVED, static_cast<unsigned>(channels),
                           static_cast<unsigned>(std::lround(o.sample_rate)), 0,
                           static_cast<unsigned>(std::lround(o.latency * 1e6)));
  if (err < 0) {
    snd_pcm_close(pcm);
    const std::string layout = channels == 1 ? "mono" : std::to_string(channels) + " channels of";
    throw std::runtime_error("ALSA device '" + o.device + "': refuses " + what + " of " + layout + " float samples at " +
                             std::to_string(std::lround(o.sample_rate)) + " Hz" +
                             (channels > 1 ? " (has it fewer microphones than that?)" : "") + ": " + snd_strerror(err));
  }
  return pcm;
}

}  // namespace

AlsaDevice::AlsaDevice(const AlsaOptions& options) : options_(options) {
  if (!(options_.capture_channels >= 1 && options_.capture_channels <= 64)) {
    throw std::invalid_argument("ALSA capture channels " + std::to_string(options_.capture_channels) + ": expected 1 to 64");
  }
  if (!(options_.latency > 0.0 && options_.latency <= 2.0)) {
    throw std::invalid_argument("ALSA latency " + std::to_string(options_.latency) + " s: expected above 0 and at most 2");
  }
  capture_ = Open(options_, SND_PCM_STREAM_CAPTURE);
  try {
    playback_ = Open(options_, SND_PCM_STREAM_PLAYBACK);
  } catch (...) {
    snd_pcm_close(capture_);
    throw;
  }
  snd_pcm_start(capture_);
}

AlsaDevice::~AlsaDevice() {
  if (playback_) {
    snd_pcm_drain(playback_);
    snd_pcm_close(playback_);
  }
  if (capture_) snd_pcm_close(capture_);
}

// Moves `count` frames of `width` samples with `io` (snd_pcm_readi or snd_pcm_writei on `pcm`),
// recovering from over- and underruns, which are counted in `xruns`.
template <typename Buffer, typename Io>
void AlsaDevice::Transfer(snd_pcm_t* pcm, Buffer* data, std::size_t count, std::size_t width, Io io, const char* what,
                          std::uint64_t& xruns) {
  while (count > 0) {
    const snd_pcm_sframes_t done = io(pcm, data, count);
    if (done > 0) {
      data += static_cast<std::size_t>(done) * width;
      count -= static_cast<std::size_t>(done);
      continue;
    }
    if (done == -EAGAIN) continue;
    ++xruns;  // an overrun, an underrun or a suspend: recover and go on
    if (snd_pcm_recover(pcm, static_cast<int>(done), 1) < 0) {
      throw std::runtime_error("ALSA device '" + options_.device + "': " + what + " failed: " +
                               snd_strerror(static_cast<int>(done)));
    }
    if (pcm == capture_) snd_pcm_start(pcm);
  }
}

bool AlsaDevice::Read(float* out, std::size_t count) {
  Transfer(capture_, out, count, static_cast<std::size_t>(options_.capture_channels),
           [](snd_pcm_t* p, float* d, std::size_t n) { return snd_pcm_readi(p, d, n); }, "capture", overruns_);
  return true;
}

void AlsaDevice::Write(const float* in, std::size_t count) {
  Transfer(playback_, in, count, 1, [](snd_pcm_t* p, const float* d, std::size_t n) { return snd_pcm_writei(p, d, n); },
           "playback", underruns_);
}

}  // namespace nava_modem
