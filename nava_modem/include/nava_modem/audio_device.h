#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace nava_modem {

// The device has stopped working (a USB card unplugged, a sound server gone) and recovering
// the stream in place failed: the link closes it and reopens it later (Reopen()). Over- and
// underruns are not faults: the device recovers from those itself and counts them.
class DeviceFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where a link's sound goes and comes from: a sound card (AlsaDevice) or files (WavDevice).
// Float samples in [-1, 1]; playback is mono, capture has capture_channels() interleaved
// channels (one per microphone of an array). Capture and playback run in step: the link writes
// as many frames as it reads, silence when it has nothing to say.
class AudioDevice {
 public:
  virtual ~AudioDevice() = default;
  virtual double sample_rate() const = 0;
  virtual int capture_channels() const { return 1; }
  // Fills `out` with the next `count` captured frames (count x capture_channels() samples,
  // interleaved), blocking until they are there. False at the end of the input (files only).
  // Throws DeviceFault when the device has failed.
  virtual bool Read(float* out, std::size_t count) = 0;
  // Plays `count` samples, blocking while the device's buffer is full. Throws DeviceFault when
  // the device has failed.
  virtual void Write(const float* in, std::size_t count) = 0;
  // Samples written but not yet played, now: what a failure would lose of the playback. Never
  // more than was written since the stream last (re)started. Throws DeviceFault.
  virtual std::size_t PlaybackDelay() = 0;
  // Samples Write() would take now without waiting.
  virtual std::size_t PlaybackRoom() = 0;
  // Captured frames waiting to be read beyond the device's own buffering, now. A sound card
  // overruns when a stalled process leaves its buffer full, but a sound server keeps what was
  // not read and hands it over late: the link then falls behind real time (see NavaLink).
  virtual std::size_t CaptureLag() = 0;
  // Closes what is left of a failed device and opens it again, with empty buffers. Throws
  // DeviceFault when it cannot be opened (yet).
  virtual void Reopen() = 0;
  // Capture overruns (captured samples lost) and playback underruns (a gap in what was
  // played) recovered from so far, across reopens.
  virtual std::uint64_t overruns() const = 0;
  virtual std::uint64_t underruns() const = 0;
};

}  // namespace nava_modem
