// A microphone array's recordings, rendered by nava_room's array renderer in a reverberant room,
// decoded as the link does it: the bearing of every packet within a stated band.
#include "nava_modem/array_decode.h"

#include <cmath>

#include <gtest/gtest.h>

#include "nava_modem/room_array.h"

namespace nava_modem {
namespace {

// One room packet from `bearing` (rad) at 2 m in a room with RT60 0.5 s and DRR 0 dB, heard by
// `mics`, decoded; the packet's direction (NaN if it was not decoded).
double HeardFrom(const std::vector<Microphone2D>& mics, double bearing, unsigned seed) {
  ModemOptions o;
  o.sample_rate = 16000.0;
  const auto profile = MakeProfile(Profile::kRoom, o);
  std::vector<float> clean(static_cast<std::size_t>(0.4 * o.sample_rate), 0.0f);
  const std::vector<float> burst = profile->ModulatePacket({1, 2, 3, 4});
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.4 * o.sample_rate), 0.0f);
  RoomOptions room;
  room.rt60 = 0.5;
  room.drr_db = 0.0;
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = 10.0;
  room.seed = seed;
  ArraySource source;
  source.mics = mics;
  source.bearing = bearing;
  for (const RxEvent& e : DecodeArray(*profile, {}, RenderRoomArray(clean, o.sample_rate, room, source), mics)) {
    if (e.kind == RxEvent::Kind::kPacket) return e.direction;
  }
  return std::nan("");
}

double ErrorDeg(double estimate, double truth) {
  return std::abs(std::remainder(estimate - truth, 2.0 * M_PI)) * 180.0 / M_PI;
}

TEST(ArrayDecode, SquareFindsBearingsAllRoundInAReverberantRoom) {
  const double h = 0.1 / std::sqrt(2.0);
  const std::vector<Microphone2D> square = {{h, h}, {-h, h}, {-h, -h}, {h, -h}};
  for (int deg = 0; deg < 360; deg += 30) {
    const double truth = deg * M_PI / 180.0;
    const double estimate = HeardFrom(square, truth, 100 + static_cast<unsigned>(deg));
    ASSERT_TRUE(std::isfinite(estimate)) << deg << " deg";
    EXPECT_LT(ErrorDeg(estimate, truth), 5.0) << deg << " deg";  // about 0.2 deg when written
  }
}

TEST(ArrayDecode, PairTellsFrontFromBackAndSaysNothingFromTheSide) {
  const std::vector<Microphone2D> pair = {{0.1, 0.0}, {-0.1, 0.0}};
  for (int deg : {0, 40, 140, 180, 220, 320}) {
    const double truth = deg * M_PI / 180.0;
    const double estimate = HeardFrom(pair, truth, 200 + static_cast<unsigned>(deg));
    ASSERT_TRUE(std::isfinite(estimate)) << deg << " deg";
    EXPECT_NEAR(estimate, std::cos(truth) > 0.0 ? 0.0 : M_PI, 1e-9) << deg << " deg";
  }
  EXPECT_TRUE(std::isnan(HeardFrom(pair, M_PI / 2.0, 300))) << "from the side a pair must not guess";
}

}  // namespace
}  // namespace nava_modem
