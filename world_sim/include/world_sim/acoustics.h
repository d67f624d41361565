#pragma once

// The acoustics of a world: how the rooms reverberate, how loud the building is, and what else
// makes noise. Read from a world file's optional `acoustics` section and used only by the
// `acoustic` channel model (audio_propagation/acoustic_model.h) and the scene renderer; a world
// without the section keeps the thesis's threshold channel.
//
// Levels are in the propagation model's dB scale: a robot's packet is `source_level_db` (70 by
// default) at 1 m, so a noise source of 60 dB at 1 m is 10 dB quieter than a speaker at the
// same distance. Treat the scale as dB SPL and a real room's meter readings carry over.
#include <optional>
#include <string>
#include <vector>

namespace world_sim {

// What a noise sounds like; the receivers suffer each kind differently (speech and a whine hit
// a few tones hard, white and pink noise spread over the band).
// kRecording: a recording of the noise itself (a fan, a corridor, a kitchen), played in a loop.
enum class NoiseKind { kWhite, kPink, kSpeech, kWhine, kRecording };
std::optional<NoiseKind> ParseNoiseKind(const std::string& name);  // white | pink | speech | whine | recording
const char* NoiseKindName(NoiseKind kind);
inline const char* kNoiseKindNames = "white, pink, speech, whine or recording";

// A room's reverberation. The critical distance is where the direct sound and the reverberant
// field are equally loud; beyond it a microphone hears more room than speaker. From Sabine's
// equation for an omnidirectional source it is about 0.057 sqrt(V / RT60) m (V in m^3).
struct RoomAcoustics {
  double rt60 = 0.5;               // s, mid-frequency reverberation time
  double volume = 0.0;             // m^3; used when critical_distance is 0
  double critical_distance = 0.0;  // m; 0 = from volume and rt60
};
// The critical distance in m (given, or from volume and RT60).
double CriticalDistance(const RoomAcoustics& room);

// A named part of the map with its own reverberation (a hall, a corridor), an axis-aligned box
// in world coordinates. Where boxes overlap, the first listed wins.
struct AcousticRegion {
  std::string name;
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;  // m
  RoomAcoustics room;
  bool Contains(double x, double y) const { return x >= min_x && x <= max_x && y >= min_y && y <= max_y; }
};

// Something that makes noise: fixed (a fan, a radio) or carried by a robot (its motors). It
// sounds for the first `duty` x `period` seconds of every period, the periods starting at
// t = phase (mod period).
struct NoiseSourceSpec {
  std::string name;
  double x = 0.0, y = 0.0;  // m, where a fixed source stands
  std::string robot;        // not empty: the source rides on this robot, and x, y are unused
  double level_db = 60.0;   // at 1 m
  NoiseKind kind = NoiseKind::kPink;
  double frequency = 0.0;   // Hz, a whine's fundamental (harmonics at 2x and 3x)
  std::string file;         // a recording's audio file (absolute once loaded from a world file)
  double duty = 1.0;        // fraction of the time it sounds, (0, 1]
  double period = 10.0;     // s
  double phase = 0.0;       // s
};
// Whether the source sounds at simulated time `t`.
bool Sounding(const NoiseSourceSpec& source, double t);
// The fraction of [t0, t1] during which it sounds (whether it sounds at t0 when t1 <= t0).
double SoundingFraction(const NoiseSourceSpec& source, double t0, double t1);
// How long it has been sounding at `t` since it last started: infinity for a source that never
// stops (duty 1), 0 when it is silent at `t`.
double SoundingFor(const NoiseSourceSpec& source, double t);

// A building of coupled rooms (the world file's `acoustics.rooms`): the map is cut into rooms at
// its narrow places (grid/room_segmentation.h), each room keeps its own reverberant field, and the
// fields are coupled through the openings between rooms (audio_propagation/coupled_rooms.h), so
// that a room's reverberation reaches the next room weakened by the doorway. Without it one
// reverberant field fills the whole map, as in the thesis.
struct CoupledRoomsSpec {
  double ceiling_height = 2.7;   // m: a room's volume is its floor area times this
  double door_height = 2.1;      // m: an opening's area is its width times this
  double door_half_width = 0.6;  // m: passages up to twice this wide divide rooms
  double min_room_area = 1.0;    // m^2: smaller pieces join their neighbour
  double max_obstacle_size = 1.0;  // m: free-standing obstacles no longer than this divide no room
  // A room longer along its floor than this many of its mean widths (a corridor) is cut into
  // zones along its length, so that its field falls down it (audio_propagation/room_zones.h);
  // 0 keeps every room one field.
  double corridor_elongation = 3.0;
};

struct Acoustics {
  RoomAcoustics room;                 // everywhere no region covers
  std::vector<AcousticRegion> regions;
  // Coupled rooms, when the world asks for them. A room takes the RT60, volume and critical
  // distance of the region covering most of its floor; a room no region covers takes `room`'s
  // RT60 and its own volume (floor area x ceiling_height).
  std::optional<CoupledRoomsSpec> rooms;
  double ambient_db = 30.0;           // the building's background noise at every listener
  NoiseKind ambient_kind = NoiseKind::kPink;
  double corner_loss_db = 6.0;        // lost by the direct sound at each corner it bends round
  std::vector<NoiseSourceSpec> noise_sources;

  // The reverberation at a point: the first region holding it, else `room`.
  const RoomAcoustics& RoomAt(double x, double y) const;
};

}  // namespace world_sim
