#pragma once

#include <cstdint>
#include <deque>

#include <Eigen/Core>

#include "sounds_good_explorer/listen_mode.h"

namespace sounds_good_explorer {

struct AudioTermOptions {
  double lifetime = 180.0;      // s: freshness falls from 1 to 0 over this, then the message goes
  double level_floor_db = 40.0;  // level weighted 0 (the simulated hearing threshold)
  double level_full_db = 70.0;   // level weighted 1 (the simulated source level at 1 m)
  std::size_t capacity = 512;    // messages kept; the oldest is dropped (and counted) beyond it
};

void ValidateOptions(const AudioTermOptions& options);

// One announcement heard: which marker, where it came from in the odom frame (NaN unknown),
// how loud, when.
struct HeardMessage {
  std::uint32_t marker = 0;
  double direction = 0.0;  // rad, odom frame
  double level_db = 0.0;
  double time = 0.0;
  bool half_plane = false;  // one bit: only the side of the robot it came from is known
};

// The queue of heard announcements and the audio term of the frontier cost (thesis section
// 3.3.3). The thesis writes the term as a product over messages; a product of factors in -1..1
// shrinks with every message and flips sign with each disagreeing one, which cannot be the
// intent ("each cell can be scored based on the received messages"). Here each message adds
// its own score, and the cost subtracts w times the sum:
//   score(cell) = sum over messages m about the sought marker of
//                 agreement(m, cell) * freshness(m) * loudness(m)
//   agreement  = cos(angle between the message's direction and the cell's, seen from the robot)
//                (the thesis's (pi - 2x) / pi is its linear stand-in); for a one-bit
//                (bidirectional) message, +1 anywhere in the heard half-plane and -1 outside:
//                the bit says nothing about where in the half-plane, and the cosine would
//                favour the robot's own axis (tried: bidirectional teams were then slower than
//                no audio in two of ten configurations)
//   freshness  = 1 - age / lifetime (the thesis's "message age factor", 0 at three minutes)
//   loudness   = level mapped linearly from level_floor_db (0) to level_full_db (1), clamped.
class HeardMessages {
 public:
  explicit HeardMessages(const AudioTermOptions& options);

  // `direction` is in the robot frame as the microphone reported it (NaN when unknown);
  // `robot_yaw` turns it into the odom frame. In bidirectional mode only its sign survives:
  // ahead (cos >= 0) becomes 0 and behind becomes pi, whatever the microphone gave. In
  // none mode nothing is kept.
  void Add(std::uint32_t marker, double direction, double robot_yaw, double level_db,
           double time, ListenMode mode);
  void Forget(double time);  // drops messages older than the lifetime

  // The audio term for a cell seen from the robot in direction `cell_direction` (odom frame).
  double Score(std::uint32_t marker, double cell_direction, double time) const;
  // Whether any message about `marker` is kept.
  bool Has(std::uint32_t marker) const;

  const std::deque<HeardMessage>& messages() const { return messages_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  AudioTermOptions options_;
  std::deque<HeardMessage> messages_;
  std::uint64_t dropped_ = 0;
};

}  // namespace sounds_good_explorer
