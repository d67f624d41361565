#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "nava_modem/noise_floor.h"

namespace nava_modem {

// Timing and thresholds of the Nava CSMA-CA link layer (thesis section 5.2.4). All timing runs
// in ticks of 1/16 of a bit time, so a faster bit rate makes everything faster alike.
struct MacOptions {
  double bit_rate = 300.0;            // bits per second
  int packet_bits = 110;              // 40 bits of break + 7 bytes of 8N1
  double calibration_time = 4.0;      // s of silence listened to before the first send
  std::optional<double> fixed_threshold_db;  // skip calibration and use this carrier threshold
  double threshold_margin_db = 6.0;   // calibrated threshold: loudest silence + this margin
  // After the calibration the threshold follows the floor where the robot is: the loudest level
  // of each block of floor_block (its own sending and deaf time left out), the quietest
  // of the last floor_window of them, plus the margin. 0: the thesis's one calibration.
  double floor_window = 10.0;
  double floor_block = 1.0;
  double backoff_min_bits = 2.0;      // random wait on a free medium before sending, in bits
  double backoff_max_bits = 30.0;
  double deaf_time = 0.2;             // s of own echo ignored after sending (< a packet)
  double carrier_release_bits = 1.0;  // bits without carrier that end a reception
  std::size_t queue_capacity = 16;    // packets waiting to be sent
};

enum class MacState { kCalibrating, kWaiting, kSending, kDeaf, kReceiving };
const char* MacStateName(MacState s);

// Throws std::invalid_argument naming the option when it is impossible.
void ValidateMacOptions(const MacOptions& options);

// A frame waiting for the air: its bytes, the rate step it goes at, and how long it holds the
// air once sent (frames of one profile differ in length and rate, so each carries its own).
struct MacFrame {
  std::vector<std::uint8_t> data;
  int rate = 0;
  double airtime = 0.0;  // s, above 0
};
// Throws std::invalid_argument for an airtime that is not a positive number of seconds.
void ValidateMacFrame(const MacFrame& frame);

// The Nava state machine: Calibrating -> Waiting; Waiting -> Receiving on carrier, or ->
// Sending after a random back-off on a free medium when a packet is queued; Sending -> Deaf
// -> Waiting; Receiving -> Waiting when the carrier has gone. The caller owns time: it calls
// Tick() once per tick with the level heard, and transmits the packet Tick() hands back (the
// MAC then stays in Sending for one packet time). Deterministic for a seed.
class CsmaMac {
 public:
  CsmaMac(const MacOptions& options, std::uint32_t seed);

  // Queues a frame; false (and counted) when the queue is full. Throws as ValidateMacFrame.
  bool Enqueue(MacFrame frame);
  // Today's packet: `data` at rate 0, lasting packet_bits at bit_rate.
  MacFrame Packet(std::vector<std::uint8_t> data) const;
  bool Enqueue(std::vector<std::uint8_t> data) { return Enqueue(Packet(std::move(data))); }

  // Advances one tick having heard `level_db`; returns the frame to start sending now, if any
  // (the MAC then stays in Sending for its airtime). With `may_send` false (the caller's carrier
  // sense is stale) a send waits, its back-off held where it is.
  std::optional<MacFrame> Tick(double level_db, bool may_send = true);

  // The audio stopped (the device failed): a send, deaf time or reception under way is over.
  // `unsent` (frames whose sound did not all play, oldest first) go back to the front of the
  // queue, even past its capacity (they were accepted once), and count in requeued(). The
  // MAC then waits at least `hold_seconds` and a fresh back-off (with something to send and the
  // air free) before it sends; a calibration under way goes on.
  void Interrupt(std::vector<MacFrame> unsent, double hold_seconds);

  // Waiting with nothing to send: ticks on a steady level below the threshold change nothing but
  // the tick count and the floor (which only raises the threshold then), so a caller that knows
  // the air is silent may skip such ticks.
  bool Idle() const { return state_ == MacState::kWaiting && queue_.empty(); }
  // Counts `ticks` silent ticks at `level_db` while Idle() without running them one by one.
  void SkipIdle(std::uint64_t ticks, double level_db);

  // Ticks until the state or the carrier can next change if every tick from the next on hears
  // `level_db` and nothing is queued (nullopt: not before one of those changes).
  std::optional<int> TicksToNextChange(double level_db) const;

  MacState state() const { return state_; }
  double threshold_db() const { return threshold_db_; }
  bool carrier() const { return carrier_; }
  double tick_seconds() const { return tick_seconds_; }
  int packet_ticks() const { return packet_ticks_; }  // today's packet's airtime
  int Ticks(double seconds) const;                     // rounded to the nearest tick
  std::uint64_t ticks() const { return ticks_; }
  std::size_t queued() const { return queue_.size(); }
  std::uint64_t sent() const { return sent_; }
  std::uint64_t dropped() const { return dropped_; }
  std::uint64_t receptions() const { return receptions_; }
  std::uint64_t requeued() const { return requeued_; }

 private:
  void EnterWaiting();
  // Hears `ticks` at `level_db` on the floor; once calibrated, the threshold follows it.
  void Follow(double level_db, std::uint64_t ticks);

  MacOptions options_;
  std::mt19937 rng_;
  double tick_seconds_;
  int packet_ticks_, deaf_ticks_, release_ticks_, calibration_ticks_;
  MacState state_ = MacState::kCalibrating;
  double threshold_db_ = 0.0;
  double loudest_silence_db_ = -1e300;
  std::optional<NoiseFloor> floor_;  // none: a fixed threshold, or the thesis's one calibration
  bool carrier_ = false;
  int remaining_ = 0;  // ticks left in the current timed phase (calibration, back-off, send, deaf, release)
  std::deque<MacFrame> queue_;
  std::uint64_t ticks_ = 0, sent_ = 0, dropped_ = 0, receptions_ = 0, requeued_ = 0;
};

}  // namespace nava_modem
