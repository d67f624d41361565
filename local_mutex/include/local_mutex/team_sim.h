#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/audio_channel.h"
#include "audio_propagation/propagation_model.h"
#include "local_mutex/local_mutex.h"

namespace local_mutex {

// One use of the lock: wanted from `want_at` (s) once the robot has heard `after_heard`
// packets, kept for `hold` s once held, then released.
struct Demand {
  double want_at = 0.0;
  std::uint64_t after_heard = 0;
  double hold = 10.0;
};

struct TeamRobot {
  int id = 1;                 // the lock's robot id, 1..255
  Eigen::Vector2d position;   // m, map frame; robots do not move while they want or hold the lock
  std::vector<Demand> demands;
};

struct TeamSimOptions {
  MutexOptions mutex;  // timers shared by every robot; ids come from the robots, seeds from `seed`
  audio_propagation::ChannelOptions channel;
  double step = 0.05;  // s between lock ticks
  // Beyond the simulated channel's own collisions: the probability that a packet heard arrives
  // corrupted (heard as noise, as a bad CRC would be), and that a reception is lost altogether
  // (not even a carrier: outside the thesis's assumptions, and what can break safety).
  double noise = 0.0;
  double loss = 0.0;
  // Set, with `acoustics`: the acoustic channel model (acoustic_model.h) with this decode table
  // and these acoustics on the trials' floor; unset: the thesis's hearing threshold. Robot k is
  // named robot_k for noise sources that ride on a robot.
  std::shared_ptr<const audio_propagation::DecodeTable> decode_table;
  std::optional<world_sim::Acoustics> acoustics;
  bool record = false;  // keep every lock event, for timelines
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field, its value and what was expected: noise and
// loss outside [0, 1], a step not above 0 s, impossible channel options, a decode table without
// acoustics or acoustics without a decode table.
void ValidateTeamSimOptions(const TeamSimOptions& options);

// The copies of requests that could reach a robot in range, and what became of them: each
// REQUEST sent offers one copy to every robot in its sender's range. `heard` arrived whole (not
// lost to a collision, the noise or the half-duplex radio): 1 - heard / offered is the thesis's
// p_r, the chance that one request is lost (section 6.3.2). `sounded` arrived at all, whole or
// as noise: the lock takes any sound as a reason to wait, so only a copy that did not even
// sound leaves a robot free to take the lock.
struct RequestCopies {
  std::uint64_t offered = 0, heard = 0, sounded = 0;
  RequestCopies& operator+=(const RequestCopies& o) {
    offered += o.offered;
    heard += o.heard;
    sounded += o.sounded;
    return *this;
  }
};

// A lock event of one robot; for a packet heard, `from` is the robot that sent it.
struct RobotEvent {
  std::size_t robot = 0;
  std::size_t from = std::numeric_limits<std::size_t>::max();
  MutexEvent event;
};

// One demand served: when it was wanted, granted and released.
struct Grant {
  std::size_t robot = 0;
  RequestTuple request;
  double wanted = 0.0, granted = 0.0;
  double released = std::numeric_limits<double>::quiet_NaN();
};

// A team of robots running the lock over the simulated audio channel of audio_propagation
// (the real link's CSMA-CA MAC, travel times, collisions, half duplex), each robot following
// its list of demands. Watches safety: a robot taking the lock while another robot within
// hearing range holds it is a violation; with the acoustic model, within hearing range means
// that either robot's packets reach the other at least half the time (the model's prediction
// under the noise at the start), the range at which the thesis's lock is meant to hold.
// Deterministic for a seed.
class TeamSim {
 public:
  // Throws std::invalid_argument for impossible options (ValidateTeamSimOptions) or robots (an
  // id outside 1..255, a robot off the map or in a wall).
  TeamSim(const audio_propagation::PropagationModel& model, std::vector<TeamRobot> robots,
          const TeamSimOptions& options);

  // Runs until every demand has been served and released, or until `until` s.
  void Run(double until);
  bool Done() const;
  double time() const { return now_; }

  std::size_t size() const { return robots_.size(); }
  const TeamRobot& robot(std::size_t k) const { return robots_[k]; }
  const LocalMutex& mutex(std::size_t k) const { return *mutexes_[k]; }
  bool InRange(std::size_t a, std::size_t b) const { return in_range_[a][b]; }
  // In the order the lock was granted.
  const std::vector<Grant>& grants() const { return grants_; }
  // Demands wanted but not yet granted: (robot, wanted since).
  std::vector<std::pair<std::size_t, double>> Waiting() const;
  std::uint64_t violations() const { return violations_; }
  std::uint64_t corrupted() const { return corrupted_; }
  std::uint64_t lost() const { return lost_; }
  const RequestCopies& request_copies() const { return request_copies_; }
  const std::vector<RobotEvent>& events() const { return events_; }
  const audio_propagation::AudioChannel& channel() const { return channel_; }

 private:
  struct Progress {
    std::size_t next = 0;  // index of the demand being served
    bool wanted = false;
    double wanted_at = 0.0;
    std::size_t grant = 0;  // index into grants_ while held
    bool held = false;
  };
  void Deliver(const audio_propagation::Reception& rx);
  void FollowDemands(std::size_t k, double now);
  void OnEvent(std::size_t k, const MutexEvent& e);

  std::vector<TeamRobot> robots_;
  TeamSimOptions options_;
  std::unique_ptr<audio_propagation::AcousticModel> acoustic_;  // before channel_, which refers to it
  audio_propagation::AudioChannel channel_;
  std::vector<std::unique_ptr<LocalMutex>> mutexes_;
  std::vector<std::vector<bool>> in_range_;
  std::vector<Progress> progress_;
  std::vector<Grant> grants_;
  std::vector<RobotEvent> events_;
  std::mt19937 rng_;
  std::size_t sender_ = std::numeric_limits<std::size_t>::max();  // of the reception being delivered
  double now_ = 0.0;
  std::uint64_t violations_ = 0, corrupted_ = 0, lost_ = 0;
  RequestCopies request_copies_;
  std::vector<bool> sending_request_;  // per robot: its last packet sent was a REQUEST
};

}  // namespace local_mutex
