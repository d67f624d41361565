#include "grid/room_segmentation.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace grid {
namespace {

constexpr double kResolution = 0.05;  // m a cell

// A floor plan drawn in metres: everything starts free, walls are filled boxes.
class Floor {
 public:
  Floor(double width, double height)
      : map_(static_cast<int>(width / kResolution + 0.5), static_cast<int>(height / kResolution + 0.5), kResolution) {
    Wall(0, 0, width, 0.1);
    Wall(0, height - 0.1, width, height);
    Wall(0, 0, 0.1, height);
    Wall(width - 0.1, 0, width, height);
  }
  Floor& Wall(double x0, double y0, double x1, double y1) { return Fill(x0, y0, x1, y1, Cell::kOccupied); }
  Floor& Door(double x0, double y0, double x1, double y1) { return Fill(x0, y0, x1, y1, Cell::kFree); }
  const OccupancyMap& map() const { return map_; }

 private:
  Floor& Fill(double x0, double y0, double x1, double y1, Cell c) {
    for (int j = 0; j < map_.height(); ++j) {
      for (int i = 0; i < map_.width(); ++i) {
        const Eigen::Vector2d p = map_.CellCenter(i, j);
        if (p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1) map_.set(i, j, c);
      }
    }
    return *this;
  }
  OccupancyMap map_;
};

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
  OccupancyMap walls(10, 10, kResolution);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) walls.set(i, j, Cell::kOccupied);
  EXPECT_NE(message(walls, {}).find("no free space"), std::string::npos);
}

}  // namespace
}  // namespace grid
