#include "world_sim/world_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "grid/input_error.h"

namespace world_sim {
namespace {

namespace fs = std::filesystem;

// Each test writes world files next to a copy-free reference to the shipped test room map.
class WorldFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           (std::string("world_file_test_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& body, bool with_map = true) {
    const fs::path p = dir_ / "world.yaml";
    std::ofstream out(p);
    if (with_map) out << "map: " << PROJECT_MAPS_DIR << "/test_room.yaml\n";
    out << body;
    return p.string();
  }

  void ExpectError(const std::string& body, const std::string& words, bool with_map = true) {
    const std::string file = Write(body, with_map);
    try {
      LoadWorldFile(file);
      FAIL() << "expected an error containing '" << words << "'";
    } catch (const grid::InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(file, 0), 0u) << "should start with the file name: " << msg;
      EXPECT_NE(msg.find(words), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }

  fs::path dir_;
};

TEST_F(WorldFileTest, LoadsEveryField) {
  const LoadedWorld w = LoadWorldFile(Write(
      "seed: 42\n"
      "robot_model: {radius: 0.1, camera_fov: 1.0, odometry: {linear: 0.0}, battery: {charge_rate: 0.01}}\n"
      "robots:\n"
      "  - {name: a, pose: [1.0, 1.0, 0.5], microphone: bidirectional, battery: 0.5}\n"
      "  - {name: b, pose: [4.5, 1.0, 0.0]}\n"
      "markers: [{id: 3, position: [1.0, 3.0]}]\n"
      "chargers: [{pose: [5.0, 3.0, 0.0], radius: 0.3, marker: 9}]\n"));
  EXPECT_EQ(w.config.seed, 42u);
  EXPECT_DOUBLE_EQ(w.config.model.radius, 0.1);
  EXPECT_DOUBLE_EQ(w.config.model.camera_fov, 1.0);
  EXPECT_DOUBLE_EQ(w.config.model.odometry.linear, 0.0);
  EXPECT_DOUBLE_EQ(w.config.model.battery.charge_rate, 0.01);
  ASSERT_EQ(w.config.robots.size(), 2u);
  EXPECT_EQ(w.config.robots[0].microphone, Microphone::kBidirectional);
  EXPECT_DOUBLE_EQ(w.config.robots[0].battery, 0.5);
  EXPECT_DOUBLE_EQ(w.config.robots[0].start.yaw, 0.5);
  EXPECT_EQ(w.config.robots[1].microphone, Microphone::kOmni);
  ASSERT_EQ(w.config.markers.size(), 1u);
  EXPECT_EQ(w.config.markers[0].id, 3u);
  ASSERT_EQ(w.config.chargers.size(), 1u);
  EXPECT_EQ(*w.config.chargers[0].marker, 9u);
  EXPECT_EQ(w.map.width(), 120);
}

TEST_F(WorldFileTest, SavedWorldLoadsBackTheSame) {
  const LoadedWorld w = LoadWorldFile(Write(
      "seed: 7\n"
      "robot_model: {radius: 0.1, ir_range: 1.25, odometry: {heading_bias: 0.01}}\n"
      "robots:\n"
      "  - {name: a, pose: [1.0, 1.0, 0.5], microphone: bidirectional, battery: 0.5}\n"
      "  - {name: b, pose: [4.5, 1.0, -3.0], microphone: none}\n"
      "markers: [{id: 3, position: [1.0, 3.0]}, {id: 70000, position: [2.25, 3.5]}]\n"
      "chargers: [{pose: [5.0, 3.0, 0.0], radius: 0.3, marker: 9}, {pose: [4.0, 3.0, 1.0]}]\n"));
  const std::string saved = (dir_ / "saved.yaml").string();
  SaveWorldFile(saved, w.config);
  const LoadedWorld back = LoadWorldFile(saved);
  const WorldConfig &a = w.config, &b = back.config;
  EXPECT_EQ(b.map_file, a.map_file);
  EXPECT_EQ(b.seed, 7u);
  EXPECT_DOUBLE_EQ(b.model.radius, 0.1);
  EXPECT_DOUBLE_EQ(b.model.ir_range, 1.25);
  EXPECT_DOUBLE_EQ(b.model.odometry.heading_bias, 0.01);
  EXPECT_DOUBLE_EQ(b.model.battery.motion_drain, a.model.battery.motion_drain);
  ASSERT_EQ(b.robots.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(b.robots[k].name, a.robots[k].name);
    EXPECT_DOUBLE_EQ(b.robots[k].start.x, a.robots[k].start.x);
    EXPECT_DOUBLE_EQ(b.robots[k].start.yaw, a.robots[k].start.yaw);
    EXPECT_EQ(b.robots[k].microphone, a.robots[k].microphone);
    EXPECT_DOUBLE_EQ(b.robots[k].battery, a.robots[k].battery);
  }
  ASSERT_EQ(b.markers.size(), 2u);
  EXPECT_EQ(b.markers[1].id, 70000u);
  EXPECT_DOUBLE_EQ(b.markers[1].x, 2.25);
  ASSERT_EQ(b.chargers.size(), 2u);
  EXPECT_EQ(*b.chargers[0].marker, 9u);
  EXPECT_FALSE(b.chargers[1].marker);
  EXPECT_THROW(SaveWorldFile((dir_ / "no_such_dir" / "x.yaml").string(), a), std::runtime_error);
  // A map given relative to the working directory is written absolute.
  WorldConfig relative = a;
  relative.map_file = fs::relative(a.map_file).string();
  SaveWorldFile(saved, relative);
  EXPECT_EQ(LoadWorldFile(saved).config.map_file, a.map_file);
}

TEST_F(WorldFileTest, ShippedWorldsLoad) {
  // Every world shipped in maps/ (world files end in _world.yaml; the other YAML files there are
  // maps), so that a new one cannot be left out.
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(PROJECT_MAPS_DIR)) {
    const std::string name = e.path().filename().string();
    const std::string suffix = "_world.yaml";
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      names.push_back(name);
  }
  for (const char* name : {"office_world.yaml", "test_room_world.yaml", "test_room_audio_world.yaml",
                           "mutex_world.yaml", "sounds_good_world.yaml", "test_room_sounds_good_world.yaml",
                           "charging_world.yaml", "test_charging_world.yaml", "hospital_world.yaml",
                           "test_room_acoustic_world.yaml", "open_floor_world.yaml"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name << " is not in " << PROJECT_MAPS_DIR;
  }
  // The thesis's map is not shipped (scripts put it in maps/thesis/); where it is missing, the
  // development setup's copy stands in, and without either the world is skipped by name.
  const std::string thesis_map = std::string(PROJECT_MAPS_DIR) + "/thesis/hospital_section.yaml";
  const std::string shared_map = std::string(PROJECT_MAPS_DIR) + "/../../shared/maps/hospital_section.yaml";
  for (const std::string& name : names) {
    std::string map_override;
    if (name == "hospital_world.yaml" && !fs::exists(thesis_map)) {
      if (!fs::exists(shared_map)) {
        std::cout << "skipped " << name << ": no " << thesis_map << "\n";
        continue;
      }
      map_override = shared_map;
    }
    const LoadedWorld w = LoadWorldFile(std::string(PROJECT_MAPS_DIR) + "/" + name, map_override);
    EXPECT_FALSE(w.config.robots.empty()) << name;
  }
}

TEST_F(WorldFileTest, AcousticsLoadAndSaveBack) {
  const LoadedWorld w = LoadWorldFile(Write(
      "robots: [{name: a, pose: [1.0, 1.0, 0]}]\n"
      "acoustics:\n"
      "  rt60: 0.8\n"
      "  volume: 60\n"
      "  ambient_db: 38\n"
      "  ambient_kind: white\n"
      "  corner_loss_db: 4\n"
      "  regions: [{name: east, box: [3.0, 0.0, 6.0, 4.0], rt60: 1.5, critical_distance: 1.2}]\n"
      "  noise_sources:\n"
      "    - {name: fan, position: [1.0, 3.0], kind: whine, frequency: 900, level_db: 55, duty: 0.25, period: 8, phase: 2}\n"
      "    - {robot: a, kind: pink, level_db: 50}\n"));
  ASSERT_TRUE(w.config.acoustics.has_value());
  const Acoustics& a = *w.config.acoustics;
  EXPECT_DOUBLE_EQ(a.room.rt60, 0.8);
  EXPECT_NEAR(CriticalDistance(a.room), 0.057 * std::sqrt(60 / 0.8), 0.01);
  EXPECT_EQ(a.ambient_kind, NoiseKind::kWhite);
  ASSERT_EQ(a.regions.size(), 1u);
  EXPECT_DOUBLE_EQ(a.RoomAt(4.0, 1.0).rt60, 1.5);
  EXPECT_DOUBLE_EQ(a.RoomAt(1.0, 1.0).rt60, 0.8);
  ASSERT_EQ(a.noise_sources.size(), 2u);
  EXPECT_EQ(a.noise_sources[0].kind, NoiseKind::kWhine);
  EXPECT_EQ(a.noise_sources[1].robot, "a");
  EXPECT_EQ(a.noise_sources[1].name, "noise_1");
  // Sounds for 2 s of every 8, its periods starting at t = 2 s: on from 2 to 4 s, 10 to 12 s, ...
  EXPECT_FALSE(Sounding(a.noise_sources[0], 0.5));
  EXPECT_TRUE(Sounding(a.noise_sources[0], 2.5));
  EXPECT_FALSE(Sounding(a.noise_sources[0], 4.5));
  EXPECT_TRUE(Sounding(a.noise_sources[0], 10.5));

  const std::string saved = (dir_ / "saved.yaml").string();
  SaveWorldFile(saved, w.config);
  const LoadedWorld back = LoadWorldFile(saved);
  ASSERT_TRUE(back.config.acoustics.has_value());
  EXPECT_EQ(back.config.acoustics->noise_sources.size(), 2u);
  EXPECT_DOUBLE_EQ(back.config.acoustics->regions[0].room.critical_distance, 1.2);
  EXPECT_DOUBLE_EQ(back.config.acoustics->noise_sources[0].phase, 2.0);
  EXPECT_FALSE(LoadWorldFile(Write("robots: [{name: a, pose: [1.0, 1.0, 0]}]\n")).config.acoustics.has_value());
}

TEST_F(WorldFileTest, ARecordedNoiseSourceNamesItsFileRelativeToTheWorld) {
  std::ofstream(dir_ / "kitchen.wav") << "not read here: the acoustic model and the renderer read it";
  const LoadedWorld w = LoadWorldFile(Write(
      "robots: [{name: a, pose: [1.0, 1.0, 0]}]\n"
      "acoustics:\n"
      "  rt60: 0.5\n"
      "  volume: 60\n"
      "  noise_sources: [{name: kitchen, position: [1.0, 3.0], kind: recording, file: kitchen.wav, level_db: 60}]\n"));
  const NoiseSourceSpec& s = w.config.acoustics->noise_sources.at(0);
  EXPECT_EQ(s.kind, NoiseKind::kRecording);
  EXPECT_EQ(fs::path(s.file), fs::absolute(dir_ / "kitchen.wav").lexically_normal());
  // Saved elsewhere, the file stays the same (absolute) one.
  fs::create_directories(dir_ / "elsewhere");
  const std::string saved = (dir_ / "elsewhere" / "saved.yaml").string();
  SaveWorldFile(saved, w.config);
  EXPECT_EQ(LoadWorldFile(saved).config.acoustics->noise_sources.at(0).file, s.file);

  const std::string robot = "robots: [{name: a, pose: [1.0, 1.0, 0]}]\nacoustics:\n  rt60: 0.5\n  volume: 60\n";
  ExpectError(robot + "  noise_sources: [{position: [1.0, 3.0], kind: recording}]\n",
              "acoustics.noise_sources[0].file: expected the recording's audio file");
  ExpectError(robot + "  noise_sources: [{position: [1.0, 3.0], kind: recording, file: gone.wav}]\n",
              "acoustics.noise_sources[0].file: no such file: " + (dir_ / "gone.wav").string());
  ExpectError(robot + "  noise_sources: [{position: [1.0, 3.0], kind: pink, file: kitchen.wav}]\n",
              "acoustics.noise_sources[0].file: expected only with kind: recording");
  ExpectError(robot + "  ambient_kind: recording\n", "acoustics.ambient_kind: expected white, pink or speech");
}

TEST_F(WorldFileTest, BadAcoustics) {
  const std::string robot = "robots: [{name: a, pose: [1.0, 1.0, 0]}]\n";
  ExpectError(robot + "acoustics: {rt60: 0, volume: 50}\n", "acoustics.rt60: expected a reverberation time in (0, 10] s");
  ExpectError(robot + "acoustics: {rt60: 0.5}\n", "acoustics.volume: expected a room volume");
  ExpectError(robot + "acoustics: {volume: 50, loudness: 3}\n", "loudness");
  ExpectError(robot + "acoustics: {volume: 50, noise_sources: [{position: [1, 3], kind: drill}]}\n",
              "acoustics.noise_sources[0].kind: expected white, pink, speech, whine or recording, got 'drill'");
  ExpectError(robot + "acoustics: {volume: 50, noise_sources: [{position: [3.05, 1.0]}]}\n",
              "acoustics.noise_sources[0].position: noise source 'noise_0' at (3.050000, 1.000000) is inside a wall");
  ExpectError(robot + "acoustics: {volume: 50, noise_sources: [{robot: b}]}\n",
              "acoustics.noise_sources[0].robot: no robot named 'b'");
  ExpectError(robot + "acoustics: {volume: 50, noise_sources: [{kind: whine, position: [1, 3]}]}\n",
              "frequency: expected a whine's frequency above 0 Hz");
  ExpectError(robot + "acoustics: {volume: 50, noise_sources: [{position: [1, 3], duty: 0}]}\n", "duty: expected a duty cycle in (0, 1]");
  ExpectError(robot + "acoustics: {volume: 50, regions: [{name: r, box: [3, 0, 1, 4], volume: 5}]}\n",
              "regions[0].box: expected min_x < max_x");
  ExpectError(robot + "acoustics: {volume: 50, regions: [{name: far, box: [100, 100, 120, 110], volume: 5}]}\n",
              "acoustics.regions[0].box: region 'far' [100.000000, 100.000000, 120.000000, 110.000000] covers none");
  // An infinite box is the whole map.
  EXPECT_EQ(LoadWorldFile(Write(robot + "acoustics: {volume: 50, regions: [{name: all, box: [-.inf, -.inf, .inf, .inf], "
                                        "volume: 5}]}\n"))
                .config.acoustics->regions.size(),
            1u);
}

TEST_F(WorldFileTest, CoupledRoomsLoadSaveBackAndRefuseImpossibleSizes) {
  const std::string world = "robots: [{name: a, pose: [1.0, 1.0, 0]}]\nacoustics:\n  rt60: 0.5\n  volume: 60\n";
  EXPECT_FALSE(LoadWorldFile(Write(world)).config.acoustics->rooms.has_value());
  const LoadedWorld w = LoadWorldFile(Write(world + "  rooms: {ceiling_height: 3.0, door_height: 2.0}\n"));
  const LoadedWorld all = LoadWorldFile(
      Write(world + "  rooms: {door_half_width: 0.8, min_room_area: 2.5, max_obstacle_size: 0.4, corridor_elongation: 0}\n"));
  const std::string all_saved = (dir_ / "all_rooms.yaml").string();
  SaveWorldFile(all_saved, all.config);
  const CoupledRoomsSpec back_all = *LoadWorldFile(all_saved).config.acoustics->rooms;
  EXPECT_DOUBLE_EQ(back_all.door_half_width, 0.8);
  EXPECT_DOUBLE_EQ(back_all.min_room_area, 2.5);
  EXPECT_DOUBLE_EQ(back_all.max_obstacle_size, 0.4);
  EXPECT_DOUBLE_EQ(back_all.corridor_elongation, 0.0);
  ASSERT_TRUE(w.config.acoustics->rooms.has_value());
  EXPECT_DOUBLE_EQ(w.config.acoustics->rooms->ceiling_height, 3.0);
  EXPECT_DOUBLE_EQ(w.config.acoustics->rooms->door_height, 2.0);
  EXPECT_DOUBLE_EQ(w.config.acoustics->rooms->door_half_width, 0.6);  // the defaults
  EXPECT_DOUBLE_EQ(w.config.acoustics->rooms->min_room_area, 1.0);
  const std::string saved = (dir_ / "rooms.yaml").string();
  SaveWorldFile(saved, w.config);
  const LoadedWorld back = LoadWorldFile(saved);
  ASSERT_TRUE(back.config.acoustics->rooms.has_value());
  EXPECT_DOUBLE_EQ(back.config.acoustics->rooms->ceiling_height, 3.0);
  EXPECT_DOUBLE_EQ(back.config.acoustics->rooms->door_height, 2.0);

  ExpectError(world + "  rooms: {ceiling_height: 0}\n", "acoustics.rooms.ceiling_height: expected a height in (0, 100] m");
  ExpectError(world + "  rooms: {ceiling_height: 2.5, door_height: 3}\n",
              "acoustics.rooms.door_height: expected a height in (0, ceiling_height = 2.500000] m, got 3");
  ExpectError(world + "  rooms: {door_half_width: 0.001}\n",
              "acoustics.rooms.door_half_width: expected at least one cell of the map");
  ExpectError(world + "  rooms: {min_room_area: -1}\n", "acoustics.rooms.min_room_area: expected an area in m^2 (>= 0)");
  ExpectError(world + "  rooms: {corridor_elongation: 0.5}\n",
              "acoustics.rooms.corridor_elongation: 0 (rooms kept whole) or a ratio of length to width >= 1");
  ExpectError(world + "  rooms: {windows: 3}\n", "acoustics.rooms.windows: unknown key");
}

TEST_F(WorldFileTest, MissingFile) {
  try {
    LoadWorldFile((dir_ / "absent.yaml").string());
    FAIL();
  } catch (const grid::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("world file not found"), std::string::npos);
  }
}

// A name the file system refuses (longer than a file name may be) is a bad field, not a crash:
// the loader once let std::filesystem's error escape (found by the world_file fuzz target).
TEST_F(WorldFileTest, NamesTooLongForTheFileSystemAreRefusedByField) {
  const std::string name(300, 'a');
  const std::string robot = "robots: [{name: a, pose: [1.0, 1.0, 0]}]\nacoustics:\n  rt60: 0.5\n  volume: 60\n";
  ExpectError(robot + "  noise_sources: [{position: [1.0, 3.0], kind: recording, file: " + name + ".wav}]\n",
              "acoustics.noise_sources[0].file: File name too long: ");
  ExpectError("map: " + name + ".yaml\nrobots: [{name: a, pose: [1.0, 1.0, 0]}]\n",
              "map: cannot load the map: ", /*with_map=*/false);
  ExpectError("map: " + name + ".yaml\nrobots: [{name: a, pose: [1.0, 1.0, 0]}]\n",
              "map file not found (File name too long)", /*with_map=*/false);
}

TEST_F(WorldFileTest, MalformedYaml) { ExpectError("robots: [\n", "malformed YAML"); }

TEST_F(WorldFileTest, UnknownKeys) {
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nwind: 3\n", "wind: unknown key");
  ExpectError("robots: [{name: a, pose: [1, 1, 0], colour: red}]\n", "robots[0].colour: unknown key");
  ExpectError("robot_model: {legs: 4}\nrobots: [{name: a, pose: [1, 1, 0]}]\n",
              "robot_model.legs: unknown key");
}

// Found by fuzz/world_file.cpp: a list as a key in a nested section escaped as yaml-cpp's bad
// conversion instead of an InputError naming the section.
TEST_F(WorldFileTest, KeyThatIsNotTextIsRefused) {
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nacoustics: {volume: 50, regions: [{name: r, [x]: 1}]}\n",
              "acoustics.regions[0]: expected text keys");
}

// Found by fuzz/world_file.cpp: a pose far beyond the map (or NaN) overflowed the cell index
// (undefined behaviour) instead of being refused as off the map.
TEST_F(WorldFileTest, FarAndNonFinitePosesAreOffTheMap) {
  ExpectError("robots: [{name: a, pose: [1.5, 42949672961.5, 0]}]\n", "robots[0].pose: robot 'a' starts outside");
  ExpectError("robots: [{name: a, pose: [.nan, 1, 0]}]\n", "robots[0].pose: robot 'a' starts outside");
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nmarkers: [{id: 1, position: [-1e300, 1]}]\n",
              "markers[0].position");
}

