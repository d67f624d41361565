#pragma once

// What a simulated robot hears of the audio channel (audio_channel.h). The channel keeps time,
// runs every robot's MAC, carries each transmission along its paths and keeps track of which
// arrivals overlap at each listener; a reception model says the rest: what the air sounds like
// with nothing in it, how loud an arrival is at a listener (if it is heard at all), what a
// robot's level meter reads, and whether a finished arrival is decoded, given what overlapped it.
// Two models: the thesis's hearing threshold with its capture margin (ThresholdReception) and the
// world's acoustics with the profile's decode table (AcousticReception: acoustic_reception.h,
// threshold_reception.h). No ROS.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/propagation_model.h"
#include "nava_modem/csma_mac.h"
#include "nava_modem/packet_receiver.h"

namespace audio_propagation {

class AcousticModel;

// Another arrival at the same listener that overlapped the one being decided.
struct Overlap {
  double level_db = 0.0;
  // Its power (linear) averaged over the decided arrival: its own power times the share of the
  // decided arrival's length it overlapped (above 0).
  double mean_power = 0.0;
};

// A transmission's sound at one listener, as it starts.
struct ArrivalSound {
  // The chance the listener decodes it with no other packet in the air (models that predict).
  std::optional<double> probability;
  // Its level, dB; none for a sound the listener's carrier and decisions would not notice.
  std::optional<double> level_db;
};

// How a finished arrival was received: a packet, noise of a class, or nothing noticed at all.
struct Decision {
  bool heard = true;   // false: the receiver would not have noticed it (nothing reported)
  bool packet = false;
  bool collision = false;  // noise from overlapping transmissions (see Reception::collision)
  nava_modem::RxEvent::Noise noise = nava_modem::RxEvent::Noise::kNone;
  double probability = 1.0;  // the model's predicted chance of decoding it
};

class ReceptionModel {
 public:
  virtual ~ReceptionModel() = default;
  // The carrier threshold every robot's MAC uses; none where each robot calibrates its own on
  // the noise it hears, as a real robot does.
  virtual std::optional<double> CarrierThresholdDb() const = 0;
  // How often (s) the air's own sound is worked out again (Background); 0 for silent air.
  virtual double BackgroundSeconds() const = 0;
  // Each robot's background power (linear) at `time`, the robots standing at `at`.
  virtual void Background(double time, const std::vector<Eigen::Vector2d>& at, std::vector<double>& powers) const = 0;
  // What a robot's level meter reads (dB) for the linear power in the air, background included.
  virtual double LevelDb(double power) const = 0;
  // Whether a robot whose air holds `power` (of which `background` is its background) at level
  // `level_db` hears nothing its MAC could react to: ticks may then be skipped.
  virtual bool Quiet(double power, double background, double level_db, const nava_modem::CsmaMac& mac) const = 0;
  // Whether Arrive gives each listener a probability (Transmission::probability).
  virtual bool Predicts() const = 0;
  // The sound at robot `listener` of a transmission that starts at `time` along `path`, every
  // robot standing at `at`.
  virtual ArrivalSound Arrive(const SoundPath& path, std::size_t listener, const std::vector<Eigen::Vector2d>& at,
                              double time) const = 0;
  // The fate of an arrival at robot `listener` from `start` to `end` (s) at `level_db` along
  // `path`, given the others that overlapped it there (in the order they arrived), every robot
  // at `at`. `draw` gives a uniform number in [0, 1) where chance decides; it is called at most
  // once.
  virtual Decision Decide(const SoundPath& path, std::size_t listener, double level_db, double start, double end,
                          const std::vector<Overlap>& overlaps, const std::vector<Eigen::Vector2d>& at,
                          const std::function<double()>& draw) const = 0;
  // The acoustic model behind the decisions, if there is one.
  virtual const AcousticModel* acoustic() const { return nullptr; }
};

}  // namespace audio_propagation
