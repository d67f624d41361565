#include "audio_propagation/coupled_rooms.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace audio_propagation {
namespace {

// The closed forms below are written out from the two-room energy balance on paper (Kuttruff,
// Room Acoustics, "coupled rooms"), not from the class's matrices.

double Db(double x) { return 10.0 * std::log10(x); }

TEST(CoupledRoomsTest, SabineAbsorptionIsPointOneSixOneVOverT) {
  EXPECT_NEAR(SabineAbsorption(100.0, 0.5), 0.161 * 100.0 / 0.5, 0.2);
  EXPECT_NEAR(SabineAbsorption(1285.0, 0.5), 0.161 * 1285.0 / 0.5, 2.0);
}

TEST(CoupledRoomsTest, ARoomWithNoOpeningsIsTheSingleDiffuseRoom) {
  const CoupledRooms one({{"hall", 300.0, 1.2}}, {});
  EXPECT_EQ(one.RelativeLevelDb(0, 0), 0.0);  // exactly: today's model, bit for bit
  ASSERT_EQ(one.DecayRates().size(), 1u);
  EXPECT_NEAR(one.DecayRates()[0], 6.0 * std::log(10.0) / 1.2, 1e-9);
  // 60 dB down after its RT60.
  EXPECT_NEAR(one.DecayDb(0, 0, 1.2), -60.0, 1e-9);
  EXPECT_NEAR(one.DecayDb(0, 0, 0.0), 0.0, 1e-12);
}

TEST(CoupledRoomsTest, TwoRoomsMatchTheSteadyEnergyBalance) {
  // Two offices (A about 20 m^2 each) joined by a 2 m^2 door.
  const double v1 = 60.0, t1 = 0.5, v2 = 80.0, t2 = 0.7, s = 2.0;
  const CoupledRooms rooms({{"a", v1, t1}, {"b", v2, t2}}, {{0, 1, s}});
  const double a1 = SabineAbsorption(v1, t1), a2 = SabineAbsorption(v2, t2);
  // Source in room a: E2 / E1 = S / (A2 + S); E1 (relative to a shut) = A1 (A2 + S) / det.
  const double det = (a1 + s) * (a2 + s) - s * s;
  EXPECT_NEAR(rooms.RelativeLevelDb(0, 0), Db(a1 * (a2 + s) / det), 1e-9);
  EXPECT_NEAR(rooms.RelativeLevelDb(0, 0) - rooms.RelativeLevelDb(0, 1), Db((a2 + s) / s), 1e-9);
  // The level difference through one ordinary door: about 8 to 12 dB.
  EXPECT_GT(rooms.RelativeLevelDb(0, 0) - rooms.RelativeLevelDb(0, 1), 8.0);
  EXPECT_LT(rooms.RelativeLevelDb(0, 0) - rooms.RelativeLevelDb(0, 1), 12.0);
  // And from the other side.
  EXPECT_NEAR(rooms.RelativeLevelDb(1, 1) - rooms.RelativeLevelDb(1, 0), Db((a1 + s) / s), 1e-9);
}

TEST(CoupledRoomsTest, EveryWattPutInIsAbsorbedByTheWalls) {
  // A chain with a side room: the absorbed power sum_i A_i E_i equals the source's, 4 W / c
  // over (c / 4): relative to the source room shut, sum_i A_i E_i / (A_s E_s,shut) = 1.
  const CoupledRooms rooms({{"a", 50.0, 0.4}, {"b", 200.0, 1.5}, {"c", 70.0, 0.6}, {"d", 30.0, 0.3}},
                           {{0, 1, 2.0}, {1, 2, 3.5}, {1, 3, 1.6}});
  for (std::size_t src = 0; src < rooms.size(); ++src) {
    double absorbed = 0.0;
    for (std::size_t i = 0; i < rooms.size(); ++i) {
      absorbed += rooms.Absorption(i) * std::pow(10.0, rooms.RelativeLevelDb(src, i) / 10.0);
    }
    EXPECT_NEAR(absorbed / rooms.Absorption(src), 1.0, 1e-9) << "source in room " << src;
  }
}

TEST(CoupledRoomsTest, AChainLosesTheSameAtEachDoorAsItsClosedForm) {
  // Rooms a - b - c in a row: the last room only hears b, so E_c / E_b = S_bc / (A_c + S_bc),
  // and the field falls door by door.
  const double s1 = 2.0, s2 = 1.8;
  const CoupledRooms chain({{"a", 60.0, 0.5}, {"b", 60.0, 0.5}, {"c", 60.0, 0.5}}, {{0, 1, s1}, {1, 2, s2}});
  const double ac = chain.Absorption(2);
  EXPECT_NEAR(chain.RelativeLevelDb(0, 1) - chain.RelativeLevelDb(0, 2), Db((ac + s2) / s2), 1e-9);
  EXPECT_GT(chain.RelativeLevelDb(0, 0) - chain.RelativeLevelDb(0, 1), 8.0);
  EXPECT_GT(chain.RelativeLevelDb(0, 1) - chain.RelativeLevelDb(0, 2), 8.0);
  // Symmetric: a source in c is heard in a as a source in a is heard in c, scaled by absorption.
  EXPECT_NEAR(chain.RelativeLevelDb(0, 2), chain.RelativeLevelDb(2, 0), 1e-9);  // equal A
}

TEST(CoupledRoomsTest, ARoomWithTwoDoorsFeedsEachNeighbourByItsOwnDoor) {
  // Room a opens on b (2 m^2) and on c (4 m^2); b and c do not touch.
  const CoupledRooms rooms({{"a", 90.0, 0.6}, {"b", 60.0, 0.5}, {"c", 60.0, 0.5}}, {{0, 1, 2.0}, {0, 2, 4.0}});
  const double ab = rooms.Absorption(1), ac = rooms.Absorption(2);
  EXPECT_NEAR(rooms.RelativeLevelDb(0, 0) - rooms.RelativeLevelDb(0, 1), Db((ab + 2.0) / 2.0), 1e-9);
  EXPECT_NEAR(rooms.RelativeLevelDb(0, 0) - rooms.RelativeLevelDb(0, 2), Db((ac + 4.0) / 4.0), 1e-9);
  // The wider door lets more through.
  EXPECT_GT(rooms.RelativeLevelDb(0, 2), rooms.RelativeLevelDb(0, 1));
}

TEST(CoupledRoomsTest, TwoRoomsDecayWithTheTwoRatesOfTheirClosedForm) {
  // A dead office (0.4 s) opening onto a live hall (2.5 s): the office's decay bends from its
  // own slope to the hall's (the double slope).
  const double v1 = 60.0, t1 = 0.4, v2 = 1500.0, t2 = 2.5, s = 3.0;
  const CoupledRooms rooms({{"office", v1, t1}, {"hall", v2, t2}}, {{0, 1, s}});
  const double c = kSoundSpeed;
  const double a1 = SabineAbsorption(v1, t1), a2 = SabineAbsorption(v2, t2);
  // dE/dt = -K E, K = [[c (A1 + S) / 4 V1, -c S / 4 V1], [-c S / 4 V2, c (A2 + S) / 4 V2]].
  const double k11 = c * (a1 + s) / (4 * v1), k12 = -c * s / (4 * v1);
  const double k21 = -c * s / (4 * v2), k22 = c * (a2 + s) / (4 * v2);
  const double tr = k11 + k22, det = k11 * k22 - k12 * k21;
  const double slow = (tr - std::sqrt(tr * tr - 4 * det)) / 2, fast = (tr + std::sqrt(tr * tr - 4 * det)) / 2;
  ASSERT_EQ(rooms.DecayRates().size(), 2u);
  EXPECT_NEAR(rooms.DecayRates()[0], slow, 1e-9 * fast);
  EXPECT_NEAR(rooms.DecayRates()[1], fast, 1e-9 * fast);
  // A source in the office, heard in the office: early on it falls near the office's own rate,
  // late at the hall's (the slow mode), each slope read off the curve.
  const double dt = 0.01;
  const double early = (rooms.DecayDb(0, 0, 0.0) - rooms.DecayDb(0, 0, dt)) / dt;  // dB/s
  const double late = (rooms.DecayDb(0, 0, 3.0) - rooms.DecayDb(0, 0, 3.0 + dt)) / dt;
  const double db_per_rate = 10.0 / std::log(10.0);  // a rate r falls 10 log10(e) r dB/s
  EXPECT_NEAR(late, slow * db_per_rate, 0.01 * slow * db_per_rate);
  EXPECT_GT(early, 0.8 * 60.0 / t1);  // near the office's own 150 dB/s
  EXPECT_LT(late, 1.05 * 60.0 / t2 + 1.0);  // near the hall's 24 dB/s
  // It starts at the steady level.
  EXPECT_NEAR(rooms.DecayDb(0, 1, 0.0), rooms.RelativeLevelDb(0, 1), 1e-9);
}

TEST(CoupledRoomsTest, ImpossibleRoomsAndOpeningsAreRefusedByName) {
  const auto message = [](const std::vector<CoupledRoomSpec>& r, const std::vector<RoomOpening>& o) {
    try {
      CoupledRooms rooms(r, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({}, {}).find("no rooms"), std::string::npos);
  EXPECT_NE(message({{"a", 0.0, 0.5}}, {}).find("'a').volume"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 0.0}}, {}).find("'a').rt60"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 25.0}}, {}).find("(0, 20]"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 0.5}}, {{0, 1, 2.0}}).find("there are 1"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 0.5}, {"b", 10.0, 0.5}}, {{1, 1, 2.0}}).find("to itself"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 0.5}, {"b", 10.0, 0.5}}, {{0, 1, -1.0}}).find("opening 0.area"), std::string::npos);
  EXPECT_NE(message({{"a", 10.0, 0.5}, {"b", 10.0, 0.5}}, {{0, 1, NAN}}).find("opening 0.area"), std::string::npos);
}

}  // namespace
}  // namespace audio_propagation
