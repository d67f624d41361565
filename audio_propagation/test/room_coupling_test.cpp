#include "audio_propagation/room_coupling.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "floor_plan.h"

#include "audio_propagation/acoustic_model.h"

namespace audio_propagation {
namespace {

using grid::test::Floor;

PropagationOptions Options() {
  PropagationOptions o;
  o.threshold_db = 0.0;  // every path is computed; the acoustic model decides
  o.threads = 1;
  return o;
}

world_sim::Acoustics Building(double rt60) {
  world_sim::Acoustics a;
  a.room.rt60 = rt60;
  a.room.volume = 1000.0;  // the whole floor's: rooms take their own
  a.ambient_db = 20.0;
  world_sim::CoupledRoomsSpec rooms;
  rooms.ceiling_height = 3.0;
  rooms.door_height = 2.0;
  a.rooms = rooms;
  return a;
}

// Two 5 x 4 m rooms side by side; a 0.9 m door in the wall between them at y = 1.5 .. 2.4.
Floor TwoRooms() {
  Floor floor(10.0, 4.0, 0.1);
  floor.Wall(4.95, 0, 5.15, 4.0).Door(4.9, 1.5, 5.2, 2.4);
  return floor;
}

TEST(RoomCoupling, TwoRoomsHearEachOtherThroughTheirDoorAsTheEnergyBalanceSays) {
  const Floor floor = TwoRooms();
  const world_sim::Acoustics acoustics = Building(0.8);
  const RoomCoupling rooms(floor.map(), acoustics);
  ASSERT_EQ(rooms.segmentation().rooms().size(), 2u);
  ASSERT_EQ(rooms.segmentation().openings().size(), 1u);
  const int left = rooms.RoomAt({2.0, 2.0}), right = rooms.RoomAt({8.0, 2.0});
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  ASSERT_NE(left, right);

  // Cremer and Mueller's two rooms: A_i from each room's own volume (floor x 3 m) and the
  // world's RT60, the door absorbing fully on both sides: E_right / E_left,shut =
  // A_l S / ((A_l + S)(A_r + S) - S^2).
  const double area_l = rooms.segmentation().rooms()[static_cast<std::size_t>(left)].area;
  const double area_r = rooms.segmentation().rooms()[static_cast<std::size_t>(right)].area;
  const double a_l = SabineAbsorption(area_l * 3.0, 0.8), a_r = SabineAbsorption(area_r * 3.0, 0.8);
  const double s = rooms.segmentation().openings()[0].width * 2.0;
  EXPECT_NEAR(s, 0.9 * 2.0, 0.2 * 2.0);
  const double through = 10.0 * std::log10(a_l * s / ((a_l + s) * (a_r + s) - s * s));
  const double at_home = 10.0 * std::log10(a_l * (a_r + s) / ((a_l + s) * (a_r + s) - s * s));
  EXPECT_NEAR(rooms.RelativeLevelDb({2.0, 2.0}, {8.0, 2.0}), through, 1e-9);
  EXPECT_NEAR(rooms.RelativeLevelDb({2.0, 2.0}, {3.0, 1.0}), at_home, 1e-9);
  // Rooms of ordinary absorption, a door between them: the next room's field is 8-12 dB down.
  EXPECT_LT(through - at_home, -8.0);
  EXPECT_GT(through - at_home, -12.0);
  // Off the free space a point keeps the single field.
  EXPECT_EQ(rooms.RelativeLevelDb({5.05, 0.5}, {8.0, 2.0}), 0.0);

  // A room no region covers has its own volume; the world's RT60.
  EXPECT_DOUBLE_EQ(rooms.Acoustics(static_cast<std::size_t>(left)).volume, area_l * 3.0);
  EXPECT_DOUBLE_EQ(rooms.Acoustics(static_cast<std::size_t>(left)).rt60, 0.8);
}

TEST(RoomCoupling, ARegionNamesTheAcousticsOfTheRoomItMostlyCovers) {
  const Floor floor = TwoRooms();
  world_sim::Acoustics acoustics = Building(0.8);
  world_sim::AcousticRegion hall;
  hall.name = "hall";
  hall.min_x = 4.0, hall.min_y = 0.0, hall.max_x = 10.0, hall.max_y = 4.0;  // the right room and a strip of the left
  hall.room.rt60 = 1.5;
  hall.room.critical_distance = 1.0;
  acoustics.regions.push_back(hall);
  const RoomCoupling rooms(floor.map(), acoustics);
  const auto left = static_cast<std::size_t>(rooms.RoomAt({2.0, 2.0}));
  const auto right = static_cast<std::size_t>(rooms.RoomAt({8.0, 2.0}));
  EXPECT_EQ(rooms.Region(right), 0);
  EXPECT_EQ(rooms.Region(left), -1);
  EXPECT_DOUBLE_EQ(rooms.Acoustics(right).rt60, 1.5);
  EXPECT_DOUBLE_EQ(rooms.Acoustics(left).rt60, 0.8);
  // The right room's share of the region's floor gets that share of its absorption
  // (r_c^2 = A / (16 pi)): the strip of the left room the box also covers keeps the rest.
  int in_box = 0, right_in_box = 0;
  for (int j = 0; j < floor.map().height(); ++j) {
    for (int i = 0; i < floor.map().width(); ++i) {
      const Eigen::Vector2d c = floor.map().CellCenter(i, j);
      if (floor.map().Blocks(i, j) || !hall.Contains(c.x(), c.y())) continue;
      ++in_box;
      right_in_box += rooms.segmentation().RoomOfCell(i, j) == static_cast<int>(right);
    }
  }
  const double share = static_cast<double>(right_in_box) / in_box;
  EXPECT_GT(share, 0.7);
  EXPECT_LT(share, 0.95);
  EXPECT_NEAR(rooms.field().Absorption(static_cast<std::size_t>(rooms.ZoneAt({8.0, 2.0}))), 16.0 * M_PI * share, 1e-9);
  EXPECT_NEAR(world_sim::CriticalDistance(rooms.Acoustics(right)), std::sqrt(share), 1e-12);
}

// A region whose box is the larger part of no room (a strip of each) would be overruled in
// every room without a word: it is refused by name.
TEST(RoomCoupling, ARegionThatNamesNoRoomIsRefusedByName) {
  const Floor floor = TwoRooms();
  world_sim::Acoustics acoustics = Building(0.8);
  world_sim::AcousticRegion strip;
  strip.name = "doorway";
  strip.min_x = 4.0, strip.min_y = 0.0, strip.max_x = 6.0, strip.max_y = 4.0;
  strip.room.rt60 = 1.5;
  strip.room.volume = 20.0;
  acoustics.regions.push_back(strip);
  try {
    const RoomCoupling rooms(floor.map(), acoustics);
    FAIL() << "a region naming no room was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("region 'doorway' is the larger part of none of the rooms"), std::string::npos)
        << e.what();
  }
}

TEST(RoomCoupling, RoomsNoOpeningJoinsShareNothingButAFiniteFloor) {
  // Two rooms with no door between them.
  Floor floor(10.0, 4.0, 0.1);
  floor.Wall(4.95, 0, 5.15, 4.0);
  const RoomCoupling rooms(floor.map(), Building(0.8));
  ASSERT_EQ(rooms.segmentation().rooms().size(), 2u);
  EXPECT_EQ(rooms.RelativeLevelDb({2.0, 2.0}, {8.0, 2.0}), CoupledRooms::kNoCouplingDb);
}

TEST(RoomCoupling, AnAcousticsWithoutRoomsIsRefusedAndBadOptionsAreNamed) {
  const Floor floor = TwoRooms();
  world_sim::Acoustics acoustics = Building(0.8);
  acoustics.rooms.reset();
  EXPECT_THROW(RoomCoupling(floor.map(), acoustics), std::invalid_argument);
  acoustics = Building(0.8);
  acoustics.rooms->door_half_width = 0.01;  // under a cell
  const PropagationModel propagation(floor.map(), Options());
  try {
    AcousticModel(propagation, acoustics, test::FlatTable("nava"), {});
    FAIL() << "a door half-width under a cell was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("acoustics.rooms: room segmentation: door_half_width"), std::string::npos)
        << e.what();
  }
  acoustics = Building(0.8);
  acoustics.rooms->corridor_elongation = 0.5;  // a room shorter than it is wide cut
  try {
    AcousticModel(propagation, acoustics, test::FlatTable("nava"), {});
    FAIL() << "an elongation under 1 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("room zones: corridor_elongation"), std::string::npos) << e.what();
  }
}

// A building of one room (a region naming its acoustics, as the world's room does without rooms)
// is today's model, to the bit: a room as long as it is wide, or a long hall kept whole.
void ExpectOneRoomIsTheSingleFieldModel(const Floor& floor, double elongation) {
  const PropagationModel propagation(floor.map(), Options());
  world_sim::Acoustics single;
  single.room.rt60 = 0.6;
  single.room.critical_distance = 2.0;
  single.ambient_db = 30.0;
  world_sim::Acoustics coupled = single;
  coupled.rooms = world_sim::CoupledRoomsSpec{};
  coupled.rooms->corridor_elongation = elongation;
  world_sim::AcousticRegion all;
  all.name = "all";
  all.min_x = 0.0, all.min_y = 0.0, all.max_x = 20.0, all.max_y = 20.0;
  all.room = single.room;
  coupled.regions.push_back(all);
  const AcousticModel a(propagation, single, test::FlatTable("nava"), {});
  const AcousticModel b(propagation, coupled, test::FlatTable("nava"), {});
  ASSERT_NE(b.rooms(), nullptr);
  ASSERT_EQ(b.rooms()->segmentation().rooms().size(), 1u);
  ASSERT_EQ(b.rooms()->zones().zones().size(), 1u);
  for (const double x : {1.0, 4.0, 9.5, 18.0}) {
    if (floor.map().Blocks(floor.map().WorldToCell({x, 1.5}).x(), floor.map().WorldToCell({x, 1.5}).y())) continue;
    const SoundPath path = propagation.Path({0.5, 2.5}, {x, 1.5});
    const LinkLevels la = a.Levels(path, {x, 1.5}), lb = b.Levels(path, {x, 1.5});
    EXPECT_EQ(la.direct_db, lb.direct_db) << x;
    EXPECT_EQ(la.reverberant_db, lb.reverberant_db) << x;
    EXPECT_EQ(la.drr_db, lb.drr_db) << x;
    EXPECT_EQ(la.rt60, lb.rt60) << x;
  }
}

TEST(RoomCoupling, OneRoomIsTheSingleFieldModelBitForBit) {
  ExpectOneRoomIsTheSingleFieldModel(Floor(12.0, 9.0, 0.1), 3.0);
  ExpectOneRoomIsTheSingleFieldModel(Floor(20.0, 5.0, 0.1), 0.0);  // long, but kept whole
}

// Down a corridor the reverberant field falls as the diffusion equation says (Valeau, Picaut and
// Billon; Kang's corridors fall about a dB a metre): w(x) ~ exp(-k x), k = (P / A_c) sqrt(3
// alpha) / 4 for a cross-section A_c of perimeter P whose surfaces absorb alpha (Sabine's, from
// the RT60). Worked out here from the corridor's own dimensions, not from the zones' lengths.
TEST(RoomCoupling, ACorridorsFieldFallsAlongItAsTheDiffusionEquationSays) {
  const double width = 2.0, length = 40.0, height = 2.7, rt60 = 0.8;
  const Floor floor(length + 0.2, width + 0.2, 0.1);
  world_sim::Acoustics acoustics = Building(rt60);
  acoustics.rooms->ceiling_height = height;
  const RoomCoupling corridor(floor.map(), acoustics);
  ASSERT_EQ(corridor.segmentation().rooms().size(), 1u);
  ASSERT_GT(corridor.zones().zones().size(), 8u);
  const double zone = CorridorZoneLength(width, height);
  EXPECT_NEAR(length / static_cast<double>(corridor.zones().zones().size()), zone, 0.25 * zone);

  const double volume = length * width * height;
  const double surface = 2.0 * length * (width + height) + 2.0 * width * height;
  const double alpha = SabineAbsorption(volume, rt60) / surface;
  const double perimeter = 2.0 * (width + height), section = width * height;
  const double k = perimeter / section * std::sqrt(3.0 * alpha) / 4.0;  // 1/m, energy
  const double diffusion_db_per_m = 10.0 * std::log10(std::exp(1.0)) * k;
  EXPECT_GT(diffusion_db_per_m, 0.7);  // a corridor, as Kang measured them
  EXPECT_LT(diffusion_db_per_m, 2.0);

  // The slope between 8 and 28 m from a source near one end (away from the ends, where the
  // diffusion solution bends).
  const Eigen::Vector2d source(2.0, 1.1);
  const double near = corridor.RelativeLevelDb(source, {10.0, 1.1});
  const double far = corridor.RelativeLevelDb(source, {30.0, 1.1});
  const double chain_db_per_m = (near - far) / 20.0;
  EXPECT_NEAR(chain_db_per_m, diffusion_db_per_m, 0.15 * diffusion_db_per_m)
      << "chain " << chain_db_per_m << " dB/m, diffusion " << diffusion_db_per_m << " dB/m";

  // Kept whole, the corridor is one field again.
  acoustics.rooms->corridor_elongation = 0.0;
  const RoomCoupling whole(floor.map(), acoustics);
  EXPECT_EQ(whole.zones().zones().size(), 1u);
  EXPECT_DOUBLE_EQ(whole.RelativeLevelDb(source, {30.0, 1.1}), 0.0);
}

// Four corridors 20 x 3 m side by side, each joined to the next by a 1 m door at alternating
// ends (the serpentine the coupled-rooms issue measured, doors where it had open ends), RT60
// 0.9 s: one source at the start of the first corridor.
Floor Serpentine() {
  Floor floor(20.2, 12.8, 0.1);
  for (int k = 1; k < 4; ++k) {
    const double y = 0.1 + k * 3.1;  // the wall between corridor k-1 and k
    floor.Wall(0, y, 20.2, y + 0.1);
    const double door_x = (k % 2 == 1) ? 18.5 : 0.7;
    floor.Door(door_x, y - 0.05, door_x + 1.0, y + 0.15);
  }
  return floor;
}

TEST(RoomCoupling, TheReverberantFieldFallsAtLeast8DbAtEachDoorwayOfASerpentine) {
  const Floor floor = Serpentine();
  const PropagationModel propagation(floor.map(), Options());
  const AcousticModel model(propagation, Building(0.9), test::FlatTable("nava"), {});
  ASSERT_NE(model.rooms(), nullptr);
  EXPECT_EQ(model.rooms()->segmentation().rooms().size(), 4u);
  const Eigen::Vector2d source(1.5, 1.6);
  double last = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d listener(10.0, 1.6 + k * 3.2);
    const SoundPath path = propagation.Path(source, listener);
    ASSERT_TRUE(path.reachable) << k;
    const double level = model.Levels(path, listener).reverberant_db;
    if (k > 0) {
      EXPECT_LT(level, last - 8.0) << "corridor " << k;
    }
    last = level;
  }
}

// The coupled-rooms issue's serpentine (RT60 0.9 s, 45 dB of ambient noise, a speaker of 70 dB at
// 1 m), its corridors joined by doors: with one field the robot three corridors away hears the
// whole building's reverberation over the ambient; in coupled rooms the shipped nava table no
// longer decodes it.
TEST(RoomCoupling, ThreeCorridorsAwayNavaNoLongerHearsThroughTheDoors) {
  const std::string shipped = ShippedDecodeTable("nava");
  if (!std::filesystem::exists(shipped)) GTEST_SKIP() << "no shipped nava table (" << shipped << ")";
  const DecodeTable table = LoadDecodeTable(shipped, "nava");
  const Floor floor = Serpentine();
  const PropagationModel propagation(floor.map(), Options());
  world_sim::Acoustics coupled = Building(0.9);
  coupled.ambient_db = 45.0;
  world_sim::Acoustics single = coupled;
  single.rooms.reset();
  single.room.volume = 20.0 * 12.4 * 3.0;  // the whole floor, as a world without rooms gives it
  const AcousticModel rooms(propagation, coupled, table, {});
  const AcousticModel hall(propagation, single, table, {});
  const Eigen::Vector2d source(1.5, 1.6), far(10.0, 1.6 + 3 * 3.2);
  const SoundPath path = propagation.Path(source, far);
  ASSERT_TRUE(path.reachable);
  const LinkPrediction in_rooms = rooms.Predict(path, far, rooms.NoiseAt(far, 0.0, {}));
  const LinkPrediction in_hall = hall.Predict(path, far, hall.NoiseAt(far, 0.0, {}));
  EXPECT_GT(in_hall.signal.reverberant_db, 45.0 + 5.0);   // the hall's field, over the ambient
  EXPECT_LT(in_rooms.signal.reverberant_db, 45.0 - 10.0);  // three doors down, under it
  EXPECT_LT(in_rooms.probability, 0.01) << "one field: " << in_hall.probability << ", reverberant "
                                        << in_hall.signal.reverberant_db << " against " << in_rooms.signal.reverberant_db;
}

}  // namespace
}  // namespace audio_propagation
