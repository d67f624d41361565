#pragma once

// The scene renderer: what each robot's microphone hears while robots move and send packets in
// a world with acoustics, as waveforms the real receivers can decode. It is how the `acoustic`
// channel model (acoustic_model.h) is validated (audio_channel_validate), not how it runs. No ROS.
//
// For each listener, over the scene's time:
//  - each packet sent by another robot: the profile's modulated packet through RenderRoom
//    (nava_modem/room_channel.h) with the RT60 of the listener's room and the link's DRR from
//    AcousticModel::Levels on the shortest path at send time (clamped to RenderRoom's +-40 dB),
//    in a room of the kind the model's table was measured over (DecodeTable::rooms; a
//    measured-like room at the path's length, its direct sound moved to the travel time) where
//    the path has no corner, and round a corner and from a robot to itself in the statistical
//    room (a measured-like room is a sender and a listener in one room, and draws the
//    transducers' colouring anew for each packet),
//    scaled so that its signal power (room_channel.h's definition: the mean square over the
//    samples where the clean packet sounds) is the link's total (direct plus reverberant) level,
//    and delayed by the path's travel time. A robot does not hear its own packets (it is sending).
//    The path, levels and reverberation stay as they were at send time for the whole packet.
//  - the ambient noise, of its kind, at the ambient level, all the time;
//  - each noise source while it sounds (world_sim::Sounding), of its kind (white, pink, speech,
//    a motor whine at its frequency), at the level AcousticModel::SourceLevelDb gives it at the
//    listener (recomputed every `level_step` s as robots move, linear in dB between).
// Noise is not reverberated (its level already counts its reverberant field), as in the decode
// tables' recordings; each disturbance has mean power 1 before its level is applied (speech:
// over the whole speech recording, pauses included), so the packet's signal power over the sum of
// the disturbances' powers is exactly the SNR of decode_table.h, the one the model computes
// (for a whine, the model then weighs the power by how much of it falls in the profile's band).
//
// Levels: the model's dB scale (dB SPL) maps to linear power with one reference: a mean square
// of 1 (0 dBFS power) is kReferenceDb. A robot's 70 dB packet then has an RMS of 0.03, and a 35 dB
// ambient an RMS of 0.0006; the renderer never clips or normalises (write float WAV).
//
// Scene files (YAML); every time is simulated time in s (the noise sources' duty cycles run on
// it), the first sample is at `start`:
//   profile: nava                # nava | room (the modem that sends the packets)
//   start: 0.0                   # optional, default 0
//   duration: 6.0                # s, above 0
//   robots:                      # robots of the world, each with keyframes [t, x, y, yaw]
//     robot_0: [[0.0, 2.0, 6.75, 0.0], [5.0, 4.0, 6.75, 0.0]]   # t ascending; linear between,
//     robot_1: [[0.0, 12.0, 6.75, 3.1416]]                         # held before and after
//   packets:
//     - {time: 0.5, sender: robot_0, data: [1, 2, 3, 4]}           # 4 bytes, 0-255
//   own_packets: true            # optional (default false): each robot hears its own packets
//   self_distance: 0.15          # optional, m from a robot's speaker to its microphone
//   sound_cards:                 # optional, per robot (default: an ideal card)
//     robot_0: {rate_ppm: 40, latency: 0.012}
// Robots of the world not in the scene stand at their world pose (carrying any motors they
// have) and are not rendered.
//
// Sound cards, for ranging: a robot's card plays each of its packets `latency` s after the
// scene's time for it (the playback latency no robot knows), and samples at its own rate,
// (1 + rate_ppm / 10^6) times the nominal: a listener's recording starts at the scene's start and
// its sample i is at true time start + i / (rate (1 + rate_ppm / 10^6)); a packet reaches it
// stretched by the ratio of the two cards' rates (RoomOptions::clock_offset). With own_packets a
// robot hears its own packets through a direct path of self_distance m in its room (as a real
// robot's microphone hears its speaker), which two-way ranging times them by.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/acoustic_model.h"
#include "grid/occupancy_map.h"
#include "grid/pose2d.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/moved_rooms.h"

