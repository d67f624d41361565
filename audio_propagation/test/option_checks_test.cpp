// The options checks beside audio_propagation's options structs: a wrong value is refused with
// a message naming the field and the value; the defaults pass.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/channel_validation.h"
#include "audio_propagation/scene_render.h"

namespace audio_propagation {
namespace {

// What ValidateOptions(o) throws, or "accepted".
template <typename Options>
std::string Refusal(const Options& o) {
  try { ValidateOptions(o); } catch (const std::invalid_argument& e) { return e.what(); }
  return "accepted";
}

#define EXPECT_REFUSED(options, words) \
  EXPECT_NE(Refusal(options).find(words), std::string::npos) << Refusal(options)

TEST(ChannelOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal(ChannelOptions{}), "accepted");
  ChannelOptions o;
  o.capture_margin_db = -1.0;
  EXPECT_REFUSED(o, "capture_margin_db (dB) must be >= 0, got -1");
  o = {};
  o.direction_noise = std::nan("");
  EXPECT_REFUSED(o, "direction_noise (rad) must be >= 0, got nan");
  o = {};
  o.noise_floor_db = -INFINITY;
  EXPECT_REFUSED(o, "noise_floor_db must be a finite level in dB, got -inf");
}

TEST(SceneRenderOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal(SceneRenderOptions{}), "accepted");
  SceneRenderOptions o;
  o.sample_rate = 0.0;
  EXPECT_REFUSED(o, "scene renderer: sample rate 0 Hz: expected 4000 to 384000");
  o = {};
  o.level_step = 0.0;
  EXPECT_REFUSED(o, "level_step (s) must be > 0, got 0");
}

TEST(ValidationOptions, ImpossibleValuesAreNamed) {
  EXPECT_EQ(Refusal(ValidationOptions{}), "accepted");
  ValidationOptions o;
  o.threads = 0;
  EXPECT_REFUSED(o, "validation threads must be >= 1, got 0");
  o = {};
  o.min_separation = -0.5;
  EXPECT_REFUSED(o, "validation min_separation (m) must be >= 0, got -0.5");
  o = {};
  o.sample_rate = 1e6;
  EXPECT_REFUSED(o, "validation sample rate 1e+06 Hz");
}

}  // namespace
}  // namespace audio_propagation
