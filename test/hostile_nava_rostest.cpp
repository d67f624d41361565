// A broken peer against nava_modem's audio/tx (test/hostile_nava.test, run by test/nava_air.sh):
// garbage, then a flood at 10 kHz for 10 s; the link must stay up, account for every message
// on /diagnostics and carry a packet over the air afterwards.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <ros/ros.h>

#include "hostile_peer.h"
#include "wait_for.h"

namespace multirobot_audio {
namespace {

using testing::WaitFor;

TEST(HostileNavaTest, TheLinkCountsEveryMessageAndCarriesPacketsAfterwards) {
  const ros::WallTime start = ros::WallTime::now();
  ros::NodeHandle nh;
  testing::DiagnosticsWatch watch(nh);
  // The payload of the second good variant: changed after the flood, so that what the flood
  // left queued cannot pass for the packet sent afterwards.
  std::vector<std::uint8_t> probe = {0x5A, 0xA5, 0x5A, 0xA5};
  int probes_heard = 0;
  ros::Subscriber rx = nh.subscribe<AudioReception>("/robot_1/audio/rx", 100, [&](const AudioReception::ConstPtr& m) {
    if (m->kind == AudioReception::PACKET && m->data == probe) ++probes_heard;
  });
  AudioPacket valid;
  valid.data = {0xEE, 0xEE, 0xEE, 0xEE};
  testing::TypedFeed<AudioPacket> tx(nh, "robot_0/nava_modem", "/robot_0/audio/tx", valid);
  tx.Good()
      .Good([&](AudioPacket& p) { p.data = probe; })
      .Bad([](AudioPacket& p) { p.data.clear(); })
      .Bad([](AudioPacket& p) { p.data.resize(3); })
      .Bad([](AudioPacket& p) { p.data.resize(5); })
      .Bad([](AudioPacket& p) { p.data.assign(1000, 0x55); })
      .Backwards();
  const std::string link = "robot_0/nava_modem: audio link";
  ASSERT_TRUE(WaitFor([&] { return tx.Connected() && watch.Age("robot_0/nava_modem: inputs") < 2.0 &&
                                   watch.Age("robot_1/nava_modem: inputs") < 2.0; }, 30.0))
      << "the links did not come up";
  ros::WallDuration(1.5).sleep();  // calibration

  // Each kind of garbage once, then the flood.
  testing::SendEachOnce({&tx});
  testing::ExpectAccounted(watch, {&tx}, true, 10.0);
  const std::vector<double> rates = testing::Flood({&tx}, 10000.0, 10.0);
  std::printf("hostile_nava: flood of /robot_0/audio/tx: %.0f messages/s\n", rates[0]);
  testing::SendClosing({&tx});
  testing::ExpectAccounted(watch, {&tx}, false, 20.0);

  // Afterwards the probe crosses the air (after what the flood left queued: at most the MAC's
  // queue, some seconds of packets).
  probe = {0x12, 0x34, 0x56, 0x78};
  ros::WallTime next;
  EXPECT_TRUE(WaitFor([&] {
    if (ros::WallTime::now() > next) {
      tx.Send(1);
      next = ros::WallTime::now() + ros::WallDuration(3.0);
    }
    return probes_heard > 0;
  }, 40.0)) << "robot_1 never heard robot_0's packet after the flood";
  testing::ExpectAccounted(watch, {&tx}, false, 10.0);
  EXPECT_LT(watch.Age("robot_0/nava_modem: inputs"), 3.0) << "robot_0's nava_modem stopped reporting (died?)";
  std::printf("hostile_nava: robot_0 link: %s; queue drops %s, packets out %s, capture overruns %s\n",
              watch.Message(link).c_str(), watch.Value(link, "queue drops").c_str(),
              watch.Value(link, "packets out").c_str(), watch.Value(link, "capture overruns").c_str());
  std::printf("hostile_nava: test took %.0f s (wall)\n", (ros::WallTime::now() - start).toSec());
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "hostile_nava");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
