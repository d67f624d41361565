#pragma once

// The measured rooms of a folder of impulse responses (nava_bench --rir-dir): every channel of
// every audio file a room, with its figures in the modems' band.
#include <string>
#include <vector>

#include "nava_modem/measured_response.h"
#include "nava_modem/moved_rooms.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// One measured room: a channel of a response file, with its figures in the modems' band.
struct MeasuredRoom {
  std::string name;  // file name, and ":K" for channel K of a file with several
  std::string path;
  int channel = 0;
  ResponseMeasures figures;
};

// Every channel of every audio file in `dir` (sorted by name), each a room; other files (a
// README) are passed over. A folder without audio files, or a file that cannot serve, fails the
// tool through `usage`, naming it.
std::vector<MeasuredRoom> MeasuredRooms(const std::string& dir, const multirobot_audio::tools::ToolUsage& usage);

// The rooms of every folder of `dirs` (comma-separated: a --rir-dir that takes several), in turn.
std::vector<MeasuredRoom> MeasuredRoomsIn(const std::string& dirs, const multirobot_audio::tools::ToolUsage& usage);

// The rooms of every folder of `dirs` (comma-separated, as MeasuredRoomsIn), loaded at
// `sample_rate` to be moved (moved_rooms.h), grouped by RoomOfFile; a room without its figures
// (ResponseProblem) fails the tool through `usage`, naming it.
// The room a response file was measured in, by its name: the name without its extension, cut
// before the first "_"-separated part that holds a digit or a sign (a seat, a position, a head
// angle: pori_s1_r2_b -> pori, warehouse_7_4 -> warehouse,
// brir_sweep_Netzwerkakademie_headaz+40 -> brir_sweep_Netzwerkakademie), in its folder.
std::string RoomOfFile(const std::string& path);

std::vector<MovableRoom> MovableRooms(const std::string& dirs, double sample_rate,
                                      const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