namespace audio_propagation {

constexpr double kReferenceDb = 100.0;  // the level of a mean square of 1
double LevelToPower(double db);          // 10^((db - kReferenceDb) / 10)

struct SceneKeyframe {
  double t = 0.0, x = 0.0, y = 0.0, yaw = 0.0;
};
struct SceneRobot {
  std::string name;
  std::vector<SceneKeyframe> keyframes;  // t ascending, at least one
};
struct ScenePacket {
  double time = 0.0;  // s, when the sender starts it
  std::string sender;
  std::array<std::uint8_t, 4> data{};
};
struct SceneSoundCard {
  double rate_error = 0.0;  // its clock over true time, minus 1 (rate_ppm / 10^6)
  double latency = 0.0;     // s from the scene's time of a packet to its first sample leaving the speaker
};
struct Scene {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  double start = 0.0, duration = 0.0;  // s
  std::vector<SceneRobot> robots;      // in file order
  std::vector<ScenePacket> packets;
  bool own_packets = false;
  double self_distance = 0.15;  // m
  std::map<std::string, SceneSoundCard> sound_cards;  // by robot; absent: ideal
  // A robot's card (ideal when it has none given).
  SceneSoundCard CardOf(const std::string& robot) const;
};

// A robot's pose at `t`: linear between keyframes (yaw the short way round), held before the
// first and after the last.
grid::Pose2D PoseAt(const SceneRobot& robot, double t);

// Reads a scene file. Throws grid::InputError naming the file, the field and the value: a
// missing or malformed field, an unknown profile, keyframes out of order, a packet whose sender
// is not in the scene or whose time is outside the scene, data that is not 4 bytes of 0-255.
Scene LoadScene(const std::string& path);
// Checks a scene against a world: every robot is one of `world_robots` and every keyframe stands
// in the map's free space. Throws grid::InputError naming `file` and the field.
void CheckScene(const std::string& file, const Scene& scene, const std::vector<std::string>& world_robots,
                const grid::OccupancyMap& map);

// One packet heard at one listener: what the model predicts (the figures the channel would use:
// the path at send time, NoiseDuring the arrival) and where it lies in the listener's recording.
struct PacketHearing {
  std::size_t packet = 0;  // index into Scene::packets
  std::string listener;
  bool reachable = false;      // a path exists; when false nothing else is set
  double arrival = 0.0;        // s of simulated time the direct sound starts (the sender's latency included)
  // The same instant on the listener's sound-card clock: s from its recording's first sample.
  double arrival_clock = 0.0;
  double path_length = 0.0;    // m (self_distance for a robot's own packet)
  int corners = 0;             // the path's corners
  std::size_t first_sample = 0;  // of the arrival in the recording (it may start before the scene)
  bool in_scene = false;       // the arrival starts within the recording
  double travel_time = 0.0;    // s
  LinkPrediction prediction;
  // The powers in the rendering (linear, kReferenceDb scale), by decode_table.h's definitions:
  double signal_power = 0.0;   // the packet's, over its sounding samples
  double noise_power = 0.0;    // the rendered noise's mean square during the packet's airtime
  // The disturbances the model counts (NoiseDuring the arrival), summed unweighted (dB): what
  // the rendered noise's level should be, but for moving robots and short-term changes in speech.
  double model_noise_db = 0.0;
};

struct ListenerRecording {
  std::string robot;
  std::vector<float> packets;  // the packets alone
  std::vector<float> noise;    // the ambient and the noise sources alone
  std::vector<float> Mix() const;  // what the microphone hears: the two summed
};

struct SceneRendering {
  double sample_rate = 0.0;
  std::vector<ListenerRecording> listeners;  // in the scene's robot order
  std::vector<PacketHearing> hearings;       // by packet, then listener
};

struct SceneRenderOptions {
  double sample_rate = 48000.0;
  std::uint32_t seed = 1;    // rooms, noise and whines
  double level_step = 0.1;   // s between noise levels recomputed for moving robots
  // Speech at sample_rate (make_speech.sh's) for speech sources and a speech ambient; needed
  // only when there are such.
  std::vector<float> speech;
  // Measured rooms at sample_rate, for a model whose table was measured over them (rooms:
  // measured): each link's room is one of them moved to the link's RT60 and DRR
  // (nava_modem::MovedRooms). Needed only for such a table.
  std::shared_ptr<const nava_modem::MovedRooms> measured_rooms;
};

// Throws std::invalid_argument naming the field and its value: a sample rate the modems run at
// (nava_modem::ValidateSampleRate), level_step above 0 s.
void ValidateOptions(const SceneRenderOptions& options);

class SceneRenderer {
 public:
  // `robot_names` and `resting` (their positions when not in a scene) are the team the model was
  // built with. Reads the world's recorded noise sources. Throws std::invalid_argument for
  // impossible options (ValidateOptions), names and positions of different lengths, a
  // recording that cannot be read (naming the source and its file), or a table measured over
  // measured rooms without them (or with them at another sample rate).
  SceneRenderer(const AcousticModel& model, std::vector<std::string> robot_names, std::vector<Eigen::Vector2d> resting,
                SceneRenderOptions options);

  // Renders the listeners among the scene's robots (`listeners` empty: all of them). Throws
  // std::invalid_argument for a robot not in the team, a listener not in the scene, a scene
  // whose profile is not the model's table's, or speech to render without
  // SceneRenderOptions::speech.
  SceneRendering Render(const Scene& scene, const std::vector<std::string>& listeners = {}) const;

  const AcousticModel& model() const { return model_; }

 private:
  // Every team robot's position at `t`.
  std::vector<Eigen::Vector2d> Positions(const Scene& scene, const std::vector<int>& scene_robot, double t) const;
  // The unit-power waveform of a disturbance of `kind` (frequency for a whine; `recording`, at the
  // scene's rate, for a recording), `n` samples.
  std::vector<double> Waveform(world_sim::NoiseKind kind, double frequency, std::size_t n, std::uint32_t seed,
                               const std::vector<float>& recording = {}) const;

  const AcousticModel& model_;
  std::vector<std::string> robot_names_;
  std::vector<Eigen::Vector2d> resting_;
  SceneRenderOptions options_;
  double speech_power_ = 0.0;
  std::vector<std::vector<float>> recordings_;  // per noise source: a recording's samples, else empty
};

}  // namespace audio_propagation