TEST_F(WorldFileTest, MissingMapAndBadMap) {
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\n", "map: missing", false);
  ExpectError("map: nowhere.yaml\nrobots: [{name: a, pose: [1, 1, 0]}]\n", "map: cannot load the map",
              false);
}

TEST_F(WorldFileTest, NoRobots) { ExpectError("markers: []\n", "robots: expected a list of at least one"); }

TEST_F(WorldFileTest, RobotInsideAWall) {
  ExpectError("robots: [{name: a, pose: [3.0, 1.0, 0]}]\n", "robots[0].pose: robot 'a' starts outside");
  ExpectError("robots: [{name: a, pose: [2.95, 1.0, 0]}]\n", "robots[0].pose: robot 'a' overlaps a wall");
}

TEST_F(WorldFileTest, RobotOffTheMap) {
  ExpectError("robots: [{name: a, pose: [7.0, 1.0, 0]}]\n", "robots[0].pose");
  ExpectError("robots: [{name: a, pose: [1.0, -1.0, 0]}]\n", "starts outside the map");
}

TEST_F(WorldFileTest, DuplicateNamesAndOverlaps) {
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}, {name: a, pose: [2, 2, 0]}]\n",
              "robots[1].name: duplicate robot name 'a'");
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}, {name: b, pose: [1.1, 1, 0]}]\n",
              "robots[1].pose: robot 'b' overlaps robot 'a'");
}

