#include "nava_modem/csma_mac.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

namespace nava_modem {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("nava_modem MAC: " + what);
}

}  // namespace

const char* MacStateName(MacState s) {
  switch (s) {
    case MacState::kCalibrating:
      return "calibrating";
    case MacState::kWaiting:
      return "waiting";
    case MacState::kSending:
      return "sending";
    case MacState::kDeaf:
      return "deaf";
    case MacState::kReceiving:
      return "receiving";
  }
  return "?";
}

void ValidateMacOptions(const MacOptions& o) {
  Require(o.bit_rate > 0.0 && std::isfinite(o.bit_rate), "bit_rate must be a positive number of bits/s");
  Require(o.packet_bits > 0, "packet_bits must be positive");
  Require(o.calibration_time >= 0.0, "calibration_time must be >= 0 s");
  Require(!o.fixed_threshold_db || std::isfinite(*o.fixed_threshold_db), "fixed threshold must be finite");
  Require(o.backoff_min_bits >= 0.0 && o.backoff_max_bits >= o.backoff_min_bits,
          "back-off must satisfy 0 <= backoff_min_bits <= backoff_max_bits");
  const double packet_time = o.packet_bits / o.bit_rate;
  Require(o.deaf_time >= 0.0 && o.deaf_time < packet_time,
          "deaf_time (" + std::to_string(o.deaf_time) + " s) must be >= 0 and shorter than a packet (" +
              std::to_string(packet_time) + " s), or a carrier could be missed");
  Require(o.floor_window >= 0.0 && std::isfinite(o.floor_window),
          "floor_window must be >= 0 s (0: one calibration, as the thesis)");
  Require(o.floor_block > 0.0 && std::isfinite(o.floor_block),
          "floor_block must be a positive number of seconds");
  Require(o.floor_window == 0.0 || o.floor_window >= o.floor_block,
          "floor_window (" + std::to_string(o.floor_window) +
              " s) must be 0 or at least one floor block (floor_block " +
              std::to_string(o.floor_block) + " s)");
  Require(o.carrier_release_bits > 0.0, "carrier_release_bits must be positive");
  Require(o.queue_capacity > 0, "queue_capacity must be at least 1");
}

CsmaMac::CsmaMac(const MacOptions& options, std::uint32_t seed) : options_(options), rng_(seed) {
  ValidateMacOptions(options_);
  tick_seconds_ = 1.0 / (16.0 * options_.bit_rate);
  packet_ticks_ = options_.packet_bits * 16;
  deaf_ticks_ = Ticks(options_.deaf_time);
  release_ticks_ = std::max(1, static_cast<int>(std::lround(options_.carrier_release_bits * 16)));
  calibration_ticks_ = Ticks(options_.calibration_time);
  if (options_.fixed_threshold_db) {
    threshold_db_ = *options_.fixed_threshold_db;
    EnterWaiting();
  } else {
    remaining_ = calibration_ticks_;
    if (options_.floor_window > 0.0) {
      floor_.emplace(std::max(1, Ticks(options_.floor_block)),
                     std::max(1, static_cast<int>(std::lround(options_.floor_window / options_.floor_block))));
    }
  }
}

void CsmaMac::Follow(double level_db, std::uint64_t ticks) {
  if (!floor_ || !floor_->Hear(level_db, ticks) || state_ == MacState::kCalibrating) return;
  threshold_db_ = *floor_->floor_db() + options_.threshold_margin_db;
}

void CsmaMac::SkipIdle(std::uint64_t ticks, double level_db) {
  ticks_ += ticks;
  Follow(level_db, ticks);
}

int CsmaMac::Ticks(double seconds) const {
  return static_cast<int>(std::lround(seconds / tick_seconds_));
}

void ValidateMacFrame(const MacFrame& frame) {
  Require(frame.airtime > 0.0 && std::isfinite(frame.airtime),
          "a frame's airtime must be a positive number of seconds, got " + std::to_string(frame.airtime));
}

