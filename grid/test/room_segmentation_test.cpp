#include "grid/room_segmentation.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "floor_plan.h"

namespace grid {
namespace {

using test::Floor;
constexpr double kResolution = 0.05;  // m a cell, the floors' default

TEST(RoomSegmentationTest, OneRoomWithNoDoorsIsOneRoomWithNoOpenings) {
  const Floor floor(6.0, 4.0);
  const RoomSegmentation rooms(floor.map(), {});
  ASSERT_EQ(rooms.rooms().size(), 1u);
  EXPECT_TRUE(rooms.openings().empty());
  EXPECT_NEAR(rooms.rooms()[0].area, 5.8 * 3.8, 0.5);
  EXPECT_EQ(rooms.RoomAt({3.0, 2.0}), 0);
  EXPECT_EQ(rooms.RoomAt({0.02, 2.0}), -1);   // in the wall
  EXPECT_EQ(rooms.RoomAt({-1.0, 2.0}), -1);   // off the map
}

TEST(RoomSegmentationTest, TwoRoomsAndTheirDoorAreFound) {
  // Two 5 x 4 m rooms side by side; a 0.9 m door in the wall between them at y = 1.5 .. 2.4.
  Floor floor(10.0, 4.0);
  floor.Wall(4.95, 0, 5.15, 4.0).Door(4.9, 1.5, 5.2, 2.4);
  const RoomSegmentation rooms(floor.map(), {});
  ASSERT_EQ(rooms.rooms().size(), 2u);
  const int left = rooms.RoomAt({2.0, 2.0}), right = rooms.RoomAt({8.0, 2.0});
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  EXPECT_NE(left, right);
  EXPECT_NEAR(rooms.rooms()[left].area, 4.85 * 3.8, 0.6);
  EXPECT_NEAR(rooms.rooms()[right].area, 4.75 * 3.8, 0.6);
  ASSERT_EQ(rooms.openings().size(), 1u);
  const SegmentedOpening& door = rooms.openings()[0];
  EXPECT_EQ(std::min(door.a, door.b), std::min(left, right));
  EXPECT_EQ(std::max(door.a, door.b), std::max(left, right));
  EXPECT_NEAR(door.width, 0.9, 2 * kResolution);
  EXPECT_NEAR(door.center.y(), 1.95, 0.1);
  EXPECT_NEAR(door.center.x(), 5.05, 0.2);
}

TEST(RoomSegmentationTest, ACorridorWithThreeOfficesIsFourRoomsAndThreeDoors) {
  // A 1.6 m corridor along the bottom, three 4 x 4 m offices above it, each with a 0.9 m door.
  Floor floor(12.0, 6.0);
  floor.Wall(0, 1.7, 12.0, 1.85);                                        // corridor wall
  floor.Wall(3.95, 1.7, 4.05, 6.0).Wall(7.95, 1.7, 8.05, 6.0);           // office walls
  floor.Door(1.5, 1.65, 2.4, 1.9).Door(5.5, 1.65, 6.4, 1.9).Door(9.5, 1.65, 10.4, 1.9);
  const RoomSegmentation rooms(floor.map(), {});
  ASSERT_EQ(rooms.rooms().size(), 4u);
  const int corridor = rooms.RoomAt({6.0, 0.9});
  ASSERT_GE(corridor, 0);
  ASSERT_EQ(rooms.openings().size(), 3u);
  for (const SegmentedOpening& door : rooms.openings()) {
    EXPECT_TRUE(door.a == corridor || door.b == corridor);
    EXPECT_NEAR(door.width, 0.9, 2 * kResolution);
  }
  // Each office is its own room.
  const int a = rooms.RoomAt({2.0, 4.0}), b = rooms.RoomAt({6.0, 4.0}), c = rooms.RoomAt({10.0, 4.0});
  EXPECT_NE(a, b);
  EXPECT_NE(b, c);
  EXPECT_NE(a, c);
  EXPECT_NE(a, corridor);
}

TEST(RoomSegmentationTest, AWideOpeningKeepsOneRoom) {
  // An open-plan floor: a 3 m gap in the dividing wall is no door.
  Floor floor(10.0, 6.0);
  floor.Wall(4.95, 0, 5.05, 6.0).Door(4.9, 1.5, 5.1, 4.5);
  const RoomSegmentation rooms(floor.map(), {});
  EXPECT_EQ(rooms.rooms().size(), 1u);
  EXPECT_TRUE(rooms.openings().empty());
}

TEST(RoomSegmentationTest, ARoomSmallerThanTheSmallestJoinsItsNeighbour) {
  // A 1.4 x 1.4 m closet off an L-shaped room through a 0.7 m door.
  Floor floor(6.0, 5.0);
  floor.Wall(0, 3.4, 1.6, 3.5).Wall(1.5, 3.4, 1.6, 5.0).Door(0.3, 3.35, 1.0, 3.55);
  RoomSegmentationOptions options;
  options.min_room_area = 1.0;
  const RoomSegmentation apart(floor.map(), options);
  EXPECT_EQ(apart.rooms().size(), 2u);
  EXPECT_NE(apart.RoomAt({0.8, 4.2}), apart.RoomAt({3.0, 2.0}));
  EXPECT_EQ(apart.openings().size(), 1u);
  options.min_room_area = 3.0;  // the closet's 2 m^2 is too small: it joins the room
  const RoomSegmentation joined(floor.map(), options);
  EXPECT_EQ(joined.rooms().size(), 1u);
  EXPECT_EQ(joined.RoomAt({0.8, 4.2}), joined.RoomAt({3.0, 2.0}));
  EXPECT_TRUE(joined.openings().empty());
}

TEST(RoomSegmentationTest, APillarInACorridorDividesNothingButAWallBetweenTwoDoorsDoes) {
  // A 2.5 m corridor (y 0.1 .. 2.6) with a 0.6 x 0.1 m pillar leaving gaps of 0.8 and 1.1 m, both
  // under two door half-widths from a wall; two rooms north of it (y 2.7 .. 6), each with a door,
  // the wall between the doors 4 m of thin wall standing free of the map's edges only through
  // the doors.
  Floor floor(12.0, 6.0);
  floor.Wall(5.95, 0.9, 6.05, 1.5);               // the pillar
  floor.Wall(0, 2.6, 12.0, 2.7).Wall(5.95, 2.6, 6.05, 6.0);
  floor.Door(1.0, 2.55, 2.0, 2.75).Door(10.0, 2.55, 11.0, 2.75);
  floor.Door(5.9, 5.85, 6.1, 5.95);                // the dividing wall leaves the outer wall
  const RoomSegmentation rooms(floor.map(), {});
  EXPECT_EQ(rooms.rooms().size(), 3u);
  const int corridor = rooms.RoomAt({6.0, 0.5});
  EXPECT_EQ(rooms.RoomAt({3.0, 1.8}), corridor);
  EXPECT_EQ(rooms.RoomAt({9.0, 0.5}), corridor);
  EXPECT_EQ(rooms.RoomAt({6.0, 1.15}), -1);        // the pillar is still no floor
  EXPECT_NE(rooms.RoomAt({3.0, 4.0}), corridor);
  EXPECT_NE(rooms.RoomAt({9.0, 4.0}), corridor);
  EXPECT_NE(rooms.RoomAt({3.0, 4.0}), rooms.RoomAt({9.0, 4.0}));
  // With free-standing obstacles dividing too, the pillar cuts the corridor in two.
  RoomSegmentationOptions pillars_divide;
  pillars_divide.max_obstacle_size = 0.0;
  const RoomSegmentation cut(floor.map(), pillars_divide);
  EXPECT_NE(cut.RoomAt({3.0, 1.8}), cut.RoomAt({9.0, 0.5}));
}

TEST(RoomSegmentationTest, ImpossibleOptionsAndEmptyMapsAreRefusedByName) {
  const Floor floor(4.0, 4.0);
  const auto message = [&](const OccupancyMap& map, RoomSegmentationOptions o) {
    try {
      RoomSegmentation rooms(map, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  RoomSegmentationOptions o;
  o.door_half_width = 0.01;  // under a cell
  EXPECT_NE(message(floor.map(), o).find("door_half_width"), std::string::npos);
  o = {};
  o.min_room_area = -1.0;
  EXPECT_NE(message(floor.map(), o).find("min_room_area"), std::string::npos);
  o = {};
  o.max_obstacle_size = -1.0;
  EXPECT_NE(message(floor.map(), o).find("max_obstacle_size"), std::string::npos);
  OccupancyMap walls(10, 10, kResolution);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) walls.set(i, j, Cell::kOccupied);
  EXPECT_NE(message(walls, {}).find("no free space"), std::string::npos);
}

}  // namespace
}  // namespace grid
