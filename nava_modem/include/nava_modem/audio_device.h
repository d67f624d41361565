#pragma once

#include <cstddef>
#include <cstdint>

namespace nava_modem {

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
  virtual bool Read(float* out, std::size_t count) = 0;
  // Plays `count` samples, blocking while the device's buffer is full.
  virtual void Write(const float* in, std::size_t count) = 0;
  // Capture overruns (captured samples lost) and playback underruns (a gap in what was
  // played) recovered from so far.
  virtual std::uint64_t overruns() const = 0;
  virtual std::uint64_t underruns() const = 0;
};

}  // namespace nava_modem
