#include "measured_rooms.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "nava_modem/wav_file.h"

namespace nava_modem::tools {

using multirobot_audio::tools::ToolUsage;

std::vector<MeasuredRoom> MeasuredRooms(const std::string& dir, const ToolUsage& usage) {
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && (ext == ".wav" || ext == ".flac" || ext == ".aif" || ext == ".aiff")) {
      files.push_back(entry.path().string());
    }
  }
  if (error) usage.Fail("--rir-dir " + dir + ": " + error.message());
  if (files.empty()) usage.Fail("--rir-dir " + dir + ": no audio files (.wav, .flac, .aif): expected impulse responses");
  std::sort(files.begin(), files.end());
  std::vector<MeasuredRoom> rooms;
  for (const std::string& path : files) {
    MultiAudio audio;
    try {
      audio = ReadAudioChannels(path);
    } catch (const std::exception& e) {
      usage.Fail(std::string("--rir-dir: ") + e.what());
    }
    const int channels = static_cast<int>(audio.channels.size());
    for (int c = 0; c < channels; ++c) {
      MeasuredRoom room;
      room.path = path;
      room.channel = c;
      room.name = std::filesystem::path(path).filename().string() + (channels > 1 ? ":" + std::to_string(c) : "");
      try {
        room.figures = MeasureResponse(LoadImpulseResponse(path, c, audio.sample_rate), audio.sample_rate);
      } catch (const std::exception& e) {
        usage.Fail(std::string("--rir-dir: ") + path + " channel " + std::to_string(c) + ": " + e.what());
      }
      rooms.push_back(room);
    }
  }
  return rooms;
}

std::vector<MeasuredRoom> MeasuredRoomsIn(const std::string& dirs, const ToolUsage& usage) {
  std::vector<MeasuredRoom> rooms;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t comma = std::min(dirs.find(',', start), dirs.size());
    const std::string dir = dirs.substr(start, comma - start);
    if (dir.empty()) usage.Fail("--rir-dir " + dirs + ": an empty folder name; expected DIR[,DIR...]");
    for (MeasuredRoom& room : MeasuredRooms(dir, usage)) rooms.push_back(std::move(room));
    start = comma + 1;
  }
  return rooms;
}

std::string RoomOfFile(const std::string& path) {
  const std::filesystem::path file(path);
  const std::string stem = file.stem().string();
  std::string room;
  std::size_t start = 0;
  while (start < stem.size()) {
    const std::size_t end = std::min(stem.find('_', start), stem.size());
    const std::string part = stem.substr(start, end - start);
    if (start > 0 && part.find_first_of("0123456789+-") != std::string::npos) break;
    room += (start > 0 ? "_" : "") + part;
    start = end + 1;
  }
  return (file.parent_path() / room).string();
}

std::vector<MovableRoom> MovableRooms(const std::string& dirs, double sample_rate, const ToolUsage& usage) {
  std::vector<MovableRoom> movable;
  for (const MeasuredRoom& room : MeasuredRoomsIn(dirs, usage)) {
    if (const auto problem = ResponseProblem(room.figures)) usage.Fail(room.path + ": " + room.name + " is " + *problem);
    MovableRoom m;
    m.name = room.name;
    m.group = RoomOfFile(room.path);
    m.response = LoadImpulseResponse(room.path, room.channel, sample_rate);
    movable.push_back(std::move(m));
  }
  return movable;
}

}  // namespace nava_modem::tools
