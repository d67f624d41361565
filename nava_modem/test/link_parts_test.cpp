// The parts a NavaLink is wired from, each alone: the capture's history of every channel, the
// capture (reblocking, lag) and the playback (what is in flight when the device fails).
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "failing_device.h"
#include "nava_modem/capture_history.h"
#include "nava_modem/link_capture.h"
#include "nava_modem/link_playback.h"

namespace nava_modem {
namespace {

using test_doubles::FailingDevice;
using test_doubles::ManualClock;

FailingDevice::Options Device(std::vector<float> input, std::size_t delay = 0) {
  FailingDevice::Options o;
  o.input = std::move(input);
  o.delay = delay;
  return o;
}

std::vector<float> Ramp(std::size_t n) {
  std::vector<float> v(n);
  std::iota(v.begin(), v.end(), 1.0f);
  return v;
}

TEST(CaptureHistory, KeepsEachChannelByFrameAndSilenceAfterAFailure) {
  CaptureHistory history(2, 6.0);  // rounded up to 8 frames, of which 7 are told
  const std::vector<float> block = {1, -1, 2, -2, 3, -3};
  history.Record(block.data(), 3);
  history.RecordSilence(2);
  history.Record(block.data(), 3);
  EXPECT_EQ(history.end(), 8);
  EXPECT_EQ(history.oldest(), 1);
  std::vector<std::vector<float>> span;
  history.Copy(1, 8, span);
  ASSERT_EQ(span.size(), 2u);
  EXPECT_EQ(span[0], (std::vector<float>{2, 3, 0, 0, 1, 2, 3}));
  EXPECT_EQ(span[1], (std::vector<float>{-2, -3, 0, 0, -1, -2, -3}));
}

TEST(LinkCapture, HandsOutTheInputInTicksOfAnyLengthFromWholeBlocks) {
  ManualClock clock;
  FailingDevice device(Device(Ramp(1000)), clock);
  LinkCapture capture(CaptureOptions{16000.0, 80, 0.1, 0.0}, device, clock);
  std::vector<float> heard;
  for (std::size_t tick : {33u, 7u, 160u, 1u, 99u}) {
    std::vector<float> out(tick);
    ASSERT_TRUE(capture.Take(out.data(), tick, 0));
    heard.insert(heard.end(), out.begin(), out.end());
    // Whole blocks were read: what waits is the rest of the last one.
    EXPECT_EQ((heard.size() + capture.unheard_count()) % 80, 0u);
  }
  EXPECT_EQ(heard, Ramp(300));
  EXPECT_EQ(capture.unheard()[0], 301.0f);
  EXPECT_EQ(capture.history(), nullptr);
  capture.Reset();
  EXPECT_EQ(capture.unheard_count(), 0u);
  std::vector<float> rest(640);
  EXPECT_TRUE(capture.Take(rest.data(), 640, 0));
  EXPECT_EQ(rest[0], 321.0f);  // what was read and not taken is gone
  EXPECT_FALSE(capture.Take(rest.data(), 100, 0));  // 40 samples left: not a whole block
}

TEST(LinkCapture, FallsBehindOnABacklogAndCatchesUpWhenItIsRead) {
  ManualClock clock;
  FailingDevice::Options o = Device(std::vector<float>(16000, 0.0f));
  o.stall_at = 800;
  o.stall = 4000;  // 0.25 s waiting, over a max lag of 0.1 s
  FailingDevice device(o, clock);
  LinkCapture capture(CaptureOptions{16000.0, 80, 0.1, 0.0}, device, clock);
  std::vector<float> out(160);
  std::vector<bool> behind;
  for (std::int64_t done = 0; done < 12000; done += 160) {
    ASSERT_TRUE(capture.Take(out.data(), 160, done));
    behind.push_back(capture.behind());
  }
  EXPECT_EQ(capture.catch_ups(), 1u);
  EXPECT_EQ(capture.behind_since(), 640);  // the tick that read the block where the stall began
  EXPECT_FALSE(behind.front());
  EXPECT_FALSE(behind.back());
  // Behind until the backlog fell to half the allowed lag (0.05 s, 800 samples): from 3920 after
  // the stall's block, 160 a tick, that is the stall's tick and 19 more.
  EXPECT_EQ(std::count(behind.begin(), behind.end(), true), 20);
}

TEST(LinkPlayback, PlaysAPacketInTicksAndGivesBackWhatHadNotPlayedWhenTheDeviceFails) {
  ManualClock clock;
  FailingDevice device(Device(std::vector<float>(8000, 0.0f), 400), clock);
  LinkPlayback playback(device, 80);
  std::vector<float> in(100);
  const std::vector<float> sound(1000, 0.5f);
  playback.Start(MacFrame{{1, 2, 3, 4}, 0, 0.5}, sound);
  for (int tick = 0; tick < 10; ++tick) {  // 1000 samples captured, 1000 of the packet written
    device.Read(in.data(), 100);
    playback.Tick(100, false);
  }
  // 400 samples of it wait in the device: its end has not played.
  std::vector<MacFrame> back = playback.Abort();
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].data, (std::vector<std::uint8_t>{1, 2, 3, 4}));

  playback.Start(MacFrame{{5, 6, 7, 8}, 0, 0.5}, sound);
  for (int tick = 0; tick < 16; ++tick) {
    device.Read(in.data(), 100);
    playback.Tick(100, false);
  }
  EXPECT_TRUE(playback.Abort().empty());  // all of it played
  // On the air: the first packet's first 600 samples after the 400 of priming, then (this device
  // did not really fail, so it played what it held) its last 400 and the second.
  const std::vector<float>& air = device.air();
  EXPECT_EQ(std::count(air.begin(), air.begin() + 1000, 0.5f), 600);
  EXPECT_EQ(std::count(air.begin() + 1000, air.end(), 0.5f), 1400);
  EXPECT_EQ(playback.packets_cut(), 0u);
}

}  // namespace
}  // namespace nava_modem
