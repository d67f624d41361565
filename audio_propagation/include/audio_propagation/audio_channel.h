#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/direction_errors.h"
#include "audio_propagation/path_cache.h"
#include "audio_propagation/propagation_model.h"
#include "audio_propagation/reception_model.h"
#include "grid/pose2d.h"
#include "nava_modem/csma_mac.h"
#include "nava_modem/packet_receiver.h"
#include "world_sim/world_config.h"

namespace audio_propagation {

struct ChannelOptions {
  // Each robot's link layer. Unless set, the carrier threshold is the model's hearing threshold
  // (a simulated robot needs no calibration).
  nava_modem::MacOptions mac;
  double capture_margin_db = 10.0;  // a packet this much louder than every overlap survives it
  double direction_noise = 0.0;     // rad (standard deviation) added by omni microphones
  // Set: every microphone reports what a real array would over the link's DRR and RT60, drawn
  // from this table (direction_errors.h; direction_noise must then be 0). Needs the acoustic
  // model, which knows each link's DRR and RT60. Unset: the exact direction of the path's last leg.
  std::shared_ptr<const DirectionErrors> direction_errors;
  double noise_floor_db = 0.0;      // level reported when nothing is heard
  // Paths kept for reuse, keyed on the cells of sender and listener (0 = compute every path
  // exactly). A reused path was computed for other points of the same two cells. With a cache,
  // what each robot's cell sees of the map's corners is remembered too (VisibilityMemo; robots
  // that move still keep their cell for many packets): the paths are then exact to within a cell.
  std::size_t cache_size = 0;
  std::uint32_t seed = 1;
  // Acoustic model: links keep their fate. A real static link delivers nearly all of its packets
  // or nearly none (in 86 % of the measured rooms' cases 18-20 or 0-2 of 20), because what
  // decides a packet is the room's fading at the two places, which stays until one moves. So the
  // draw that decides a pair's packets is made once and held while neither robot has moved more
  // than fate_distance (m) from where it was drawn; then drawn again. Over many places delivery
  // still follows the decode table. Off: every packet drawn anew.
  bool link_fate = false;
  // Half a wavelength at nava's lower tone (2300 Hz): a diffuse field's correlation between two
  // points d apart is sin(kd) / kd, first zero at half a wavelength; and the measured dummy
  // heads' two ears, 0.15 m apart, often disagree completely (docs/audio_link.md).
  double fate_distance = 0.075;
};

// Throws std::invalid_argument naming the field and its value: capture_margin_db and
// direction_noise at least 0 (0 with direction_errors), a finite noise_floor_db, fate_distance above 0. Each robot's MAC checks `mac` once given
// the profile's timing (nava_modem::ValidateMacOptions).
void ValidateOptions(const ChannelOptions& options);

// Something a robot heard, at the end of its reception.
struct Reception {
  enum class Kind { kPacket, kNoise };
  std::size_t receiver = 0;
  std::size_t sender = 0;           // who sent it (for logs and plots; a robot cannot know)
  double time = 0.0;                // s, end of the reception
  Kind kind = Kind::kPacket;
  bool collision = false;           // noise because transmissions overlapped (threshold model),
                                    // or whose loudest disturbance was a packet (acoustic model)
  // Acoustic model: the class the real receiver reports for a packet it fails to decode
  // (zero_byte, one_byte, bad_crc); kNone for packets and in the threshold model.
  nava_modem::RxEvent::Noise noise = nava_modem::RxEvent::Noise::kNone;
  double probability = 1.0;         // acoustic model: the predicted chance of decoding it
  std::vector<std::uint8_t> data;   // empty for noise
  int rate = 0;                     // the rate step the frame went at
  double level_db = 0.0;
  double direction = 0.0;           // rad in the receiver's frame, from its microphone (may be NaN)
  double direction_confidence = 0.0;  // 1 where the microphone gives a direction, 0 where not
  double path_length = 0.0;         // m
};

// A transmission as it starts, with the path it takes to every robot that will hear it.
struct Transmission {
  std::size_t sender = 0;
  double start = 0.0, duration = 0.0;  // s
  std::vector<std::uint8_t> data;
  int rate = 0;                        // the profile's rate step it went at
  std::vector<SoundPath> paths;        // per robot; not reachable for the sender and the deaf
  // Acoustic model: per robot, the chance it decodes the packet as things stand at the start
  // (no other packet in the air); empty with the threshold model.
  std::vector<double> probability;
};

// The simulated audio medium shared by a team: every robot runs the real link's CSMA-CA MAC;
// a packet lasts `packet_bits` bit times, reaches each robot after its travel time along the
// shortest path, raises that robot's carrier while it lasts, and arrives as a packet, or as
// noise when another audible transmission overlapped it at that robot and was not weaker by the
// capture margin (ThresholdReception). A robot does not hear itself, nor anything while it is
// sending. Deterministic for a seed. Time advances in ticks of 1/16 bit.
//
// With an acoustic model (acoustic_model.h, AcousticReception) instead: a packet reaches every
// robot a path reaches, at its direct-plus-reverberant level; each robot's carrier level sums the
// arrivals, the ambient sound and the noise sources sounding; each robot's MAC calibrates its
// threshold on that noise during its calibration time (unless the MAC options fix one), as a real
// robot does; and at the end of an arrival the model's decode table decides, by a draw, whether
// the robot decodes it, reports noise of some class, or hears nothing at all, against the noise
// of that moment and the other packets overlapping it (each weighted by how much it overlaps).
//
// The channel itself is the same for every model (reception_model.h): the ticks, the MACs, the
// transmissions and their arrivals, the overlaps, the skipping of quiet time, the draws.
class AudioChannel {
 public:
  // `acoustic`, when given, must outlive the channel and be built for the same robots in the
  // same order; without it, the propagation model's hearing threshold decides.
  AudioChannel(const PropagationModel& model, std::vector<world_sim::Microphone> microphones,
               const ChannelOptions& options, const AcousticModel* acoustic = nullptr);
  // Any reception model (not null; options.capture_margin_db is then the model's business).
  AudioChannel(const PropagationModel& model, std::vector<world_sim::Microphone> microphones,
               const ChannelOptions& options, std::unique_ptr<ReceptionModel> reception);

