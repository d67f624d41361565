#pragma once

// Test doubles for a link's device failures: a clock that only moves when slept on, and a
// sound card that fails where it is told to and comes back after refusing some reopens.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/clock.h"

namespace nava_modem::test_doubles {

class ManualClock : public Clock {
 public:
  double Now() override { return now_; }
  void Sleep(double seconds) override {
    now_ += seconds;
    longest_sleep_ = std::max(longest_sleep_, seconds);
  }
  double longest_sleep() const { return longest_sleep_; }

 private:
  double now_ = 100.0, longest_sleep_ = 0.0;
};

// Capture hears `input` (then ends). Playback goes through a buffer that holds `delay` samples
// (the latency of a card or a sound server) onto the air, one sample played per sample
// captured; the air is what listeners would hear. At each capture position in `fail_at` the
// device fails once, losing what its buffer held, and then refuses `refusals` reopens. At
// capture position `stall_at` the link's process stalls for `stall` samples, as a sound server
// sees it: that much plays on (the buffer runs dry), and the capture keeps that much waiting,
// which the link reads without time passing.
class FailingDevice : public AudioDevice {
 public:
  struct Options {
    double rate = 16000.0;
    std::size_t delay = 0;
    std::vector<float> input;
    std::vector<std::size_t> fail_at;  // ascending
    int refusals = 0;
    std::size_t stall_at = SIZE_MAX, stall = 0;
  };
  FailingDevice(const Options& options, Clock& clock) : o_(options), clock_(clock) { Prime(); }

  double sample_rate() const override { return o_.rate; }
  bool Read(float* out, std::size_t count) override {
    if (down_) throw DeviceFault("read on a failed device");
    if (next_fail_ < o_.fail_at.size() && read_ + count > o_.fail_at[next_fail_]) {
      ++next_fail_;
      down_ = true;
      buffer_.clear();  // what it held never plays
      throw DeviceFault("the card went away");
    }
    if (read_ + count > o_.input.size()) return false;
    std::copy(o_.input.begin() + static_cast<std::ptrdiff_t>(read_), o_.input.begin() + static_cast<std::ptrdiff_t>(read_ + count), out);
    read_ += count;
    if (read_ >= o_.stall_at && !stalled_) {
      stalled_ = true;
      Play(o_.stall);
      backlog_ = o_.stall;
    }
    const std::size_t waiting = std::min(backlog_, count);  // read without time passing
    backlog_ -= waiting;
    Play(count - waiting);
    return true;
  }
  void Write(const float* in, std::size_t count) override {
    if (down_) throw DeviceFault("write on a failed device");
    buffer_.insert(buffer_.end(), in, in + count);
  }
  // What of the link's own writes is still in the buffer.
  std::size_t PlaybackDelay() override { return buffer_.size() - primed_; }
  std::size_t PlaybackRoom() override { return o_.delay > buffer_.size() ? o_.delay - buffer_.size() : 0; }
  std::size_t CaptureLag() override { return backlog_; }
  void Reopen() override {
    tries_.push_back(clock_.Now());
    if (refused_ < o_.refusals) {
      ++refused_;
      throw DeviceFault("no such card yet");
    }
    refused_ = 0;
    down_ = false;
    Prime();
  }
  std::uint64_t overruns() const override { return 0; }
  std::uint64_t underruns() const override { return 0; }

  const std::vector<float>& air() const { return air_; }
  const std::vector<double>& tries() const { return tries_; }  // clock times of the reopen tries

 private:
  // `count` samples of time pass for playback.
  void Play(std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      air_.push_back(buffer_.empty() ? 0.0f : buffer_.front());
      if (buffer_.empty()) continue;
      buffer_.pop_front();
      if (primed_ > 0) --primed_;
    }
  }
  // A stream starts with its buffer full of silence: what the link writes plays `delay` later.
  void Prime() {
    buffer_.assign(o_.delay, 0.0f);
    primed_ = o_.delay;
  }

  Options o_;
  Clock& clock_;
  std::deque<float> buffer_;
  std::vector<float> air_;
  std::vector<double> tries_;
  std::size_t read_ = 0, primed_ = 0, next_fail_ = 0, backlog_ = 0;
  int refused_ = 0;
  bool down_ = false, stalled_ = false;
};

}  // namespace nava_modem::test_doubles
