// SpliceResponses (response_splice.h): two responses joined after their direct sounds.
#include "nava_modem/response_splice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <stdexcept>
#include <vector>

#include "known_response.h"

namespace nava_modem {
namespace {

constexpr double kRate = 48000.0;

// The tail twice the head, its direct sound later in its file: at the head's energies the
// splice is the head again, sample for sample, wherever it is cut.
TEST(ResponseSpliceTest, ATailTwiceTheHeadScaledToTheHeadIsTheHead) {
  const std::vector<float> h = KnownResponse(0.4, -5.0, kRate, 480, 7);
  std::vector<float> doubled(480, 0.0f);
  for (const float v : h) doubled.push_back(2.0f * v);
  const PeakedResponse head{h, 480}, tail{doubled, 960};
  for (const std::size_t at : {std::size_t{120}, std::size_t{2400}}) {
    const std::vector<float> out = SpliceResponses(head, tail, head, at, kRate);
    ASSERT_GE(out.size(), h.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < h.size(); ++k) worst = std::max(worst, static_cast<double>(std::fabs(out[k] - h[k])));
    EXPECT_LT(worst, 1e-4) << "cut " << at << " samples after the direct sound";
  }
}

// Each part comes from its own response: the head's samples up to the cut, then the tail's,
// these all scaled by one gain.
TEST(ResponseSpliceTest, EachPartComesFromItsOwnResponse) {
  const std::vector<float> a = KnownResponse(0.3, -3.0, kRate, 480, 1), b = KnownResponse(1.0, -8.0, kRate, 240, 2);
  const PeakedResponse head{a, 480}, tail{b, 240};
  const std::size_t at = 960;
  const std::vector<float> out = SpliceResponses(head, tail, head, at, kRate);
  // Before the cut: a itself (its own energy kept, gain 1).
  for (std::size_t k = 0; k < 480 + at; k += 37) EXPECT_NEAR(out[k], a[k], 1e-5) << k;
  // After it: b's samples, all scaled by one gain.
  const double g = out[480 + at + 10] / b[240 + at + 10];
  for (std::size_t d = at + 10; d < at + 5000; d += 53) EXPECT_NEAR(out[480 + d], g * b[240 + d], 1e-4) << d;
}

TEST(ResponseSpliceTest, RefusesASpliceWithNothingAfterIt) {
  const std::vector<float> a = KnownResponse(0.3, -3.0, kRate, 480, 1);
  const PeakedResponse r{a, 480};
  EXPECT_THROW(SpliceResponses(r, r, r, a.size(), kRate), std::invalid_argument);
  EXPECT_THROW(SpliceResponses(PeakedResponse{a, a.size()}, r, r, 100, kRate), std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
