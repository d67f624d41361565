// Measured rooms moved to other figures (moved_response.h, moved_rooms.h): the moved room reads
// the RT60 and DRR asked and keeps its direct sound and the pattern of its first reflections; a
// room is only made faster; a pool draws by seed from rooms that decay at least as slowly and
// never from one with an arrival before its loudest peak. The renderer's rooms stand in for
// measured ones.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/measured_like_response.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/moved_response.h"
#include "nava_modem/moved_rooms.h"
#include "measured_rooms.h"
#include "nava_modem/room_channel.h"

namespace nava_modem {
namespace {

constexpr double kRate = 48000.0;

// The message of what `f` throws as std::invalid_argument, or "accepted".
template <typename F>
std::string Refusal(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(MovedResponse, ReadsTheRt60AndDrrAskedAndKeepsItsDirectSoundAndReflections) {
  const std::vector<float> room = MeasuredLikeResponse(1.6, 2.0, kRate, 7);
  const ResponseMeasures own = MeasureResponse(room, kRate);
  for (double rt60 : {0.3, 0.6, 1.2}) {
    for (double drr : {-24.0, -6.0, 0.0, 12.0}) {
      const std::vector<float> moved = MovedResponse(room, kRate, rt60, drr);
      EXPECT_NEAR(MeasureResponse(moved, kRate).rt60_s, rt60, kMovedRt60Tolerance * rt60 + 1e-3) << rt60 << " " << drr;
      EXPECT_NEAR(DirectOverReverberantDb(moved, own.peak, kRate), drr, 0.01) << rt60 << " " << drr;
      // MeasureResponse reads the same where the direct sound is the largest peak.
      if (drr >= 0.0) {
        EXPECT_NEAR(MeasureResponse(moved, kRate).drr_db, drr, 0.5) << rt60 << " " << drr;
      }
      EXPECT_LE(moved.size(), own.peak + static_cast<std::size_t>(std::ceil(kMovedLengthRt60 * rt60 * kRate)));
      // The direct sound as it was; the first 10 ms after it one pattern, scaled and tilted by
      // the faster decay (within a few per cent over 10 ms).
      for (std::size_t k = 0; k <= own.peak; ++k) ASSERT_EQ(moved[k], room[k]);
      const std::size_t from = own.peak + static_cast<std::size_t>(0.003 * kRate), to = own.peak + static_cast<std::size_t>(0.010 * kRate);
      double cross = 0.0, a = 0.0, b = 0.0;
      for (std::size_t k = from; k < to; ++k) {
        cross += static_cast<double>(moved[k]) * room[k];
        a += static_cast<double>(moved[k]) * moved[k];
        b += static_cast<double>(room[k]) * room[k];
      }
      EXPECT_GT(cross / std::sqrt(a * b), 0.99) << rt60 << " " << drr;
    }
  }
}

TEST(MovedResponse, ARoomIsOnlyMadeFasterAndImpossibleFiguresAreNamed) {
  const std::vector<float> room = MeasuredLikeResponse(0.8, 0.0, kRate, 3);
  EXPECT_NE(Refusal([&] { MovedResponse(room, kRate, 1.6, 0.0); }).find("at most the response's own"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedResponse(room, kRate, 0.0, 0.0); }).find("RT60"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedResponse(room, kRate, std::nan(""), 0.0); }).find("RT60"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedResponse(room, kRate, 0.5, 41.0); }).find("DRR"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedResponse(room, kRate, 0.5, std::nan("")); }).find("DRR"), std::string::npos);
  // A response too short to have figures.
  const std::vector<float> cut(room.begin(), room.begin() + 600);
  EXPECT_NE(Refusal([&] { MovedResponse(cut, kRate, 0.5, 0.0); }).find("too short"), std::string::npos);
}

MovableRoom Room(const std::string& name, double rt60, std::uint32_t seed) {
  MovableRoom r;
  r.name = name;
  r.response = MeasuredLikeResponse(rt60, 0.0, kRate, seed);
  return r;
}