bool CsmaMac::Enqueue(MacFrame frame) {
  ValidateMacFrame(frame);
  if (queue_.size() >= options_.queue_capacity) {
    ++dropped_;
    return false;
  }
  queue_.push_back(std::move(frame));
  return true;
}

MacFrame CsmaMac::Packet(std::vector<std::uint8_t> data) const {
  return MacFrame{std::move(data), 0, options_.packet_bits / options_.bit_rate};
}

void CsmaMac::Interrupt(std::vector<MacFrame> unsent, double hold_seconds) {
  requeued_ += unsent.size();
  queue_.insert(queue_.begin(), std::make_move_iterator(unsent.begin()), std::make_move_iterator(unsent.end()));
  carrier_ = false;
  if (state_ == MacState::kCalibrating) return;
  EnterWaiting();
  remaining_ += Ticks(hold_seconds);
}

void CsmaMac::EnterWaiting() {
  state_ = MacState::kWaiting;
  // A fresh random back-off every time the medium is free again: that is what spreads out
  // robots that all waited for the same sender to finish.
  std::uniform_int_distribution<int> backoff(static_cast<int>(std::lround(options_.backoff_min_bits * 16)),
                                             static_cast<int>(std::lround(options_.backoff_max_bits * 16)));
  remaining_ = backoff(rng_);
}

std::optional<int> CsmaMac::TicksToNextChange(double level_db) const {
  const bool heard = level_db > threshold_db_;
  switch (state_) {
    case MacState::kWaiting:  // a carrier makes it receive; the back-off counts down only with something to send
      if (heard) return 1;
      if (queue_.empty()) return std::nullopt;
      break;
    case MacState::kReceiving:  // the release counts down only once the carrier has gone
      if (heard != carrier_) return 1;
      // A carrier that lasts a whole window (a new, louder room) becomes the floor.
      if (carrier_) return floor_ ? std::optional<int>(static_cast<int>(floor_->TicksToBlockEnd())) : std::nullopt;
      break;
    case MacState::kCalibrating:
    case MacState::kSending:
    case MacState::kDeaf:
      break;
  }
  return std::max(remaining_, 1);
}

std::optional<MacFrame> CsmaMac::Tick(double level_db, bool may_send) {
  ++ticks_;
  // What is heard while sending or deaf is our own sound, not the room's.
  if (state_ != MacState::kSending && state_ != MacState::kDeaf) Follow(level_db, 1);
  switch (state_) {
    case MacState::kCalibrating:
      carrier_ = false;
      loudest_silence_db_ = std::max(loudest_silence_db_, level_db);
      if (--remaining_ <= 0) {
        threshold_db_ = loudest_silence_db_ + options_.threshold_margin_db;
        EnterWaiting();
      }
      return std::nullopt;
    case MacState::kWaiting:
      carrier_ = level_db > threshold_db_;
      if (carrier_) {
        state_ = MacState::kReceiving;
        remaining_ = release_ticks_;
        ++receptions_;
        return std::nullopt;
      }
      if (queue_.empty() || !may_send) return std::nullopt;
      if (--remaining_ > 0) return std::nullopt;
      {
        MacFrame p = std::move(queue_.front());
        queue_.pop_front();
        state_ = MacState::kSending;
        remaining_ = std::max(1, Ticks(p.airtime));
        ++sent_;
        return p;
      }
    case MacState::kSending:
      carrier_ = false;  // our own signal is not someone else's carrier
      if (--remaining_ <= 0) {
        state_ = MacState::kDeaf;
        remaining_ = deaf_ticks_;
        if (remaining_ == 0) EnterWaiting();
      }
      return std::nullopt;
    case MacState::kDeaf:
      carrier_ = false;
      if (--remaining_ <= 0) EnterWaiting();
      return std::nullopt;
    case MacState::kReceiving:
      carrier_ = level_db > threshold_db_;
      if (carrier_) {
        remaining_ = release_ticks_;
      } else if (--remaining_ <= 0) {
        EnterWaiting();
      }
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace nava_modem
