#include "nava_modem/moved_rooms.h"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <stdexcept>

#include "nava_modem/measured_response.h"
#include "nava_modem/moved_response.h"

namespace nava_modem {

MovedRooms::MovedRooms(std::vector<MovableRoom> rooms, double sample_rate)
    : rooms_(std::move(rooms)), sample_rate_(sample_rate) {
  if (!(sample_rate > 2.0 * kResponseBandHighHz)) {
    throw std::invalid_argument("moved rooms: expected a sample rate above " + std::to_string(2.0 * kResponseBandHighHz) +
                                " Hz, got " + std::to_string(sample_rate));
  }
  if (rooms_.empty()) throw std::invalid_argument("moved rooms: expected at least one measured room, got none");
  for (MovableRoom& room : rooms_) {
    room.figures = MeasureResponse(room.response, sample_rate);
    if (const auto problem = ResponseProblem(room.figures)) {
      throw std::invalid_argument("moved rooms: " + room.name + " cannot serve: it is " + *problem);
    }
  }
  if (excluded().size() == rooms_.size()) {
    throw std::invalid_argument("moved rooms: every room has an arrival within " + std::to_string(-kMaxBeforeDb) +
                                " dB of its loudest peak before it: none can be moved");
  }
}

std::vector<std::size_t> MovedRooms::excluded() const {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < rooms_.size(); ++k) {
    if (rooms_[k].figures.before_db >= kMaxBeforeDb) out.push_back(k);
  }
  return out;
}

std::vector<std::size_t> MovedRooms::Candidates(double rt60) const {
  std::vector<std::size_t> slower;
  for (std::size_t k = 0; k < rooms_.size(); ++k) {
    if (rooms_[k].figures.rt60_s >= rt60 && rooms_[k].figures.before_db < kMaxBeforeDb) slower.push_back(k);
  }
  if (slower.empty()) {
    double longest = 0.0;
    for (const MovableRoom& room : rooms_) {
      if (room.figures.before_db < kMaxBeforeDb) longest = std::max(longest, room.figures.rt60_s);
    }
    throw std::invalid_argument("moved rooms: no room decays as slowly as an RT60 of " + std::to_string(rt60) +
                                " s (the slowest: " + std::to_string(longest) + " s); a room is only made faster");
  }
  const auto rt60_of = [&](std::size_t k) { return rooms_[k].figures.rt60_s; };
  std::sort(slower.begin(), slower.end(), [&](std::size_t a, std::size_t b) {
    return rt60_of(a) != rt60_of(b) ? rt60_of(a) < rt60_of(b) : a < b;
  });
  std::size_t within = 0;
  while (within < slower.size() && rt60_of(slower[within]) <= kSpan * rt60) ++within;
  slower.resize(std::min(slower.size(), std::max(within, kMinCandidates)));
  std::sort(slower.begin(), slower.end());
  return slower;
}

std::size_t MovedRooms::Chosen(double rt60, std::uint32_t seed) const {
  std::map<std::string, std::vector<std::size_t>> groups;
  for (std::size_t k : Candidates(rt60)) groups[rooms_[k].group.empty() ? "\n" + rooms_[k].name : rooms_[k].group].push_back(k);
  auto group = groups.begin();
  std::advance(group, static_cast<std::ptrdiff_t>(seed % groups.size()));
  return group->second[seed / groups.size() % group->second.size()];
}


MovedRooms::Drawn MovedRooms::Move(double rt60, double drr_db, std::uint32_t seed) const {
  Drawn d;
  d.room = Chosen(rt60, seed);
  const MovableRoom& room = rooms_[d.room];
  d.peak = room.figures.peak;
  d.response = std::make_shared<const std::vector<float>>(MovedResponse(room.response, room.figures, sample_rate_, rt60, drr_db));
  return d;
}

MovedRooms::Drawn MovedRooms::Draw(double rt60, double drr_db, std::uint32_t seed) const {
  const auto key = std::make_tuple(Chosen(rt60, seed), rt60, drr_db);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = moved_.find(key); it != moved_.end()) return it->second;
  }
  // Moved outside the lock: two threads may move the same room once each, and keep the first.
  Drawn d = Move(rt60, drr_db, seed);
  const std::lock_guard<std::mutex> lock(mutex_);
  return moved_.emplace(key, std::move(d)).first->second;
}

}  // namespace nava_modem
