#include "audio_propagation/scene_render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "grid/input_error.h"
#include "grid/option_checks.h"
#include "grid/yaml_fields.h"
#include "nava_modem/frame.h"
#include "nava_modem/measured_like_response.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/room_channel.h"
#include "tool_args/number_text.h"

namespace audio_propagation {
namespace {

std::string Text(const YAML::Node& node) {
  YAML::Emitter e;
  e << YAML::Flow << node;
  return e.c_str();
}

// One seed from a few numbers (std::seed_seq's mixing is fixed by the standard, so the same
// numbers give the same seed everywhere).
std::uint32_t SeedOf(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::seed_seq seq{a, b, c};
  std::uint32_t out = 0;
  seq.generate(&out, &out + 1);
  return out;
}
// Seed streams, so that rooms, the ambient and the sources never share noise.
constexpr std::uint32_t kRoomSeeds = 1, kAmbientSeeds = 2, kSourceSeeds = 3;

double MeanSquare(const std::vector<double>& x, std::size_t from, std::size_t to) {
  if (to <= from) return 0.0;
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += x[i] * x[i];
  return sum / static_cast<double>(to - from);
}

std::vector<float> ToFloat(const std::vector<double>& x) { return std::vector<float>(x.begin(), x.end()); }

SceneKeyframe ReadKeyframe(const grid::YamlFields& robots, const std::string& field, const YAML::Node& node) {
  const char* shape = "a keyframe [t, x, y, yaw] of numbers";
  if (!node.IsSequence() || node.size() != 4) robots.Fail(field, std::string("expected ") + shape + ", got " + Text(node));
  double v[4];
  for (std::size_t k = 0; k < 4; ++k) {
    try {
      v[k] = node[k].as<double>();
    } catch (const YAML::Exception&) {
      robots.Fail(field, std::string("expected ") + shape + ", got " + Text(node));
    }
    if (!std::isfinite(v[k])) robots.Fail(field, std::string("expected ") + shape + ", got " + Text(node));
  }
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace

double LevelToPower(double db) { return std::pow(10.0, (db - kReferenceDb) / 10.0); }

grid::Pose2D PoseAt(const SceneRobot& robot, double t) {
  const std::vector<SceneKeyframe>& k = robot.keyframes;
  if (k.empty()) throw std::invalid_argument("scene robot '" + robot.name + "' has no keyframes");
  if (t <= k.front().t) return {k.front().x, k.front().y, k.front().yaw};
  if (t >= k.back().t) return {k.back().x, k.back().y, k.back().yaw};
  const auto after = std::upper_bound(k.begin(), k.end(), t, [](double v, const SceneKeyframe& f) { return v < f.t; });
  const SceneKeyframe& b = *after;
  const SceneKeyframe& a = *(after - 1);
  const double w = (t - a.t) / (b.t - a.t);
  return {a.x + w * (b.x - a.x), a.y + w * (b.y - a.y),
          grid::NormalizeAngle(a.yaw + w * grid::NormalizeAngle(b.yaw - a.yaw))};
}

Scene LoadScene(const std::string& path) {
  const grid::YamlFields f = grid::YamlFields::Load(path, "scene file");
  f.ExpectOnlyKeys({"profile", "start", "duration", "robots", "packets", "own_packets", "self_distance", "sound_cards"});
  Scene scene;
  const std::string profile = f.String("profile", "nava");
  const auto parsed = nava_modem::ParseProfile(profile);
  if (!parsed) f.Fail("profile", std::string("expected ") + nava_modem::kProfileNames + ", got '" + profile + "'");
  scene.profile = *parsed;
  scene.start = f.Number("start", 0.0);
  if (!std::isfinite(scene.start)) f.Fail("start", "expected a finite time in s");
  scene.duration = f.Number("duration");
  if (!(scene.duration > 0.0 && scene.duration <= 3600.0)) {
    f.Fail("duration", "expected a length above 0 and at most 3600 s, got " + multirobot_audio::tools::NumberText(scene.duration));
  }
  if (!f.Has("robots") || !f.node()["robots"].IsMap() || f.node()["robots"].size() == 0) {
    f.Fail("robots", "expected a mapping of robot names to lists of keyframes [t, x, y, yaw]");
  }
  const grid::YamlFields robots = f.Child("robots");
  for (const auto& entry : f.node()["robots"]) {
    SceneRobot robot;
    robot.name = entry.first.as<std::string>();
    const YAML::Node frames = entry.second;
    if (!frames.IsSequence() || frames.size() == 0) {
      robots.Fail(robot.name, "expected a list of keyframes [t, x, y, yaw], got " + Text(frames));
    }
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const std::string field = robot.name + "[" + std::to_string(k) + "]";
      robot.keyframes.push_back(ReadKeyframe(robots, field, frames[k]));
      if (k > 0 && !(robot.keyframes[k].t > robot.keyframes[k - 1].t)) {
        robots.Fail(field, "keyframe time " + multirobot_audio::tools::NumberText(robot.keyframes[k].t) + " s: expected times in ascending order");
      }
    }
    scene.robots.push_back(std::move(robot));
  }
  for (const grid::YamlFields& p : f.Elements("packets")) {
    p.ExpectOnlyKeys({"time", "sender", "data"});
    ScenePacket packet;
    packet.time = p.Number("time");
    if (!(packet.time >= scene.start && packet.time < scene.start + scene.duration)) {
      p.Fail("time", multirobot_audio::tools::NumberText(packet.time) + " s: expected a time within the scene, from " + multirobot_audio::tools::NumberText(scene.start) +
                         " to before " + multirobot_audio::tools::NumberText(scene.start + scene.duration) + " s");
    }
    packet.sender = p.String("sender");
    const bool known = std::any_of(scene.robots.begin(), scene.robots.end(),
                                   [&](const SceneRobot& r) { return r.name == packet.sender; });
    if (!known) p.Fail("sender", "'" + packet.sender + "' is not one of the scene's robots");
    const YAML::Node data = p.node()["data"];
    const std::string shape = "expected " + std::to_string(nava_modem::kDataBytes) + " bytes (whole numbers 0-255)";
    if (!data || !data.IsSequence() || data.size() != packet.data.size()) {
      p.Fail("data", shape + ", got " + (data ? Text(data) : std::string("nothing")));
    }
    for (std::size_t k = 0; k < packet.data.size(); ++k) {
      int byte = -1;
      try {
        byte = data[k].as<int>();
      } catch (const YAML::Exception&) {
      }
      if (byte < 0 || byte > 255) p.Fail("data", shape + ", got " + Text(data));
      packet.data[k] = static_cast<std::uint8_t>(byte);
    }
    scene.packets.push_back(packet);
  }
  if (f.Has("own_packets")) {
    try {
      scene.own_packets = f.node()["own_packets"].as<bool>();
    } catch (const YAML::Exception&) {
      f.Fail("own_packets", "expected true or false, got " + Text(f.node()["own_packets"]));
    }
  }
  scene.self_distance = f.Number("self_distance", scene.self_distance);
  if (!(scene.self_distance >= 0.01 && scene.self_distance <= 2.0)) {
    f.Fail("self_distance", "expected 0.01 to 2 m, got " + multirobot_audio::tools::NumberText(scene.self_distance));
  }
  if (f.Has("sound_cards")) {
    if (!f.node()["sound_cards"].IsMap()) f.Fail("sound_cards", "expected a mapping of robot names to {rate_ppm, latency}");
    const grid::YamlFields cards = f.Child("sound_cards");
    for (const auto& entry : f.node()["sound_cards"]) {
      const std::string name = entry.first.as<std::string>();
      const bool known = std::any_of(scene.robots.begin(), scene.robots.end(), [&](const SceneRobot& r) { return r.name == name; });
      if (!known) cards.Fail(name, "'" + name + "' is not one of the scene's robots");
      const grid::YamlFields card = cards.Child(name);
      card.ExpectOnlyKeys({"rate_ppm", "latency"});
      SceneSoundCard c;
      const double ppm = card.Number("rate_ppm", 0.0);
      if (!(std::abs(ppm) <= 1000.0)) card.Fail("rate_ppm", "expected -1000 to 1000 ppm, got " + multirobot_audio::tools::NumberText(ppm));
      c.rate_error = ppm * 1e-6;
      c.latency = card.Number("latency", 0.0);
      if (!(c.latency >= 0.0 && c.latency <= 1.0)) card.Fail("latency", "expected 0 to 1 s, got " + multirobot_audio::tools::NumberText(c.latency));
      scene.sound_cards[name] = c;
    }
  }
  return scene;
}

SceneSoundCard Scene::CardOf(const std::string& robot) const {
  const auto it = sound_cards.find(robot);
  return it == sound_cards.end() ? SceneSoundCard{} : it->second;
}

void CheckScene(const std::string& file, const Scene& scene, const std::vector<std::string>& world_robots,
                const grid::OccupancyMap& map) {
  for (const SceneRobot& r : scene.robots) {
    if (std::find(world_robots.begin(), world_robots.end(), r.name) == world_robots.end()) {
      throw grid::InputError(file, "robots." + r.name, "no robot named '" + r.name + "' in the world");
    }
    for (std::size_t k = 0; k < r.keyframes.size(); ++k) {
      const SceneKeyframe& f = r.keyframes[k];
      if (!map.IsFreeAt({f.x, f.y})) {
        throw grid::InputError(file, "robots." + r.name + "[" + std::to_string(k) + "]",
                               "(" + multirobot_audio::tools::NumberText(f.x) + ", " + multirobot_audio::tools::NumberText(f.y) + ") is not in the map's free space");
      }
    }
  }
}

std::vector<float> ListenerRecording::Mix() const {
  std::vector<float> out(packets.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = packets[i] + noise[i];
  return out;
}

void ValidateOptions(const SceneRenderOptions& o) {
  nava_modem::ValidateSampleRate("scene renderer: sample rate", o.sample_rate);
  grid::RequireAbove("scene renderer level_step (s)", o.level_step, 0.0);
}

SceneRenderer::SceneRenderer(const AcousticModel& model, std::vector<std::string> robot_names,
                             std::vector<Eigen::Vector2d> resting, SceneRenderOptions options)
    : model_(model), robot_names_(std::move(robot_names)), resting_(std::move(resting)), options_(std::move(options)) {
  ValidateOptions(options_);
  if (robot_names_.size() != resting_.size()) {
    throw std::invalid_argument("scene renderer: " + std::to_string(robot_names_.size()) + " robot names but " +
                                std::to_string(resting_.size()) + " resting positions");
  }
  if (model_.table().rooms == nava_modem::RoomOptions::Model::kMeasured) {
    if (!options_.measured_rooms) {
      throw std::invalid_argument("scene renderer: the " + model_.table().profile +
                                  " table was measured over measured rooms (rooms: measured): expected them "
                                  "(measured_rooms, a tool's --rir-dir)");
    }
    if (options_.measured_rooms->sample_rate() != options_.sample_rate) {
      throw std::invalid_argument("scene renderer: measured rooms at " + std::to_string(options_.measured_rooms->sample_rate()) +
                                  " Hz, expected the render's " + std::to_string(options_.sample_rate) + " Hz");
    }
  }
  double sum = 0.0;
  for (float v : options_.speech) sum += static_cast<double>(v) * v;
  speech_power_ = options_.speech.empty() ? 0.0 : sum / static_cast<double>(options_.speech.size());
  for (const world_sim::NoiseSourceSpec& s : model_.acoustics().noise_sources) {
    recordings_.emplace_back();
    if (s.kind != world_sim::NoiseKind::kRecording) continue;
    try {
      recordings_.back() = nava_modem::ReadAudioAt(s.file, options_.sample_rate);
    } catch (const std::exception& e) {
      throw std::invalid_argument("scene renderer: noise source '" + s.name + "' (" + s.file + "): " + e.what());
    }
    if (recordings_.back().empty()) {
      throw std::invalid_argument("scene renderer: noise source '" + s.name + "' (" + s.file + "): no samples");
    }
  }
}

std::vector<Eigen::Vector2d> SceneRenderer::Positions(const Scene& scene, const std::vector<int>& scene_robot,
                                                      double t) const {
  std::vector<Eigen::Vector2d> at = resting_;
  for (std::size_t k = 0; k < at.size(); ++k) {
    if (scene_robot[k] >= 0) at[k] = PoseAt(scene.robots[static_cast<std::size_t>(scene_robot[k])], t).position();
  }
  return at;
}

std::vector<double> SceneRenderer::Waveform(world_sim::NoiseKind kind, double frequency, std::size_t n,
                                            std::uint32_t seed, const std::vector<float>& recording) const {
  const double rate = options_.sample_rate;
  std::vector<double> x;
  switch (kind) {
    case world_sim::NoiseKind::kWhite: x = nava_modem::WhiteNoise(n, seed); break;
    case world_sim::NoiseKind::kPink: x = nava_modem::PinkNoise(n, rate, seed); break;
    case world_sim::NoiseKind::kWhine: {
      // The decode tables' whine: RoomOptions' amplitude modulation.
      x = nava_modem::MotorWhine(n, rate, frequency, nava_modem::RoomOptions().whine_am_hz, seed);
      break;
    }
    case world_sim::NoiseKind::kSpeech: {
      if (!(speech_power_ > 0.0)) {
        throw std::invalid_argument("scene renderer: the world has speech, but no speech was given to render it");
      }
      // Its long-term power is 1 (a talker's level is a long-term level): over a short stretch
      // it may be louder or, in a pause, quieter.
      const std::size_t m = options_.speech.size(), shift = seed % m;
      const double g = 1.0 / std::sqrt(speech_power_);
      x.resize(n);
      for (std::size_t i = 0; i < n; ++i) x[i] = g * options_.speech[(shift + i) % m];
      return x;
    }
    case world_sim::NoiseKind::kRecording: {
      if (recording.empty()) throw std::invalid_argument("scene renderer: a recorded noise with no recording");
      // Played in a loop from a place of the seed's, at unit power over the loop.
      const std::size_t m = recording.size(), shift = seed % m;
      x.resize(n);
      for (std::size_t i = 0; i < n; ++i) x[i] = recording[(shift + i) % m];
      double p = 0.0;
      for (float v : recording) p += static_cast<double>(v) * v / static_cast<double>(m);
      if (!(p > 0.0)) throw std::invalid_argument("scene renderer: a recorded noise that is silent");
      for (double& v : x) v /= std::sqrt(p);
      return x;
    }
  }
  // Exactly power 1 over the recording, as the decode tables' noise is.
  const double p = MeanSquare(x, 0, x.size());
  if (p > 0.0) {
    const double g = 1.0 / std::sqrt(p);
    for (double& v : x) v *= g;
  }
  return x;
}

SceneRendering SceneRenderer::Render(const Scene& scene, const std::vector<std::string>& listeners) const {
  const double rate = options_.sample_rate;
  const std::size_t n = static_cast<std::size_t>(std::ceil(scene.duration * rate));
  // Team index -> scene robot index (or -1), and the scene robots' team indices.
  std::vector<int> scene_robot(robot_names_.size(), -1);
  std::vector<std::size_t> team_index(scene.robots.size());
  for (std::size_t r = 0; r < scene.robots.size(); ++r) {
    const auto it = std::find(robot_names_.begin(), robot_names_.end(), scene.robots[r].name);
    if (it == robot_names_.end()) {
      throw std::invalid_argument("scene renderer: robot '" + scene.robots[r].name + "' is not in the team");
    }
    team_index[r] = static_cast<std::size_t>(it - robot_names_.begin());
    scene_robot[team_index[r]] = static_cast<int>(r);
  }
  std::vector<std::size_t> heard;  // scene robot indices to render
  if (listeners.empty()) {
    for (std::size_t r = 0; r < scene.robots.size(); ++r) heard.push_back(r);
  } else {
    for (const std::string& name : listeners) {
      const auto it = std::find_if(scene.robots.begin(), scene.robots.end(),
                                   [&](const SceneRobot& r) { return r.name == name; });
      if (it == scene.robots.end()) throw std::invalid_argument("scene renderer: listener '" + name + "' is not in the scene");
      heard.push_back(static_cast<std::size_t>(it - scene.robots.begin()));
    }
  }

  if (model_.table().profile != nava_modem::ProfileName(scene.profile)) {
    throw std::invalid_argument("scene renderer: the model's decode table is for '" + model_.table().profile +
                                "', but the scene's packets are " + nava_modem::ProfileName(scene.profile) + "'s");
  }
  nava_modem::ModemOptions modem;
  modem.sample_rate = rate;
  const auto profile = nava_modem::MakeProfile(scene.profile, modem);
  const PropagationModel& propagation = model_.propagation();
  const world_sim::Acoustics& acoustics = model_.acoustics();

  SceneRendering out;
  out.sample_rate = rate;
  std::vector<std::vector<double>> packet_stems(heard.size(), std::vector<double>(n, 0.0));
  std::vector<std::vector<double>> noise_stems(heard.size(), std::vector<double>(n, 0.0));

  // The noise: the ambient, then each source through its level track and duty cycle.
  const std::size_t steps = static_cast<std::size_t>(std::ceil(scene.duration / options_.level_step)) + 1;
  for (std::size_t h = 0; h < heard.size(); ++h) {
    const std::size_t listener = team_index[heard[h]];
    std::vector<double>& noise = noise_stems[h];
    const std::vector<double> ambient =
        Waveform(acoustics.ambient_kind, 0.0, n, SeedOf(options_.seed, kAmbientSeeds, static_cast<std::uint32_t>(listener)));
    const double a = std::sqrt(LevelToPower(acoustics.ambient_db));
    for (std::size_t i = 0; i < n; ++i) noise[i] += a * ambient[i];
    for (std::size_t k = 0; k < acoustics.noise_sources.size(); ++k) {
      const world_sim::NoiseSourceSpec& s = acoustics.noise_sources[k];
      // The level at each step; NaN where no path reaches.
      std::vector<double> level(steps);
      for (std::size_t j = 0; j < steps; ++j) {
        const double t = scene.start + static_cast<double>(j) * options_.level_step;
        const std::vector<Eigen::Vector2d> at = Positions(scene, scene_robot, t);
        const std::optional<double> db = model_.SourceLevelDb(k, at[listener], at);
        level[j] = db ? *db : std::numeric_limits<double>::quiet_NaN();
      }
      // The same source sounds the same wherever it is heard: its waveform's seed is its own.
      const std::vector<double> wave =
          Waveform(s.kind, s.frequency, n, SeedOf(options_.seed, kSourceSeeds, static_cast<std::uint32_t>(k)), recordings_[k]);
      for (std::size_t i = 0; i < n; ++i) {
        const double t = scene.start + static_cast<double>(i) / rate;
        if (!world_sim::Sounding(s, t)) continue;
        const double u = (t - scene.start) / options_.level_step;
        const std::size_t j = std::min(static_cast<std::size_t>(u), steps - 1);
        const std::size_t j1 = std::min(j + 1, steps - 1);
        const double w = u - static_cast<double>(j);
        double db = level[j];
        if (!std::isnan(level[j]) && !std::isnan(level[j1])) db = level[j] + std::min(w, 1.0) * (level[j1] - level[j]);
        if (std::isnan(db)) continue;
        noise[i] += std::sqrt(LevelToPower(db)) * wave[i];
      }
    }
  }

  // The packets.
  for (std::size_t p = 0; p < scene.packets.size(); ++p) {
    const ScenePacket& packet = scene.packets[p];
    const std::vector<float> burst = profile->ModulatePacket({packet.data.begin(), packet.data.end()});
    const std::vector<bool> sounding = nava_modem::SoundingSamples(burst, rate);
    const double airtime = static_cast<double>(burst.size()) / rate;
    const std::vector<Eigen::Vector2d> sent_at = Positions(scene, scene_robot, packet.time);
    std::size_t sender = 0;
    while (robot_names_[sender] != packet.sender) ++sender;
    const SceneSoundCard speaker = scene.CardOf(packet.sender);
    for (std::size_t h = 0; h < heard.size(); ++h) {
      const std::size_t listener = team_index[heard[h]];
      const bool own = listener == sender;
      if (own && !scene.own_packets) continue;
      PacketHearing hearing;
      hearing.packet = p;
      hearing.listener = robot_names_[listener];
      SoundPath path;
      if (own) {
        // Its microphone hears its speaker directly, a hand's breadth away.
        path.reachable = path.audible = true;
        path.length = scene.self_distance;
        path.travel_time = path.length / propagation.options().speed_of_sound;
        path.polyline = {sent_at[sender], sent_at[sender]};
      } else {
        path = propagation.Path(sent_at[sender], sent_at[listener]);
      }
      hearing.reachable = path.reachable;
      if (!path.reachable) {
        out.hearings.push_back(hearing);
        continue;
      }
      hearing.path_length = path.length;
      hearing.corners = path.bends;
      hearing.travel_time = path.travel_time;
      hearing.arrival = packet.time + speaker.latency + path.travel_time;
      const SceneSoundCard microphone = scene.CardOf(hearing.listener);
      hearing.arrival_clock = (hearing.arrival - scene.start) * (1.0 + microphone.rate_error);
      // The model's figures as the channel takes them: the path at send time, the noise over the
      // arrival (the robots where they are in its middle).
      const double middle = hearing.arrival + 0.5 * airtime;
      const std::vector<Eigen::Vector2d> mid_at = Positions(scene, scene_robot, middle);
      const std::vector<Disturbance> disturbances =
          model_.NoiseDuring(mid_at[listener], hearing.arrival, hearing.arrival + airtime, mid_at);
      hearing.prediction = model_.Predict(path, sent_at[listener], disturbances);
      double noise = 0.0;
      for (const Disturbance& d : disturbances) noise += d.power;
      hearing.model_noise_db = 10.0 * std::log10(noise);
      const LinkLevels& levels = hearing.prediction.signal;

      nava_modem::RoomOptions room;
      room.rt60 = levels.rt60;
      room.drr_db = std::clamp(levels.drr_db, -40.0, 40.0);
      // The rooms the table was measured over (the validation holds the model against the
      // receiver in them: the nava table's corner links rendered in statistical rooms decoded
      // 8-17 points more than the model said), at the path's length: without it a measured-like
      // room draws the distance from the DRR, so a diffracted sound 30 dB under the
      // reverberation became a listener 60 m down a hall whose reverberation builds up over up
      // to 80 ms, its strongest part 40-90 ms after the direct sound. A robot hearing itself, the
      // statistical room: a measured-like room draws the loudspeaker's and microphone's
      // colouring anew for every packet, which would move the leading edge of a path that is the
      // same for every packet (its ~ranging_offset).
      room.model = own ? nava_modem::RoomOptions::Model::kStatistical : model_.table().rooms;
      if (room.model == nava_modem::RoomOptions::Model::kMeasuredLike && room.rt60 > 0.0) {
        room.geometry.distance_m = path.length;
      }
      room.seed = SeedOf(options_.seed, kRoomSeeds, static_cast<std::uint32_t>(p * robot_names_.size() + listener));
      // A measured room moved to the link's figures; its direct sound lies where it was measured.
      double lead = 0.0;
      if (room.model == nava_modem::RoomOptions::Model::kMeasured) {
        if (room.rt60 > 0.0) {
          const nava_modem::MovedRooms::Drawn drawn = options_.measured_rooms->Move(room.rt60, room.drr_db, room.seed);
          room.response = *drawn.response;
          lead = static_cast<double>(drawn.peak);
        } else {
          room.model = nava_modem::RoomOptions::Model::kStatistical;
        }
        room.rt60 = room.drr_db = 0.0;
      }
      // The speaker's card plays at its rate, the microphone's samples at its own.
      room.clock_offset = (1.0 + speaker.rate_error) / (1.0 + microphone.rate_error) - 1.0;
      nava_modem::RoomRenderInfo info;
      const std::vector<float> rendered = nava_modem::RenderRoom(burst, rate, room, {}, &info);
      const double gain = std::sqrt(LevelToPower(levels.total_db) / info.signal_power) / info.output_gain;
      // The signal power as rendered, by room_channel.h's definition.
      double sum = 0.0;
      std::size_t count = 0;
      for (std::size_t i = 0; i < burst.size(); ++i) {
        if (!sounding[i]) continue;
        sum += gain * rendered[i] * gain * rendered[i];
        ++count;
      }
      hearing.signal_power = count ? sum / static_cast<double>(count) : 0.0;
      // A measured-like response has its direct sound kMeasuredLikeDelay samples in (room for
      // its reflections' pulses), a measured one where it was measured: taken back, so that
      // every kind of room's direct sound arrives after the travel time. Left in, a measured-like
      // link arrived 0.33 ms (11 cm) later than a statistical one, which a two-way range between
      // the two kinds did not cancel.
      if (room.model == nava_modem::RoomOptions::Model::kMeasuredLike && room.rt60 > 0.0) {
        lead = static_cast<double>(nava_modem::kMeasuredLikeDelay);
      }
      const double first = std::round(hearing.arrival_clock * rate);
      hearing.in_scene = first >= 0.0 && first < static_cast<double>(n);
      hearing.first_sample = static_cast<std::size_t>(std::max(first, 0.0));
      std::vector<double>& stem = packet_stems[h];
      for (std::size_t i = 0; i < rendered.size(); ++i) {
        const double at = first - lead + static_cast<double>(i);
        if (at >= 0.0 && at < static_cast<double>(n)) stem[static_cast<std::size_t>(at)] += gain * rendered[i];
      }
      const std::size_t end = std::min(n, hearing.first_sample + burst.size());
      hearing.noise_power = MeanSquare(noise_stems[h], std::min(hearing.first_sample, end), end);
      out.hearings.push_back(hearing);
    }
  }

  for (std::size_t h = 0; h < heard.size(); ++h) {
    out.listeners.push_back({scene.robots[heard[h]].name, ToFloat(packet_stems[h]), ToFloat(noise_stems[h])});
  }
  return out;
}

}  // namespace audio_propagation
