#pragma once

// nava_bench's command line (nava_bench.cpp), parsed apart from the
// tool so that tests and the fuzzer can call it. Each mode reads its own flags and refuses the
// rest.
#include <string>
#include <vector>

#include "modem_args.h"
#include "nava_modem/room_channel.h"

namespace nava_modem::tools {

// nava_bench [--profile P] ...: packets in white noise against the SNR.
struct WhiteNoiseRequest {
  int packets = 60;
  unsigned seed = 1;
  int snr_min = -12, snr_max = 0;
  std::string dir;        // "" for a new folder in /tmp
  std::string minimodem;  // "" for not run (--minimodem none, or a profile minimodem cannot decode)
  ToolModem modem;
};

// nava_bench --rooms: packets under each room condition, and delivery against DRR; with
// --rir-dir, also through each measured response in a folder (every file and channel a room).
struct RoomsRequest {
  int packets = 60, plot_packets = 30, rooms_per_row = 6;
  std::string rir_dir;       // "" for no measured rows
  int rir_packets = 20;      // per measured room and condition
  bool measured_only = false;  // --measured-only: no rendered rows, no plot
  std::vector<double> drier;   // --drier: DRRs (dB) each measured room is also made drier to
  // The delivery-against-DRR curve: its reverberation times (--curve-rt60), its DRRs from +12 dB
  // down to --curve-drr-min in steps of 3, its white noise (--curve-snr) and room model (--response).
  std::vector<double> curve_rt60 = {0.3, 0.6, 1.0};
  double curve_drr_min = -15.0, curve_snr_db = 40.0;
  RoomOptions::Model curve_model = RoomOptions::Model::kStatistical;
  unsigned seed = 1;
  std::string dir, minimodem, plot;  // dir "" for a new folder; minimodem "" for not run; plot "" for DIR/delivery_vs_drr.png
  std::vector<Profile> profiles;
  ModemOptions options;
};

// nava_bench --doa: directions of arrival from microphone arrays.
struct DoaRequest {
  int packets = 100;
  unsigned seed = 1;
  std::string dir, plot;  // plot "" for DIR/doa_polar.png
  ModemOptions options;
};

// nava_bench --direction: the arrays' direction errors by RT60 and DRR (direction_table.h).
struct DirectionRequest {
  int packets = 40;  // per cell and array
  int min_decoded = 10;   // more are sent until this many are decoded...
  int max_packets = 1000;  // ...or this many sent
  unsigned seed = 1;
  double snr_db = 20.0;  // white noise, full band, per microphone
  std::vector<double> rt60 = {0.3, 0.6, 1.0, 2.0};
  std::vector<double> drr_db = {-15.0, -9.0, -3.0, 3.0, 9.0};
  std::string binaural_dir;  // "" for no measured check
  std::string errors_out;    // "" for no table
  int threads = 2;
  Profile profile = Profile::kRoom;
  ModemOptions options;
};

// nava_bench --arrival --rir-dir DIR: first arrivals of room packets through measured responses.
struct ArrivalRequest {
  std::string rir_dir;
  int packets = 10;         // per room
  double snr_db = 10.0;     // white noise, full band
  double min_drr_db = -8.0;  // rooms below this DRR are listed, not counted in the targets
  unsigned seed = 1;
  Profile profile = Profile::kRoom;  // the targets are the room profile's
  // --errors-out FILE: the signed errors' quantiles over the counted rooms, the table the
  // simulation's ranging draws from (audio_propagation/arrival_errors_file.h); "" for none.
  std::string errors_out;
  ModemOptions options;
};

// nava_bench --likeness --rir-dir DIR: measured rooms' features beside the renderer's
// measured-like rooms at the same RT60 and DRR.
struct LikenessRequest {
  std::string rir_dir;
  int rooms = 5;  // measured-like rooms drawn per measured one (seeds seed, seed + 1, ...)
  unsigned seed = 1;
  double sample_rate = 48000.0;
};

// nava_bench --splice --early A.wav[:K] --late B.wav[:K] --at-ms LIST --out DIR: two responses
// spliced at each time after their direct sounds (response_splice.h).
struct SpliceRequest {
  std::string early, late;  // path[:channel]
  std::vector<double> at_ms;
  std::string out_dir;
  double sample_rate = 48000.0;
};

// nava_bench --link-cost: what timing packets for ranging adds to a link's CPU.
struct LinkCostRequest {
  double seconds = 120.0;  // of audio
  double period = 6.0;     // s between one robot's packets
  int runs = 3;
  Profile profile = Profile::kRoom;
  ModemOptions options;
};

// nava_bench --frames --rir-dir DIR: frames of any length at each rate through measured responses.
struct FramesRequest {
  std::string rir_dir;
  std::string noise_file;  // a recording heard at snr_db too ("" for white noise alone)
  int bytes = 64;          // data bytes a frame
  int frames = 20;         // per room-ear, condition and rate (--count)
  double snr_db = 10.0;    // full band, of the white noise and the recording
  std::vector<int> speeds;  // the rate steps to run (all of the profile's when empty)
  unsigned seed = 1;
  int threads = 2;
  Profile profile = Profile::kRoom;
  ModemOptions options;
};

struct NavaBenchOptions {
  enum class Mode { kWhiteNoise, kRooms, kDoa, kArrival, kLikeness, kSplice, kLinkCost, kFrames, kDirection };
  Mode mode = Mode::kWhiteNoise;
  WhiteNoiseRequest white;  // the mode's request; the others stay at their defaults
  RoomsRequest rooms;
  DoaRequest doa;
  ArrivalRequest arrival;
  LikenessRequest likeness;
  SpliceRequest splice;
  LinkCostRequest link_cost;
  FramesRequest frames;
  DirectionRequest direction;
  multirobot_audio::tools::ToolUsage usage;  // to refuse what turns out wrong while running
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
NavaBenchOptions ParseNavaBenchArgs(const std::vector<std::string>& words);

}  // namespace nava_modem::tools