TEST(MovedRooms, DrawsBySeedFromRoomsThatDecayAtLeastAsSlowlyAndNeverFromOneWithAnEarlierArrival) {
  std::vector<MovableRoom> rooms{Room("a", 0.5, 1), Room("b", 0.9, 2), Room("c", 1.3, 3), Room("d", 4.0, 4)};
  // An echo: a weaker arrival 20 ms before the loudest peak.
  MovableRoom echo = Room("echo", 1.0, 5);
  std::vector<float> early(echo.response.size() + 960, 0.0f);
  for (std::size_t k = 0; k < echo.response.size(); ++k) early[k + 960] = echo.response[k];
  for (std::size_t k = 0; k < 40; ++k) early[k] = 0.5f * echo.response[k];
  echo.response = early;
  rooms.push_back(echo);
  const MovedRooms pool(rooms, kRate);
  ASSERT_EQ(pool.excluded(), (std::vector<std::size_t>{4}));
  // [rt60, 3 x rt60], at least six where there are as many: here all that decay slowly enough.
  EXPECT_EQ(pool.Candidates(0.45), (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(pool.Candidates(1.2), (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(pool.Candidates(3.0), (std::vector<std::size_t>{3}));
  EXPECT_NE(Refusal([&] { pool.Candidates(4.5); }).find("no room decays as slowly"), std::string::npos);
  // The same seed, the same room moved the same; kept for the next draw.
  const MovedRooms::Drawn first = pool.Draw(0.45, -6.0, 11), again = pool.Draw(0.45, -6.0, 11);
  EXPECT_EQ(first.response.get(), again.response.get());
  const MovedRooms::Drawn anew = pool.Move(0.45, -6.0, 11);
  EXPECT_EQ(*anew.response, *first.response);
  EXPECT_EQ(anew.room, first.room);
  EXPECT_EQ(first.peak, pool.rooms()[first.room].figures.peak);
  int drawn[4] = {0, 0, 0, 0};
  for (std::uint32_t seed = 0; seed < 40; ++seed) ++drawn[pool.Draw(0.45, 0.0, seed).room];
  for (int n : drawn) EXPECT_EQ(n, 10);
}

// A room measured from several places weighs as much as one measured from one: the draw picks a
// room (group), then a place in it.
TEST(MovedRooms, ARoomMeasuredFromManyPlacesWeighsAsOne) {
  std::vector<MovableRoom> rooms{Room("hall_1", 0.8, 1), Room("hall_2", 0.8, 2), Room("hall_3", 0.8, 3),
                                 Room("kitchen", 0.8, 4)};
  for (int k = 0; k < 3; ++k) rooms[k].group = "hall";
  const MovedRooms pool(rooms, kRate);
  int drawn[4] = {0, 0, 0, 0};
  for (std::uint32_t seed = 0; seed < 60; ++seed) ++drawn[pool.Move(0.5, 0.0, seed).room];
  EXPECT_EQ(drawn[3], 30);
  EXPECT_EQ(drawn[0] + drawn[1] + drawn[2], 30);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(drawn[k], 10);
  // Rooms by their files' names: the parts before the first that holds a digit or a sign.
  EXPECT_EQ(tools::RoomOfFile("/r/pori_s1_r2_b.wav"), "/r/pori");
  EXPECT_EQ(tools::RoomOfFile("/r/warehouse_7_4.wav"), "/r/warehouse");
  EXPECT_EQ(tools::RoomOfFile("/r/brir_sweep_Netzwerkakademie_headaz+40.wav"), "/r/brir_sweep_Netzwerkakademie");
  EXPECT_EQ(tools::RoomOfFile("/r/house_kitchen.wav"), "/r/house_kitchen");
  EXPECT_EQ(tools::RoomOfFile("/r/3d_hall.flac"), "/r/3d_hall");
}

TEST(MovedRooms, RoomsThatCannotServeAreNamed) {
  std::vector<MovableRoom> rooms{Room("fine", 0.5, 1), Room("short", 0.5, 2)};
  rooms[1].response.resize(600);
  EXPECT_NE(Refusal([&] { MovedRooms(rooms, kRate); }).find("short cannot serve"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedRooms({}, kRate); }).find("at least one"), std::string::npos);
  EXPECT_NE(Refusal([&] { MovedRooms({Room("fine", 0.5, 1)}, 8000.0); }).find("sample rate"), std::string::npos);
}

// A table measured over such rooms names them "measured"; a room of that model is the response
// given, so one without it is refused by field.
TEST(MovedRooms, TheMeasuredModelIsARoomGivenAsAResponse) {
  ASSERT_EQ(ParseRoomModel("measured"), RoomOptions::Model::kMeasured);
  EXPECT_STREQ(RoomModelName(RoomOptions::Model::kMeasured), "measured");
  RoomOptions o;
  o.model = RoomOptions::Model::kMeasured;
  try {
    ValidateRoomOptions(o, kRate);
    ADD_FAILURE() << "a measured room without its response was accepted";
  } catch (const RoomOptionError& e) {
    EXPECT_EQ(e.field(), "model");
  }
  o.response = MeasuredLikeResponse(0.5, 0.0, kRate, 1);
  EXPECT_NO_THROW(ValidateRoomOptions(o, kRate));
}

}  // namespace
}  // namespace nava_modem
