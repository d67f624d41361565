#include "audio_propagation/direction_errors.h"

#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "run_channel.h"

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/audio_channel.h"
#include "audio_propagation/direction_errors_file.h"
#include "audio_propagation/microphone.h"
#include "grid/input_error.h"

namespace audio_propagation {
namespace {

using world_sim::Microphone;

constexpr double kDeg = M_PI / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every omni packet `omni_error` off with confidence `confidence`; the pair right near its axis,
// wrong 20-50 degrees off broadside, silent at broadside.
DirectionCell Cell(double rt60, double drr, double omni_error, double confidence = 0.5) {
  DirectionCell c;
  c.rt60 = rt60;
  c.drr_db = drr;
  for (double truth : {-150.0, -60.0, 10.0, 100.0}) c.omni.push_back({truth * kDeg, (truth + omni_error) * kDeg, confidence});
  c.bidirectional = {{10.0 * kDeg, 5.0 * kDeg, 0.9},      // near the axis: right
                     {170.0 * kDeg, 175.0 * kDeg, 0.9},
                     {60.0 * kDeg, 120.0 * kDeg, 0.3},     // 30 degrees off broadside: wrong
                     {-120.0 * kDeg, -60.0 * kDeg, 0.3},
                     {85.0 * kDeg, kNaN, 0.0},             // broadside: no direction
                     {-95.0 * kDeg, kNaN, 0.0}};
  return c;
}

// Cells of a handful of packets each: drawn from as they are (min_packets 1).
DirectionErrors Table() {
  return DirectionErrors("room", {Cell(0.3, -9.0, 40.0), Cell(0.3, 3.0, 2.0), Cell(1.0, -9.0, 90.0), Cell(1.0, 3.0, 5.0)}, 1);
}

TEST(DirectionErrors, TheNearestCellByRt60RatioAndDrrAndTheGridsEdgesBeyond) {
  const DirectionErrors t = Table();
  EXPECT_EQ(t.Nearest(0.3, 3.0).omni[0].estimate, (-150.0 + 2.0) * kDeg);
  EXPECT_EQ(t.Nearest(0.5, 0.0).rt60, 0.3);   // 0.5 / 0.3 < 1.0 / 0.5
  EXPECT_EQ(t.Nearest(0.6, 0.0).rt60, 1.0);   // 0.6 / 0.3 > 1.0 / 0.6
  EXPECT_EQ(t.Nearest(0.6, -2.9).drr_db, 3.0);
  EXPECT_EQ(t.Nearest(0.6, -3.1).drr_db, -9.0);
  EXPECT_EQ(t.Nearest(9.0, -40.0).rt60, 1.0);
  EXPECT_EQ(t.Nearest(9.0, -40.0).drr_db, -9.0);
  EXPECT_EQ(t.Nearest(0.01, 40.0).rt60, 0.3);
  EXPECT_EQ(t.Nearest(0.01, 40.0).drr_db, 3.0);
}

TEST(DirectionErrors, OmniReportsTheTrueDirectionPlusADrawnPacketsErrorAndItsConfidence) {
  const DirectionErrors t = Table();
  std::mt19937 rng(1);
  for (int k = 0; k < 20; ++k) {
    const SensedDirection s = t.Sense(Microphone::kOmni, 0.5, -9.0, 1.0, rng);
    EXPECT_NEAR(s.direction, 0.5 + 90.0 * kDeg, 1e-9);
    EXPECT_EQ(s.confidence, 0.5);
  }
  // The error wraps round.
  const SensedDirection s = t.Sense(Microphone::kOmni, 3.0, -9.0, 1.0, rng);
  EXPECT_NEAR(s.direction, std::remainder(3.0 + 90.0 * kDeg, 2.0 * M_PI), 1e-9);
  EXPECT_TRUE(std::isnan(t.Sense(Microphone::kNone, 0.5, 3.0, 0.3, rng).direction));
}

TEST(DirectionErrors, AnOmniPacketWithoutADirectionReportsNone) {
  DirectionCell c = Cell(0.5, 0.0, 0.0);
  for (DirectionSample& s : c.omni) s.estimate = kNaN;
  const DirectionErrors t("room", {c}, 1);
  std::mt19937 rng(1);
  const SensedDirection s = t.Sense(Microphone::kOmni, 1.0, 0.0, 0.5, rng);
  EXPECT_TRUE(std::isnan(s.direction));
  EXPECT_EQ(s.confidence, 0.0);
}

TEST(DirectionErrors, ThePairDrawsFromPacketsAsFarOffItsAxis) {
  const DirectionErrors t = Table();
  std::mt19937 rng(3);
  for (int k = 0; k < 30; ++k) {
    // Near the axis: the bit is right, front or back.
    EXPECT_EQ(t.Sense(Microphone::kBidirectional, 20.0 * kDeg, 3.0, 0.3, rng).direction, 0.0);
    EXPECT_EQ(t.Sense(Microphone::kBidirectional, -160.0 * kDeg, 3.0, 0.3, rng).direction, M_PI);
    // 30 degrees off broadside: wrong, with the drawn packet's confidence.
    const SensedDirection wrong = t.Sense(Microphone::kBidirectional, 55.0 * kDeg, 3.0, 0.3, rng);
    EXPECT_EQ(wrong.direction, M_PI);
    EXPECT_EQ(wrong.confidence, 0.3);
    EXPECT_EQ(t.Sense(Microphone::kBidirectional, -125.0 * kDeg, 3.0, 0.3, rng).direction, 0.0);
    // Broadside: none.
    EXPECT_TRUE(std::isnan(t.Sense(Microphone::kBidirectional, 88.0 * kDeg, 3.0, 0.3, rng).direction));
  }
}

TEST(DirectionErrors, ACellWithTooFewPacketsDrawsFromItsDrrAtTheNearestRt60ThatHasEnough) {
  // RT60 0.3, 1 and 2 s at DRR -9 and +3 dB; the wet cells of 1 and 2 s hold one packet or none.
  DirectionCell thin = Cell(1.0, -9.0, 90.0);
  thin.omni.resize(1);
  thin.bidirectional.resize(1);
  DirectionCell empty = Cell(2.0, -9.0, 120.0);
  empty.omni.clear();
  empty.bidirectional.clear();
  const DirectionErrors t("nava", {Cell(0.3, -9.0, 40.0), Cell(0.3, 3.0, 2.0), thin, Cell(1.0, 3.0, 5.0), empty,
                                   Cell(2.0, 3.0, 7.0)}, 2);
  std::mt19937 rng(1);
  // Not the drier cell of its RT60 (5 and 7 degrees): the same DRR, 0.3 s.
  EXPECT_NEAR(t.Sense(Microphone::kOmni, 0.5, -9.0, 1.0, rng).direction, 0.5 + 40.0 * kDeg, 1e-9);
  EXPECT_NEAR(t.Sense(Microphone::kOmni, 0.5, -20.0, 2.0, rng).direction, 0.5 + 40.0 * kDeg, 1e-9);
  EXPECT_EQ(&t.Packets(Microphone::kBidirectional, 2.0, -9.0), &t.Nearest(0.3, -9.0).bidirectional);
  // Enough where it is: its own.
  EXPECT_NEAR(t.Sense(Microphone::kOmni, 0.5, 3.0, 2.0, rng).direction, 0.5 + 7.0 * kDeg, 1e-9);
  // No RT60 with enough at -9 dB: the next drier DRR's, at the nearest RT60.
  DirectionCell thin_short = Cell(0.3, -9.0, 40.0);
  thin_short.omni.resize(1);
  const DirectionErrors u("nava", {thin_short, Cell(0.3, 3.0, 2.0), thin, Cell(1.0, 3.0, 5.0), empty, Cell(2.0, 3.0, 7.0)}, 2);
  EXPECT_NEAR(u.Sense(Microphone::kOmni, 0.5, -9.0, 1.0, rng).direction, 0.5 + 5.0 * kDeg, 1e-9);
  // A link the model cannot place gets the wettest, longest cell's draw.
  EXPECT_NEAR(t.Sense(Microphone::kOmni, 0.5, -std::numeric_limits<double>::infinity(), kNaN, rng).direction,
              0.5 + 40.0 * kDeg, 1e-9);
  // Nothing with enough at the driest DRR: refused.
  DirectionCell dry = Cell(1.0, 3.0, 5.0);
  dry.omni.resize(1);
  EXPECT_THROW(DirectionErrors("nava", {Cell(0.3, -9.0, 40.0), Cell(0.3, 3.0, 2.0), Cell(1.0, -9.0, 90.0), dry}, 5),
               std::invalid_argument);
  EXPECT_THROW(DirectionErrors("nava", {Cell(0.3, 3.0, 2.0)}, 0), std::invalid_argument);
}

TEST(DirectionErrors, ATableWithAHoleOrBadPacketsIsRefused) {
  EXPECT_NO_THROW(DirectionErrors("room", {Cell(0.3, -9.0, 0.0)}, 1));
  EXPECT_THROW(DirectionErrors("room", {}, 1), std::invalid_argument);
  // 0.3 s with -9 and 3 dB, 1.0 s with -9 only.
  EXPECT_THROW(DirectionErrors("room", {Cell(0.3, -9.0, 0.0), Cell(0.3, 3.0, 0.0), Cell(1.0, -9.0, 0.0)}, 1),
               std::invalid_argument);
  EXPECT_THROW(DirectionErrors("room", {Cell(0.3, -9.0, 0.0), Cell(0.3, -9.0, 1.0)}, 1), std::invalid_argument);
  EXPECT_THROW(DirectionErrors("room", {Cell(0.0, -9.0, 0.0)}, 1), std::invalid_argument);
  DirectionCell empty = Cell(0.3, 0.0, 0.0);
  empty.bidirectional.clear();
  EXPECT_THROW(DirectionErrors("room", {empty}, 1), std::invalid_argument);
  DirectionCell sure = Cell(0.3, 0.0, 0.0, 1.5);
  EXPECT_THROW(DirectionErrors("room", {sure}, 1), std::invalid_argument);
  // Four packets a cell are too few for the default.
  EXPECT_THROW(DirectionErrors("room", {Cell(0.3, -9.0, 0.0)}), std::invalid_argument);
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/direction_errors_" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

const char* kTwoCells = R"(profile: room
command: "by hand"
snr_db: 20
packets: 2
min_packets: 1
rt60_s: [0.5]
drr_db: [-6, 6]
arrays:
  omni: "a square"
  bidirectional: "a pair"
cells:
  - rt60_s: 0.5
    drr_db: -6
    sent: 2
    omni: [[10.0, 40.0, 0.25], [-90.0, .nan, 0.00]]
    bidirectional: [[170.0, 5.0, 0.50]]
  - rt60_s: 0.5
    drr_db: 6
    sent: 2
    omni: [[10.0, 11.0, 0.90]]
    bidirectional: [[170.0, 175.0, 0.80]]
)";

TEST(DirectionErrorsFile, LoadsDegreesAsRadiansAndNanAsNoDirection) {
  const DirectionErrors t = LoadDirectionErrors(WriteFile("good", kTwoCells), "room");
  ASSERT_EQ(t.cells().size(), 2u);
  const DirectionCell& c = t.Nearest(0.5, -6.0);
  ASSERT_EQ(c.omni.size(), 2u);
  EXPECT_NEAR(c.omni[0].truth, 10.0 * kDeg, 1e-12);
  EXPECT_NEAR(c.omni[0].estimate, 40.0 * kDeg, 1e-12);
  EXPECT_EQ(c.omni[0].confidence, 0.25);
  EXPECT_TRUE(std::isnan(c.omni[1].estimate));
  EXPECT_NEAR(t.Nearest(0.5, 6.0).bidirectional[0].estimate, 175.0 * kDeg, 1e-12);
}

// The loader's error for `text`, which must name `field`.
void ExpectRefused(const std::string& name, const std::string& text, const std::string& field,
                   const std::string& profile = "room") {
  const std::string path = WriteFile(name, text);
  try {
    LoadDirectionErrors(path, profile);
    ADD_FAILURE() << name << ": loaded";
  } catch (const grid::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(DirectionErrorsFile, AMalformedTableNamesTheFieldAndTheFile) {
  ExpectRefused("profile", kTwoCells, "profile", "nava");
  ExpectRefused("shape", Replaced(kTwoCells, "[-90.0, .nan, 0.00]", "[-90.0, 0.00]"), "cells[0].omni[1]");
  ExpectRefused("number", Replaced(kTwoCells, "[-90.0, .nan, 0.00]", "[-90.0, west, 0.00]"), "cells[0].omni[1]");
  ExpectRefused("confidence", Replaced(kTwoCells, "[10.0, 11.0, 0.90]", "[10.0, 11.0, 1.90]"), "cells[1].omni[0]");
  ExpectRefused("missing", Replaced(kTwoCells, "    bidirectional: [[170.0, 175.0, 0.80]]\n", ""),
                "cells[1].bidirectional");
  ExpectRefused("hole", Replaced(kTwoCells, "  - rt60_s: 0.5\n    drr_db: 6", "  - rt60_s: 0.9\n    drr_db: 6"), "hole");
  ExpectRefused("key", Replaced(kTwoCells, "packets: 2", "packets: 2\nfudge: 1"), "fudge");
  ExpectRefused("min", Replaced(kTwoCells, "min_packets: 1", "min_packets: 0.5"), "min_packets");
  // By default a cell needs 10 packets: these two have too few.
  ExpectRefused("few", Replaced(kTwoCells, "min_packets: 1\n", ""), "cells");
}

TEST(DirectionErrorsFile, TheShippedTablesLoadForBothProfiles) {
  for (const std::string profile : {"room", "nava"}) {
    const DirectionErrors t = LoadDirectionErrors(ShippedDirectionErrors(profile), profile);
    EXPECT_GE(t.cells().size(), 4u) << profile;
    // Dry rooms point the square within a few degrees more often than not.
    const DirectionCell& dry = t.Nearest(0.3, 9.0);
    int close = 0;
    for (const DirectionSample& s : dry.omni) close += std::isfinite(s.estimate) && std::abs(std::remainder(s.estimate - s.truth, 2 * M_PI)) < 5.0 * kDeg;
    EXPECT_GT(close, static_cast<int>(dry.omni.size()) / 2) << profile;
  }
}

// Two robots 6 m apart on an open strip, the receiver facing the sender.
struct Pair {
  PropagationModel model{grid::OccupancyMap(90, 10, 0.5), [] {
                           PropagationOptions o;
                           o.threshold_db = 0.0;
                           o.threads = 1;
                           return o;
                         }()};
};

TEST(AudioChannel, MeasuredDirectionsComeFromTheTableAtTheLinksDrrAndNeedTheAcousticModel) {
  const Pair pair;
  world_sim::Acoustics a;
  a.room.rt60 = 0.3;
  a.room.critical_distance = 2.0;
  a.ambient_db = 0.0;
  const AcousticModel acoustic(pair.model, a, test::FlatTable("nava", 1.0), {});
  ChannelOptions o;
  o.direction_errors = std::make_shared<const DirectionErrors>(Table());
  EXPECT_THROW(AudioChannel(pair.model, {Microphone::kOmni, Microphone::kOmni}, o), std::invalid_argument);

  AudioChannel channel(pair.model, {Microphone::kBidirectional, Microphone::kOmni}, o, &acoustic);
  channel.SetPose(0, {10.0, 2.5, 0.0});
  channel.SetPose(1, {16.0, 2.5, M_PI});  // the two face each other: each hears the other ahead
  const LinkLevels levels = acoustic.Levels(pair.model.Path({10.0, 2.5}, {16.0, 2.5}), {16.0, 2.5});
  const DirectionCell& cell = o.direction_errors->Nearest(levels.rt60, levels.drr_db);
  const double omni_error = cell.omni[0].estimate - cell.omni[0].truth;
  test::RunFor(channel, 10.0);  // the robots' MACs calibrate their carrier thresholds first
  for (int k = 0; k < 5; ++k) {
    for (std::size_t sender : {0u, 1u}) {
      channel.Send(sender, {1, 2, 3, static_cast<std::uint8_t>(k)});
      const AudioChannel::Events events = test::RunFor(channel, 3.0);
      ASSERT_EQ(events.received.size(), 1u);
      const Reception& rx = events.received[0];
      if (rx.receiver == 1) {
        // From straight ahead, off by the cell's error.
        EXPECT_NEAR(std::remainder(rx.direction - omni_error, 2 * M_PI), 0.0, 1e-9);
        EXPECT_EQ(rx.direction_confidence, 0.5);
      } else {
        EXPECT_EQ(rx.direction, 0.0);  // on the pair's axis, ahead: right
        EXPECT_EQ(rx.direction_confidence, 0.9);
      }
    }
  }
}

}  // namespace
}  // namespace audio_propagation