TEST_F(WorldFileTest, BadFields) {
  ExpectError("robots: [{name: a, pose: [1, 1]}]\n", "robots[0].pose: expected [x, y, yaw]");
  ExpectError("robots: [{name: a, pose: [1, 1, 0], microphone: stereo}]\n",
              "robots[0].microphone: expected omni, bidirectional or none");
  ExpectError("robots: [{name: 3a, pose: [1, 1, 0]}]\n", "robots[0].name: expected a ROS name");
  ExpectError("robots: [{name: a, pose: [1, 1, 0], battery: 2}]\n", "robots[0].battery");
  ExpectError("robot_model: {radius: -1}\nrobots: [{name: a, pose: [1, 1, 0]}]\n",
              "robot_model.radius: expected a radius");
  ExpectError("seed: -3\nrobots: [{name: a, pose: [1, 1, 0]}]\n", "seed: expected a whole number");
}

TEST_F(WorldFileTest, MarkerInsideAWall) {
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nmarkers: [{id: 1, position: [3.0, 1.0]}]\n",
              "markers[0].position: marker 1 is inside a wall");
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nmarkers: [{id: 1, position: [9.0, 1.0]}]\n",
              "markers[0].position");
  ExpectError("robots: [{name: a, pose: [1, 1, 0]}]\nmarkers: [{id: -1, position: [1.0, 2.0]}]\n",
              "markers[0].id: expected a whole number");
}

