// audio_scene_render: what each robot's microphone hears in a scene (robots moving, packets sent)
// in a world with acoustics, as float WAV files, and the acoustic channel model's figures for
// every packet at every listener (scene_render.h has the rendering and the scene file format).
//
//   audio_scene_render --world W [--map M] --scene S --out DIR [--profile nava|room] [--rate 48000]
//                      [--table FILE] [--seed 1]
//
// Writes DIR/<robot>.wav for each robot of the scene (levels absolute: a mean square of 1 is
// 100 dB) and prints one line per packet and listener:
//   packet 0 robot_0 -> robot_1: sent 0.500 s, path 10.23 m, 2 corners, travel 0.0298 s,
//   direct 44.1 dB, reverberant 50.2 dB, total 51.1 dB, drr -6.1 dB, rt60 0.50 s,
//   noise 40.2 dB pink, snr 10.9 dB, p 0.83, rendered snr 10.8 dB
// (rendered snr: the packet's signal power over the rendered noise's power during the packet).
// --profile overrides the scene's; the table is the profile's shipped one unless --table.
// Bad input (a missing file, a robot not in the world, a pose in a wall, wrong-sized data, an
// unknown profile): one line naming the file, field or flag and the value, exit 1.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "acoustic_world.h"
#include "audio_propagation/scene_render.h"
#include "audio_propagation_args.h"

namespace {

int Run(const audio_propagation::tools::SceneRenderArgs& args) {
  using namespace audio_propagation;
  const std::string program = "audio_scene_render";
  const std::string& out = args.out;
  const std::string& scene_file = args.scene_file;
  const double rate = args.rate;
  const unsigned seed = args.seed;

  const tools::AcousticWorld world = tools::LoadAcousticWorld(program, args.world_file, args.map_file);
  Scene scene;
  try {
    scene = LoadScene(scene_file);
    CheckScene(scene_file, scene, world.robots, world.loaded.map);
  } catch (const std::exception& e) {
    tools::Fail(program, e.what());
  }
  if (args.profile) scene.profile = *args.profile;
  const DecodeTable table = tools::LoadTable(program, scene.profile, args.table_file);
  try {
    const AcousticModel model(*world.propagation, world.acoustics, table, world.robots);
    SceneRenderOptions options;
    options.sample_rate = rate;
    options.seed = seed;
    options.speech = tools::SpeechFor(program, world.acoustics, rate, seed);
    options.measured_rooms = tools::MeasuredRoomsFor(table, args.rir_dir, rate, args.usage);
    const SceneRenderer renderer(model, world.robots, world.resting, options);
    const SceneRendering r = renderer.Render(scene);
    std::filesystem::create_directories(out);
    for (const ListenerRecording& l : r.listeners) nava_modem::WriteFloatWavFile(out + "/" + l.robot + ".wav", l.Mix(), rate);
    for (const PacketHearing& h : r.hearings) {
      const ScenePacket& p = scene.packets[h.packet];
      std::printf("packet %zu %s -> %s: ", h.packet, p.sender.c_str(), h.listener.c_str());
      if (!h.reachable) {
        std::printf("sent %.3f s, no path\n", p.time);
        continue;
      }
      const LinkPrediction& m = h.prediction;
      char rendered[64] = "arrives after the scene ends";
      if (h.in_scene) std::snprintf(rendered, sizeof rendered, "rendered snr %.1f dB", 10.0 * std::log10(h.signal_power / h.noise_power));
      std::printf("sent %.3f s, path %.2f m, %d corners, travel %.4f s, direct %.1f dB, reverberant %.1f dB, "
                  "total %.1f dB, drr %.1f dB, rt60 %.2f s, noise %.1f dB %s, snr %.1f dB, p %.2f, %s\n",
                  p.time, m.path_length, m.corners, h.travel_time, m.signal.direct_db, m.signal.reverberant_db,
                  m.signal.total_db, m.signal.drr_db, m.signal.rt60, m.noise_db, InterferenceName(m.kind), m.snr_db,
                  m.probability, rendered);
    }
    std::printf("wrote %zu recordings of %.2f s at %.0f Hz to %s\n", r.listeners.size(), scene.duration, rate, out.c_str());
  } catch (const std::exception& e) {
    tools::Fail(program, e.what());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(audio_propagation::tools::ParseSceneRenderArgs(multirobot_audio::tools::Words(argc, argv))); });
}
