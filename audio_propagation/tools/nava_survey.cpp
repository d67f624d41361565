// nava_survey: a survey of a building with the robots themselves. One robot records another's
// `room` packets; from each packet it decodes (the sent waveform is then known) the link's
// impulse response is estimated (nava_modem/response_survey.h), and from it the room's figures.
//
//   nava_survey [--profile room] [--channel K] [--distance M [--source-level-db 70]
//               [--world-out FILE.yaml]] [--response-out FILE.wav] RECORDING.wav...
//   nava_survey [--channel K] --building SURVEY.yaml --world-out FILE.yaml
//   nava_survey --write-train FILE.wav [--packets 10] [--gap 0.5] [--rate 48000] [--seed 1]
//
// --building surveys a building room by room (survey_building.h: each room's box on the map,
// the robots' distance and its recordings): a JSON line per recording with its "room", and
// --world-out writes an acoustics section with the building's mean figures, a region per room
// (its RT60 and critical distance; its ambient level in a comment) and a rooms section, so that
// the acoustic model couples the rooms (audio_link.md, coupled rooms).
//
// --write-train writes what the sending robot plays: room packets of random data with silences
// drawn from 0.5 to 1.5 times --gap between them (a train at a fixed period would let the
// estimate confuse a tap with one a period later).
//
// One JSON line per recording: "rt60_s" and "drr_db" (the definitions of the measured rooms'
// README: T30 in 600-5400 Hz; the energy within 2.5 ms of the direct peak over the energy after
// it), "noise_db" and "noise_bands_db" (what the packets do not explain, in 600-5400 Hz and in
// the room profile's twelve 400 Hz sub-bands, dB of full scale), "noise_kind" (white or pink,
// whichever slope fits the bands), "snr_db" (in band), and the packets used. With --distance
// (the robots' distance while recording) also "critical_distance_m" and "ambient_db" (the noise
// over the whole band in the worlds' dB scale, the sender's level at 1 m being
// --source-level-db); --world-out writes the acoustics section a world file needs, from the
// recordings' mean figures. A recording with no decodable packet, or one that is unreadable,
// exits 1 with one line naming it.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "acoustic_world.h"
#include "audio_propagation/acoustic_model.h"
#include "audio_propagation_args.h"
#include "nava_modem/response_survey.h"
#include "nava_modem/wav_file.h"
#include "survey_building.h"
#include "tool_args/json_text.h"

