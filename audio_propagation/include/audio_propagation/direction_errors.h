#pragma once

// What a real microphone array reports of where a packet came from, room by room: the table the
// simulated microphones draw their reports from, so that a simulated robot hears directions as
// badly as a real one does (nava_bench --direction measures it; direction_errors_file.h loads
// it). No ROS.
//
// A table is a grid of reverberation times x direct-to-reverberant ratios; each cell holds the
// packets the profile's receiver decoded there with each array, as (true bearing, estimate,
// confidence), the estimate NaN where the array could not tell. A report is one of those
// packets drawn at random from the cell nearest the link's RT60 (in log) and DRR, so that the
// errors, the missing directions and the confidence keep the joint spread they were measured
// with. A cell with fewer than `min_packets` packets for an array (nava decodes one in a
// hundred under -9 dB in long reverberation) draws from the cell at its DRR and the nearest RT60
// that has enough, else from the next drier DRR's: a drier cell would be optimistic where the
// direct sound is weakest, while a shorter RT60 at the same DRR has about the same errors (the
// room profile's table: the same within a few degrees from 0.3 to 2 s at every DRR).
// Reports:
//  - omni (a square of four microphones): the true direction plus the drawn packet's error;
//  - bidirectional (a pair on the robot's x axis): one bit, front or back, right or wrong as the
//    drawn packet's was; drawn among the packets that came from as far off the pair's axis as
//    this one (within 20 degrees of broadside, 20 to 50 degrees off it, or nearer the axis),
//    since a pair cannot tell which end a sound from its broadside is nearer to; from any of
//    the cell's packets when none came from that band.
#include <random>
#include <string>
#include <vector>

#include "world_sim/world_config.h"

namespace audio_propagation {

// One decoded packet of a cell (rad; estimate NaN for no direction; confidence 0 to 1).
struct DirectionSample {
  double truth = 0.0, estimate = 0.0, confidence = 0.0;
};

struct DirectionCell {
  double rt60 = 0.0;   // s
  double drr_db = 0.0;
  std::vector<DirectionSample> omni, bidirectional;
};

// What a microphone reports: a direction in the robot's frame (rad, NaN for none) and how sure
// the array is of it.
struct SensedDirection {
  double direction = 0.0;
  double confidence = 0.0;
};

class DirectionErrors {
 public:
  // Throws std::invalid_argument naming what is wrong: no cell, a cell whose RT60 is not above 0
  // or whose DRR is not finite, two cells at the same place, a grid with a hole (every RT60 with
  // every DRR), no cell at the driest DRR with min_packets packets for an array, a sample not
  // finite (but for a NaN estimate) or a confidence outside 0..1, min_packets below 1.
  DirectionErrors(std::string profile, std::vector<DirectionCell> cells, std::size_t min_packets = kMinPackets);
  // What a cell needs to be drawn from (nava_bench --direction's --min-decoded).
  static constexpr std::size_t kMinPackets = 10;

  const std::string& profile() const { return profile_; }
  const std::vector<DirectionCell>& cells() const { return cells_; }

  // The cell nearest (rt60, drr_db): nearest RT60 by ratio, then nearest DRR; beyond the grid,
  // its edge.
  const DirectionCell& Nearest(double rt60, double drr_db) const;
  // The packets `microphone` (omni or bidirectional) draws from for (rt60, drr_db): the nearest
  // cell's, or as above when it has too few.
  const std::vector<DirectionSample>& Packets(world_sim::Microphone microphone, double rt60, double drr_db) const;

  // What `microphone` reports of a sound arriving from `relative` (rad, in the robot's frame,
  // finite) over a link of `drr_db` in a room of `rt60` s. kNone reports NaN. An RT60 that is
  // not finite is taken as the grid's longest, a DRR that is not finite as its wettest (the
  // hardest cells: a link the model cannot place is not given good directions).
  SensedDirection Sense(world_sim::Microphone microphone, double relative, double drr_db, double rt60,
                        std::mt19937& rng) const;

 private:
  std::string profile_;
  std::vector<DirectionCell> cells_;
  std::size_t min_packets_;
  std::vector<double> rt60s_, drrs_;  // the grid's values, ascending
};

}  // namespace audio_propagation