  std::size_t size() const { return macs_.size(); }
  void SetPose(std::size_t robot, const grid::Pose2D& pose) {
    poses_.at(robot) = pose;
    positions_stale_ = true;
  }
  const grid::Pose2D& pose(std::size_t robot) const { return poses_.at(robot); }
  // Queues a frame to send, lasting its own airtime; false (and counted by the MAC) when its
  // queue is full. With bytes alone: today's packet (packet_bits at the MAC's bit rate).
  bool Send(std::size_t robot, nava_modem::MacFrame frame);
  bool Send(std::size_t robot, std::vector<std::uint8_t> data);

  // The same, taking effect at simulated `time` (s), or at once if that has passed. A caller
  // that hands over everything stamped up to t before AdvanceTo(t) gets the same run however
  // often it calls AdvanceTo: the outcome depends on the stamps, not on the calls.
  void SetPoseAt(std::size_t robot, const grid::Pose2D& pose, double time);
  // A packet that finds the robot's queue full when it is to enter it is dropped and counted
  // in send_overflows(); false only when a robot has an absurd number waiting to enter.
  bool SendAt(std::size_t robot, nava_modem::MacFrame frame, double time);
  bool SendAt(std::size_t robot, std::vector<std::uint8_t> data, double time);  // today's packet
  // Nothing in the air or on its way, every MAC idle, nothing stamped still to take effect:
  // until a new SendAt() or Send(), AdvanceTo() produces no events (the acoustic model's noise
  // may still move a carrier, which AdvanceTo() then works out as it goes).
  bool Idle() const { return pending_.sends.empty() && Quiet(); }
  // The earliest simulated time (s) after now at which AdvanceTo() may have something to
  // report (a transmission starting, a reception, a carrier changing), unless something new
  // is sent before: a caller may sleep until then and lose nothing (+inf when Idle(); with an
  // acoustic model, a carrier moved by the noise alone while Idle() is not foreseen).
  double NextEventTime() const;

  struct Events {
    std::vector<Transmission> started;
    std::vector<Reception> received;
  };
  // Runs the medium up to `time` (s); what started and what was received meanwhile.
  Events AdvanceTo(double time);

  double time() const { return ticks_ * tick_; }
  double tick_seconds() const { return tick_; }
  double Level(std::size_t robot) const { return levels_.at(robot); }
  bool Carrier(std::size_t robot) const { return macs_.at(robot).carrier(); }
  const nava_modem::CsmaMac& mac(std::size_t robot) const { return macs_.at(robot); }
  std::uint64_t missed_while_sending() const { return counts_.missed_while_sending; }
  std::uint64_t send_overflows() const { return counts_.send_overflows; }
  // Acoustic model: arrivals the receiver would not have noticed at all.
  std::uint64_t unheard() const { return counts_.unheard; }
  const AcousticModel* acoustic() const { return reception_->acoustic(); }
  const ReceptionModel& reception() const { return *reception_; }
  const PathCache& cache() const { return cache_; }
  const VisibilityMemo& memo() const { return memo_; }

