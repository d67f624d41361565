#pragma once

// Measured rooms to be moved to any RT60 and DRR (moved_response.h): a renderer's source of rooms
// with real reflections, drawn by seed. Thread-safe: the moved responses are kept, one per room,
// RT60 and DRR asked, since a decode table asks each cell's rooms for every packet. No ROS.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "nava_modem/measured_response.h"

namespace nava_modem {

struct MovableRoom {
  std::string name;
  // The room it was measured in: its positions and ears share one (empty: a room of its own).
  // A draw picks a room first, then one of its positions, so that a hall measured from a dozen
  // seats weighs as much as a kitchen measured from one.
  std::string group;
  std::vector<float> response;  // at the pool's sample rate, its own delay kept
  // Filled by MovedRooms: as MeasureResponse reads the response (its RT60, its direct sound's
  // sample, the sound before it), once, for every move.
  ResponseMeasures figures;
};

class MovedRooms {
 public:
  // Every response must give its figures (ResponseProblem); throws std::invalid_argument naming
  // the first that does not, or for no rooms or a sample rate not above 2 x 5400 Hz. A room whose
  // loudest peak follows an arrival within kMaxBeforeDb of it (before_db: a listener behind an
  // obstacle, a reflection louder than the sound it reflects) is kept but never drawn: scaling
  // what follows its loudest peak leaves that arrival where it was, so made drier it would be a
  // room with an echo before its direct sound (excluded() names them).
  MovedRooms(std::vector<MovableRoom> rooms, double sample_rate);
  static constexpr double kMaxBeforeDb = -10.0;
  std::vector<std::size_t> excluded() const;

  // The rooms a room of `rt60` is drawn from: those whose own RT60 lies in [rt60, kSpan x rt60]
  // (a room is only made to decay faster, and not by more than kSpan times), or, when fewer than
  // kMinCandidates do, the kMinCandidates slowest-decaying at or above rt60 nearest to it. Throws
  // std::invalid_argument when no room decays as slowly as rt60 (naming the slowest).
  std::vector<std::size_t> Candidates(double rt60) const;
  static constexpr double kSpan = 3.0;
  static constexpr std::size_t kMinCandidates = 6;

  // One of Candidates(rt60), chosen by `seed` (a group among the candidates' groups, then one of
  // its candidates), moved to rt60 and drr_db: its response (its own delay kept) and where its
  // direct sound is.
  struct Drawn {
    std::shared_ptr<const std::vector<float>> response;
    std::size_t peak = 0;
    std::size_t room = 0;  // index into rooms()
  };
  // Kept for the next draw of the same room, RT60 and DRR (a table's cells ask few of them).
  Drawn Draw(double rt60, double drr_db, std::uint32_t seed) const;
  // Moved anew every time (a scene's links ask as many as they have).
  Drawn Move(double rt60, double drr_db, std::uint32_t seed) const;

  const std::vector<MovableRoom>& rooms() const { return rooms_; }
  double sample_rate() const { return sample_rate_; }

 private:
  std::size_t Chosen(double rt60, std::uint32_t seed) const;

  std::vector<MovableRoom> rooms_;
  double sample_rate_;
  mutable std::mutex mutex_;
  mutable std::map<std::tuple<std::size_t, double, double>, Drawn> moved_;
};

}  // namespace nava_modem