// A checkout reached through a symbolic link (a catkin workspace's package is often one): the
// same world loaded, and saved, through the link and through the real folder names one map.
TEST_F(WorldFileTest, AWorldThroughALinkNamesTheSameMapAsThroughItsRealFolder) {
  const fs::path real = dir_ / "real", link = dir_ / "link";
  fs::create_directories(real / "maps");
  for (const char* name : {"test_room.yaml", "test_room.pgm"})
    fs::copy_file(fs::path(PROJECT_MAPS_DIR) / name, real / "maps" / name);
  fs::create_directory_symlink(real, link);
  std::ofstream(real / "world.yaml") << "map: maps/test_room.yaml\nrobots: [{name: a, pose: [1.0, 1.0, 0]}]\n";

  const LoadedWorld through_real = LoadWorldFile((real / "world.yaml").string());
  const LoadedWorld through_link = LoadWorldFile((link / "world.yaml").string());
  EXPECT_EQ(through_link.config.map_file, through_real.config.map_file);
  EXPECT_EQ(LoadWorldFile((real / "world.yaml").string(), (link / "maps" / "test_room.yaml").string()).config.map_file,
            through_real.config.map_file);

  SaveWorldFile((link / "saved.yaml").string(), through_link.config);
  EXPECT_EQ(LoadWorldFile((real / "saved.yaml").string()).config.map_file, through_real.config.map_file);
  WorldConfig relative = through_link.config;
  relative.map_file = fs::relative(link / "maps" / "test_room.yaml").string();
  SaveWorldFile((real / "saved.yaml").string(), relative);
  EXPECT_EQ(LoadWorldFile((link / "saved.yaml").string()).config.map_file, through_real.config.map_file);
}

TEST_F(WorldFileTest, MapOverrideLoadsAnotherMapByPath) {
  const std::string file = Write("robots: [{name: a, pose: [1.0, 7.0, 0]}]\n");
  const LoadedWorld w = LoadWorldFile(file, std::string(PROJECT_MAPS_DIR) + "/office.yaml");
  EXPECT_EQ(w.map.width(), 680);
}

}  // namespace
}  // namespace world_sim