 private:
  struct Arrival {
    std::size_t sender;
    std::int64_t start, end;  // ticks
    double level_db;
    double power;  // 10^(level_db / 10), summed every tick the arrival lasts
    std::vector<std::uint8_t> data;
    int rate;
    SoundPath path;
    bool done = false;  // finished, kept a while to judge overlaps with later arrivals
  };
  struct PendingPose {
    std::int64_t tick;
    std::size_t robot;
    grid::Pose2D pose;
  };
  struct PendingSend {
    std::int64_t tick;
    std::size_t robot;
    nava_modem::MacFrame frame;
  };
  // The first tick at or after `time`, never before the current one.
  std::int64_t TickAt(double time) const;
  // Puts into effect what was stamped up to the current tick.
  void ApplyPending();
  // The first tick after the current one at which something must be looked at even in quiet:
  // a stamped send, or the next update of the background.
  std::int64_t NextWake(std::int64_t target) const;
  void StartTransmission(std::size_t sender, nava_modem::MacFrame frame, Events& events);
  // A new arrival at `receiver`: its level and its finishing are looked at then.
  void NoteArrival(std::size_t receiver, std::int64_t start, std::int64_t end);
  void Finish(std::size_t receiver, const Arrival& a, Events& events);
  // Nothing in the air, nothing on its way, nobody with anything to send: ticks change nothing.
  bool Quiet() const;
  // The path from the sender to every robot, from the cache where it can.
  std::vector<SoundPath> PathsFrom(std::size_t sender);
  // The robots' positions, worked out again only after a pose has changed (every reception asks
  // for them, and a big team hears many receptions a pose update).
  const std::vector<Eigen::Vector2d>& Positions();
  // Each robot's background power, worked out again.
  void UpdateBackground();
  // The first tick after the current one at which the background is worked out again, if ever.
  std::int64_t NextBackgroundTick() const;

  const PropagationModel& model_;
  std::unique_ptr<ReceptionModel> reception_;
  // Each robot's background power (linear), worked out again every `ticks` (whole bits; 0: never).
  struct Background {
    std::vector<double> power;
    std::int64_t ticks = 0;
  } background_;
  std::vector<world_sim::Microphone> microphones_;
  ChannelOptions options_;
  std::vector<nava_modem::CsmaMac> macs_;
  std::vector<grid::Pose2D> poses_;
  std::vector<Eigen::Vector2d> positions_;  // of poses_ (Positions)
  bool positions_stale_ = true;
  std::vector<double> levels_;
  std::vector<double> powers_;  // linear power behind each level
  std::vector<std::deque<Arrival>> arrivals_;  // per receiver: pending and recently finished
  std::vector<std::vector<std::pair<std::int64_t, std::int64_t>>> sending_;  // per robot, recent
  // What was stamped to take effect later (SetPoseAt, SendAt), in stamp order.
  struct Stamped {
    std::deque<PendingPose> poses;
    std::deque<PendingSend> sends;
    std::vector<std::size_t> per_robot;  // sends not yet in each robot's queue
  } pending_;
  // Per robot, the next tick its level may change (an arrival starts or ends) and the next tick
  // an arrival of its finishes: between them a tick need not look at its arrivals.
  std::vector<std::int64_t> level_edge_, finish_edge_;
  PathCache cache_;
  VisibilityMemo memo_;
  std::mt19937 rng_;
  // With link_fate: per (sender, listener) pair, where both stood when its draw was made.
  struct Fate {
    bool drawn = false;
    Eigen::Vector2d sender, listener;
    double draw = 0.0;
  };
  std::vector<Fate> fates_;
  // The draw that decides a packet from `sender` at `listener` (each at `at`).
  double DecisionDraw(std::size_t sender, std::size_t listener, const std::vector<Eigen::Vector2d>& at);
  double tick_;
  std::int64_t ticks_ = 0;
  // The longest transmission yet, in ticks: what has finished longer ago than a few of these can
  // no longer overlap anything still to come.
  std::int64_t longest_ticks_ = 0;
  // What the channel counts for its callers (missed_while_sending() and the others).
  struct Counts {
    std::uint64_t missed_while_sending = 0;
    std::uint64_t unheard = 0;
    std::uint64_t send_overflows = 0;
  } counts_;
};

}  // namespace audio_propagation
