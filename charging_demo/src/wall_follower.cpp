#include "charging_demo/wall_follower.h"

#include <algorithm>
#include <cmath>

#include "grid/option_checks.h"

namespace charging_demo {

namespace {

// m beyond `distance` at which something ahead makes the robot turn away on the spot: room to
// turn before it touches.
constexpr double kTurnRoom = 0.25;
// Round the end of a wall at this share of the speed, for at most this angle (rad): a
// three-quarter turn brings a wall that ended (a door jamb) back within reach.
constexpr double kArcSpeedShare = 0.6;
constexpr double kArcLimit = 1.5 * M_PI;

}  // namespace

void ValidateOptions(const WallFollowOptions& o) {
  using grid::RequireAbove;
  RequireAbove("wall_follow distance (m)", o.distance, 0.0);
  RequireAbove("wall_follow speed (m/s)", o.speed, 0.0);
  RequireAbove("wall_follow gain", o.gain, 0.0);
  RequireAbove("wall_follow turn_rate (rad/s)", o.turn_rate, 0.0);
  RequireAbove("wall_follow lost_range (m)", o.lost_range, o.distance);
  RequireAbove("wall_follow corner_radius (m)", o.corner_radius, 0.0);
}

WallFollower::WallFollower(const WallFollowOptions& options, Hand hand)
    : options_((ValidateOptions(options), options)), hand_(hand) {}

void WallFollower::Reset() {
  on_wall_ = false;
  arcing_ = 0.0;
}

local_navigation::Velocity WallFollower::Update(const std::vector<local_navigation::RangeReading>& ranges,
                                                    double dt) {
  const WallFollowOptions& o = options_;
  const double side = hand_ == Hand::kLeft ? 1.0 : -1.0;  // the wall's side, as a sign of bearings
  const double front = local_navigation::NearestRange(ranges, 0.0, M_PI / 6.0);
  // The wall straight across, and half way between ahead and across (a wall along the way reads
  // 1/cos 45 further there; nearer, the wall closes in ahead).
  const double across = local_navigation::NearestRange(ranges, side * M_PI / 2.0, M_PI / 8.0);
  const double diagonal = local_navigation::NearestRange(ranges, side * M_PI / 4.0, M_PI / 8.0) * std::cos(M_PI / 4.0);
  local_navigation::Velocity out;
  if (front < o.distance + kTurnRoom) {
    // Something ahead: turn away from the wall side on the spot; it becomes the wall.
    on_wall_ = true;
    arcing_ = 0.0;
    out.w = -side * o.turn_rate;
    return out;
  }
  if (across <= o.lost_range) {
    on_wall_ = true;
    arcing_ = 0.0;
    out.v = o.speed * std::clamp((front - o.distance) / o.lost_range, 0.3, 1.0);
    // Keep the wall at `distance`, and turn away early where it closes in ahead.
    const double off = std::min(across, diagonal) - o.distance;
    out.w = std::clamp(side * o.gain * off, -o.turn_rate, o.turn_rate);
    return out;
  }
  if (on_wall_) {
    // The wall ended (a door, a corner turning away): arc round its end; with still no wall
    // after kArcLimit, it is lost.
    out.v = kArcSpeedShare * o.speed;
    out.w = side * std::min(out.v / o.corner_radius, o.turn_rate);
    arcing_ += dt;
    if (arcing_ * std::abs(out.w) > kArcLimit) Reset();
    return out;
  }
  out.v = o.speed;  // open space: straight on to the next wall
  return out;
}

}  // namespace charging_demo