namespace {

using multirobot_audio::tools::JsonNumber;
using multirobot_audio::tools::JsonString;
constexpr const char* kProgram = "nava_survey";

// The slope of the sub-bands' levels, dB per octave, least squares: 0 for white noise, -3 for pink.
double SlopePerOctave(const std::array<double, nava_modem::kSurveyBands>& db) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  const double n = static_cast<double>(db.size());
  for (std::size_t b = 0; b < db.size(); ++b) {
    const double x = std::log2(800.0 + 400.0 * static_cast<double>(b));  // the band's centre, Hz
    sx += x, sy += db[b], sxx += x * x, sxy += x * db[b];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The share of a noise's power (over 20 Hz to `nyquist`) that lies in 600-5400 Hz, dB: white
// noise spreads evenly over frequency, pink evenly over octaves.
double InBandShareDb(bool pink, double nyquist) {
  const double lo = nava_modem::kResponseBandLowHz, hi = nava_modem::kResponseBandHighHz;
  const double share = pink ? std::log(hi / lo) / std::log(nyquist / 20.0) : (hi - lo) / nyquist;
  return 10.0 * std::log10(share);
}

struct Survey {
  double rt60 = 0.0, drr = 0.0, critical_distance = 0.0, ambient = 0.0;
  bool pink = false;
};

// `room`: the building survey's room the recording was made in ("" outside one).
Survey SurveyOne(const audio_propagation::tools::SurveyArgs& a, const std::string& file, const std::string& room = "") {
  using audio_propagation::tools::Fail;
  nava_modem::Audio audio;
  try {
    if (a.channel) {
      const nava_modem::MultiAudio all = nava_modem::ReadAudioChannels(file);
      if (*a.channel >= static_cast<int>(all.channels.size())) {
        Fail(kProgram, file + ": channel " + std::to_string(*a.channel) + " asked for: the file has " +
                           std::to_string(all.channels.size()));
      }
      audio.samples = all.channels[static_cast<std::size_t>(*a.channel)];
      audio.sample_rate = all.sample_rate;
    } else {
      audio = nava_modem::ReadAudioFile(file);
    }
  } catch (const std::exception& e) {
    Fail(kProgram, std::string(e.what()) + " (expected a recording of room packets)");
  }
  nava_modem::SurveyResult r;
  try {
    r = nava_modem::SurveyResponse(audio.samples, audio.sample_rate,
                                   nava_modem::FindSurveyPackets(audio.samples, audio.sample_rate));
  } catch (const std::exception& e) {
    Fail(kProgram, file + ": " + e.what());
  }
  // Written first, so that a response that cannot give its figures can still be looked at.
  if (!a.response_out.empty()) nava_modem::WriteFloatWavFile(a.response_out, r.response, audio.sample_rate);
  if (const auto problem = nava_modem::ResponseProblem(r.figures)) {
    Fail(kProgram, file + ": the response estimated from " + std::to_string(r.packets.size()) + " packets is " + *problem);
  }

  Survey s;
  s.rt60 = r.figures.rt60_s;
  s.drr = r.figures.drr_db;
  const double slope = SlopePerOctave(r.band_noise_db);
  s.pink = slope < -1.5;
  std::string bands;
  for (double db : r.band_noise_db) bands += (bands.empty() ? "" : ", ") + JsonNumber(db, 1);
  std::string placed;
  if (a.distance) {
    s.critical_distance = audio_propagation::CriticalDistanceFromDrr(s.drr, *a.distance, s.rt60);
    // The direct sound stands for the sender's level less spreading over the distance.
    const double in_band = a.source_level_db - 20.0 * std::log10(*a.distance) + (r.noise_db - r.direct_db);
    s.ambient = in_band - InBandShareDb(s.pink, audio.sample_rate / 2.0);
    placed = ", \"distance_m\": " + JsonNumber(*a.distance, 2) + ", \"critical_distance_m\": " +
             JsonNumber(s.critical_distance, 2) + ", \"ambient_db\": " + JsonNumber(s.ambient, 1);
  }
  if (!room.empty()) placed += ", \"room\": " + JsonString(room);
  std::printf("{\"file\": %s, \"packets\": %zu, \"undecoded\": %zu, \"rt60_s\": %s, \"drr_db\": %s, \"noise_db\": %s, "
              "\"noise_bands_db\": [%s], \"noise_slope_db_per_octave\": %s, \"noise_kind\": \"%s\", "
              "\"signal_db\": %s, \"snr_db\": %s%s}\n",
              JsonString(file).c_str(), r.packets.size(), r.undecoded, JsonNumber(s.rt60, 3).c_str(), JsonNumber(s.drr, 2).c_str(),
              JsonNumber(r.noise_db, 1).c_str(), bands.c_str(), JsonNumber(slope, 2).c_str(), s.pink ? "pink" : "white",
              JsonNumber(r.signal_db, 1).c_str(), JsonNumber(r.signal_db - r.noise_db, 1).c_str(), placed.c_str());
  std::fflush(stdout);
  return s;
}

// The mean of surveys: RT60 and critical distance as numbers, the ambient as power, the noise's
// kind by the majority.
Survey Mean(const std::vector<Survey>& surveys) {
  Survey mean;
  int pink = 0;
  double power = 0.0;
  for (const Survey& s : surveys) {
    mean.rt60 += s.rt60 / surveys.size();
    mean.critical_distance += s.critical_distance / surveys.size();
    power += std::pow(10.0, s.ambient / 10.0) / surveys.size();
    pink += s.pink ? 1 : 0;
  }
  mean.ambient = 10.0 * std::log10(power);
  mean.pink = 2 * pink > static_cast<int>(surveys.size());
  return mean;
}

// What a world file takes (world_file.cpp): a survey outside it has no section to give. `what`
// names the figures ("the surveyed", "room 'kitchen': the surveyed").
void RequireWorldFigures(const std::string& path, const std::string& what, const Survey& s) {
  const auto refuse = [&](const std::string& field, double value, const std::string& expected) {
    audio_propagation::tools::Fail(kProgram, "--world-out " + path + ": " + what + " " + field + " " +
                                                 JsonNumber(value, 3) + " is not " + expected);
  };
  if (!(s.rt60 > 0.0 && s.rt60 <= 10.0)) refuse("rt60", s.rt60, "a reverberation time in (0, 10] s");
  if (!(s.critical_distance > 0.0 && s.critical_distance <= 1000.0)) {
    refuse("critical_distance", s.critical_distance, "a distance in (0, 1000] m (a DRR that high leaves no room)");
  }
  if (!(s.ambient >= -50.0 && s.ambient <= 150.0)) refuse("ambient_db", s.ambient, "a level in [-50, 150] dB");
}

void WriteWorldSection(const std::string& path, const std::vector<Survey>& surveys,
                       const std::vector<std::string>& files) {
  const Survey mean = Mean(surveys);
  RequireWorldFigures(path, "the surveyed", mean);
  std::ofstream out(path);
  if (!out) audio_propagation::tools::Fail(kProgram, path + ": cannot write (--world-out)");
  out << "# The acoustics section of a world file, surveyed by nava_survey from";
  for (const std::string& f : files) out << " " << f;
  out << "\n# (the recordings' mean figures). Paste it into a world file; add noise sources by hand.\n";
  char text[400];
  std::snprintf(text, sizeof text,
                "acoustics:\n  rt60: %.3f\n  critical_distance: %.2f\n  ambient_db: %.1f\n  ambient_kind: %s\n",
                mean.rt60, mean.critical_distance, mean.ambient, mean.pink ? "pink" : "white");
  out << text;
  if (!out) audio_propagation::tools::Fail(kProgram, path + ": write failed (--world-out)");
}

// The building's section: its mean figures over the rooms, a region a room, coupled rooms.
void WriteBuildingSection(const std::string& path, const audio_propagation::tools::BuildingSurvey& building,
                          const std::vector<Survey>& rooms) {
  for (std::size_t k = 0; k < rooms.size(); ++k) {
    RequireWorldFigures(path, "room '" + building.rooms[k].name + "': the surveyed", rooms[k]);
  }
  const Survey mean = Mean(rooms);
  std::ofstream out(path);
  if (!out) audio_propagation::tools::Fail(kProgram, path + ": cannot write (--world-out)");
  out << "# The acoustics section of a world file, surveyed by nava_survey room by room. Paste it into\n"
         "# a world file, set the rooms' ceiling and door heights, add noise sources by hand.\n";
  char text[400];
  std::snprintf(text, sizeof text,
                "acoustics:\n  rt60: %.3f              # s, the rooms' mean\n  critical_distance: %.2f  # m, the "
                "rooms' mean\n  ambient_db: %.1f         # the rooms' mean power\n  ambient_kind: %s\n  regions:\n",
                mean.rt60, mean.critical_distance, mean.ambient, mean.pink ? "pink" : "white");
  out << text;
  for (std::size_t k = 0; k < rooms.size(); ++k) {
    const audio_propagation::tools::SurveyedRoom& r = building.rooms[k];
    std::snprintf(text, sizeof text,
                  "    - {name: %s, box: [%g, %g, %g, %g], rt60: %.3f, critical_distance: %.2f}  # ambient %.1f dB, "
                  "recordings: %zu\n",
                  r.name.c_str(), r.box[0], r.box[1], r.box[2], r.box[3], rooms[k].rt60, rooms[k].critical_distance,
                  rooms[k].ambient, r.recordings.size());
    out << text;
  }
  out << "  rooms:                   # each room its own reverberant field, coupled through the doors\n"
         "    ceiling_height: 2.7\n    door_height: 2.1\n";
  if (!out) audio_propagation::tools::Fail(kProgram, path + ": write failed (--world-out)");
}

int SurveyBuilding(const audio_propagation::tools::SurveyArgs& a) {
  audio_propagation::tools::BuildingSurvey building;
  try {
    building = audio_propagation::tools::ReadBuildingSurvey(a.building);
  } catch (const std::exception& e) {
    audio_propagation::tools::Fail(kProgram, e.what());
  }
  std::vector<Survey> rooms;
  for (const audio_propagation::tools::SurveyedRoom& room : building.rooms) {
    audio_propagation::tools::SurveyArgs one = a;
    one.distance = room.distance;
    one.source_level_db = building.source_level_db;
    std::vector<Survey> heard;
    for (const std::string& file : room.recordings) heard.push_back(SurveyOne(one, file, room.name));
    rooms.push_back(Mean(heard));
  }
  WriteBuildingSection(a.world_out, building, rooms);
  return 0;
}

// What the sending robot plays: room packets of random data, silences drawn around --gap.
void WriteTrain(const audio_propagation::tools::SurveyArgs& a) {
  std::vector<float> train;
  try {
    train = nava_modem::SurveyTrain(a.train_rate, a.train_packets, a.train_gap, a.train_seed);
  } catch (const std::invalid_argument& e) {
    audio_propagation::tools::Fail(kProgram, "--rate " + JsonNumber(a.train_rate, 0) + ": " + e.what());
  }
  try {
    nava_modem::WriteWavFile(a.train_out, train, a.train_rate);
  } catch (const std::exception& e) {
    audio_propagation::tools::Fail(kProgram, a.train_out + ": " + e.what() + " (--write-train)");
  }
  std::printf("{\"train\": %s, \"packets\": %d, \"seconds\": %s}\n", JsonString(a.train_out).c_str(), a.train_packets,
              JsonNumber(static_cast<double>(train.size()) / a.train_rate, 2).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const audio_propagation::tools::SurveyArgs a =
        audio_propagation::tools::ParseSurveyArgs(multirobot_audio::tools::Words(argc, argv));
    if (!a.train_out.empty()) {
      WriteTrain(a);
      return 0;
    }
    if (!a.building.empty()) return SurveyBuilding(a);
    std::vector<Survey> surveys;
    for (const std::string& file : a.files) surveys.push_back(SurveyOne(a, file));
    if (!a.world_out.empty()) WriteWorldSection(a.world_out, surveys, a.files);
    return 0;
  });
}
