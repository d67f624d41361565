#include "nava_modem/alsa_device.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <alsa/asoundlib.h>

#include "nava_modem/modem_options.h"

namespace nava_modem {
namespace {

snd_pcm_t* OpenStream(const AlsaOptions& o, snd_pcm_stream_t stream) {
  const bool capture = stream == SND_PCM_STREAM_CAPTURE;
  const char* what = capture ? "capture" : "playback";
  const int channels = capture ? o.capture_channels : 1;
  snd_pcm_t* pcm = nullptr;
  int err = snd_pcm_open(&pcm, o.device.c_str(), stream, 0);
  if (err < 0) {
    throw DeviceFault("ALSA device '" + o.device + "': cannot open for " + what + ": " + snd_strerror(err));
  }
  // No resampling by ALSA: a device that cannot run at the rate must say so.
  err = snd_pcm_set_params(pcm, SND_PCM_FORMAT_FLOAT_LE, SND_PCM_ACCESS_RW_INTERLEAVED, static_cast<unsigned>(channels),
                           static_cast<unsigned>(std::lround(o.sample_rate)), 0,
                           static_cast<unsigned>(std::lround(o.latency * 1e6)));
  if (err < 0) {
    snd_pcm_close(pcm);
    const std::string layout = channels == 1 ? "mono" : std::to_string(channels) + " channels of";
    throw DeviceFault("ALSA device '" + o.device + "': refuses " + what + " of " + layout + " float samples at " +
                      std::to_string(std::lround(o.sample_rate)) + " Hz" +
                      (channels > 1 ? " (has it fewer microphones than that?)" : "") + ": " + snd_strerror(err));
  }
  return pcm;
}

}  // namespace

void ValidateAlsaOptions(const AlsaOptions& o) {
  if (o.device.empty()) throw std::invalid_argument("ALSA device: expected a PCM name (default, pulse, ...), got none");
  ValidateSampleRate("ALSA sample rate", o.sample_rate);
  if (!(o.capture_channels >= 1 && o.capture_channels <= 64)) {
    throw std::invalid_argument("ALSA capture channels " + std::to_string(o.capture_channels) + ": expected 1 to 64");
  }
  if (!(o.latency > 0.0 && o.latency <= 2.0)) {
    throw std::invalid_argument("ALSA latency " + std::to_string(o.latency) + " s: expected above 0 and at most 2");
  }
}

AlsaDevice::AlsaDevice(const AlsaOptions& options) : options_(options) {
  ValidateAlsaOptions(options_);
  Open();
}

AlsaDevice::~AlsaDevice() {
  // What is queued is played out unless the device has failed (then draining fails at once).
  if (playback_) snd_pcm_drain(playback_);
  Close();
}

void AlsaDevice::Open() {
  capture_ = OpenStream(options_, SND_PCM_STREAM_CAPTURE);
  try {
    playback_ = OpenStream(options_, SND_PCM_STREAM_PLAYBACK);
  } catch (...) {
    Close();
    throw;
  }
  written_since_start_ = 0;
  const int err = snd_pcm_start(capture_);
  if (err < 0) {
    Close();
    throw DeviceFault("ALSA device '" + options_.device + "': cannot start capture: " + snd_strerror(err));
  }
}

void AlsaDevice::Close() {
  if (playback_) snd_pcm_close(playback_);
  if (capture_) snd_pcm_close(capture_);
  playback_ = capture_ = nullptr;
}

void AlsaDevice::Reopen() {
  Close();
  Open();
}

// Moves `count` frames of `width` samples with `io` (snd_pcm_readi or snd_pcm_writei on `pcm`),
// recovering from over- and underruns, which are counted in `xruns`. Anything else, or an xrun
// that cannot be recovered from (a sound server that has gone away reports one), is a
// DeviceFault.
template <typename Buffer, typename Io>
void AlsaDevice::Transfer(snd_pcm_t* pcm, Buffer* data, std::size_t count, std::size_t width, Io io, const char* what,
                          std::uint64_t& xruns) {
  if (!pcm) throw DeviceFault("ALSA device '" + options_.device + "': not open");
  while (count > 0) {
    const snd_pcm_sframes_t done = io(pcm, data, count);
    if (done > 0) {
      if (pcm == playback_) written_since_start_ += static_cast<std::size_t>(done);
      data += static_cast<std::size_t>(done) * width;
      count -= static_cast<std::size_t>(done);
      continue;
    }
    if (done == 0 || done == -EAGAIN || done == -EINTR) continue;
    const int error = static_cast<int>(done);
    const std::string failed = "ALSA device '" + options_.device + "': " + what + " failed: " + snd_strerror(error);
    if (error != -EPIPE && error != -ESTRPIPE) throw DeviceFault(failed);
    const int recovered = snd_pcm_recover(pcm, error, 1);
    if (recovered < 0) throw DeviceFault(failed + ", and recovering failed: " + snd_strerror(recovered));
    ++xruns;  // an overrun, an underrun or a suspend, recovered from
    if (pcm == capture_) {
      const int err = snd_pcm_start(pcm);
      if (err < 0) throw DeviceFault(failed + ", and restarting failed: " + snd_strerror(err));
    } else {
      written_since_start_ = 0;  // the buffer ran dry: all that was written has played
    }
  }
}

bool AlsaDevice::Read(float* out, std::size_t count) {
  Transfer(capture_, out, count, static_cast<std::size_t>(options_.capture_channels),
           [](snd_pcm_t* p, float* d, std::size_t n) { return snd_pcm_readi(p, d, n); }, "capture", overruns_);
  return true;
}

std::size_t AlsaDevice::PlaybackRoom() {
  const snd_pcm_sframes_t room = playback_ ? snd_pcm_avail_update(playback_) : 0;
  return room > 0 ? static_cast<std::size_t>(room) : 0;  // an xrun: the next write recovers from it
}

std::size_t AlsaDevice::CaptureLag() {
  snd_pcm_sframes_t waiting = 0;
  if (!capture_ || snd_pcm_delay(capture_, &waiting) < 0) return 0;  // an xrun: the next read recovers from it
  const snd_pcm_sframes_t buffered = std::lround(options_.latency * options_.sample_rate);
  return static_cast<std::size_t>(std::max<snd_pcm_sframes_t>(0, waiting - buffered));
}

void AlsaDevice::Write(const float* in, std::size_t count) {
  Transfer(playback_, in, count, 1, [](snd_pcm_t* p, const float* d, std::size_t n) { return snd_pcm_writei(p, d, n); },
           "playback", underruns_);
}

std::size_t AlsaDevice::PlaybackDelay() {
  if (!playback_) throw DeviceFault("ALSA device '" + options_.device + "': not open");
  switch (snd_pcm_state(playback_)) {
    case SND_PCM_STATE_RUNNING:
      break;
    case SND_PCM_STATE_XRUN:
      return 0;  // it ran dry: all of it has played (the next write recovers and counts it)
    default:
      return written_since_start_;  // not started (it starts once its buffer is full): none played
  }
  snd_pcm_sframes_t delay = 0;
  const int err = snd_pcm_delay(playback_, &delay);
  if (err == -EPIPE || err == -ESTRPIPE) return 0;
  if (err < 0) throw DeviceFault("ALSA device '" + options_.device + "': playback position lost: " + snd_strerror(err));
  return std::min(static_cast<std::size_t>(std::max<snd_pcm_sframes_t>(0, delay)), written_since_start_);
}

}  // namespace nava_modem
