#pragma once

// What audio_scene_render and audio_channel_validate share: a world with acoustics, its
// propagation model with every path, the profile's decode table and, when the world has speech,
// speech made by make_speech.sh. Bad input ends the program with one line naming the file, the
// field or the flag and the value.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "audio_propagation/channel_validation.h"
#include "audio_propagation/decode_table.h"
#include "bench_support/speech.h"
#include "grid/input_error.h"
#include "measured_rooms.h"
#include "nava_modem/moved_rooms.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"
#include "tool_args/tool_args.h"
#include "world_sim/world_file.h"

namespace audio_propagation::tools {

struct AcousticWorld {
  std::string file;
  world_sim::LoadedWorld loaded;
  world_sim::Acoustics acoustics;
  std::vector<std::string> robots;
  std::vector<Eigen::Vector2d> resting;  // the robots' world poses
  std::unique_ptr<PropagationModel> propagation;
};

[[noreturn]] inline void Fail(const std::string& program, const std::string& line) {
  std::cerr << program << ": " << line << "\n";
  std::exit(1);
}

// The world, which must have an acoustics section, and its propagation model (every path: the
// tools judge far links themselves).
inline AcousticWorld LoadAcousticWorld(const std::string& program, const std::string& file, const std::string& map) {
  AcousticWorld w;
  w.file = file;
  try {
    w.loaded = world_sim::LoadWorldFile(file, map);
  } catch (const std::exception& e) {
    Fail(program, e.what());
  }
  if (!w.loaded.config.acoustics) Fail(program, file + ": acoustics: missing; expected the world's acoustics section");
  w.acoustics = *w.loaded.config.acoustics;
  for (const world_sim::RobotSpec& r : w.loaded.config.robots) {
    w.robots.push_back(r.name);
    w.resting.push_back(r.start.position());
  }
  const grid::OccupancyMap& m = w.loaded.map;
  try {
    w.propagation = std::make_unique<PropagationModel>(m, ValidationPropagation(m.width_m() + m.height_m(), 2));
  } catch (const std::exception& e) {
    Fail(program, file + ": " + e.what());
  }
  return w;
}

// The profile's table: `path`, or the shipped one.
inline DecodeTable LoadTable(const std::string& program, nava_modem::Profile profile, const std::string& path) {
  const std::string name = nava_modem::ProfileName(profile);
  const std::string file = path.empty() ? ShippedDecodeTable(name) : path;
  try {
    return LoadDecodeTable(file, name);
  } catch (const std::exception& e) {
    Fail(program, std::string(e.what()) + (path.empty() ? " (the shipped table; --table FILE gives another)" : ""));
  }
}

inline bool HasSpeech(const world_sim::Acoustics& a) {
  if (a.ambient_kind == world_sim::NoiseKind::kSpeech) return true;
  for (const world_sim::NoiseSourceSpec& s : a.noise_sources) {
    if (s.kind == world_sim::NoiseKind::kSpeech) return true;
  }
  return false;
}

// The measured rooms a table measured over them (rooms: measured) renders its links through:
// those of `rir_dir` (DIR[,DIR...], a tool's --rir-dir) at `rate`; null for a table over rendered
// rooms. Fails the tool through `usage` for such a table without them, and for measured rooms
// given with a table that was not measured over them.
inline std::shared_ptr<const nava_modem::MovedRooms> MeasuredRoomsFor(const DecodeTable& table, const std::string& rir_dir,
                                                                       double rate,
                                                                       const multirobot_audio::tools::ToolUsage& usage) {
  if (table.rooms != nava_modem::RoomOptions::Model::kMeasured) {
    if (!rir_dir.empty()) {
      usage.Fail("--rir-dir: the " + table.profile + " table was measured over " + nava_modem::RoomModelName(table.rooms) +
                 " rooms; expected no measured rooms");
    }
    return nullptr;
  }
  if (rir_dir.empty()) {
    usage.Fail("the " + table.profile + " table was measured over measured rooms (rooms: measured): expected them, "
               "--rir-dir DIR[,DIR...]");
  }
  try {
    return std::make_shared<const nava_modem::MovedRooms>(nava_modem::tools::MovableRooms(rir_dir, rate, usage), rate);
  } catch (const std::invalid_argument& e) {
    usage.Fail(std::string("--rir-dir: ") + e.what());
  }
}

// 240 s of make_speech.sh's speech at `rate` (nothing when the world has none).
inline std::vector<float> SpeechFor(const std::string& program, const world_sim::Acoustics& a, double rate,
                                    unsigned seed) {
  if (!HasSpeech(a)) return {};
  char folder[] = "/tmp/audio_speech.XXXXXX";
  if (!mkdtemp(folder)) Fail(program, "cannot make a folder in /tmp for the speech");
  std::vector<float> speech = nava_modem::ReadAudioAt(bench_support::MakeSpeech(folder, seed), rate);
  std::filesystem::remove_all(folder);
  return speech;
}

}  // namespace audio_propagation::tools
