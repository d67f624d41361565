// Over the air through ALSA (test/frames_air.test, run by test/nava_air.sh): 64-byte frames of
// the room profile at each rate of its ladder, each sent by the link set to that rate and heard
// whole, with its rate, by the listening link and by the two other senders.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>
#include <ros/ros.h>

#include "nava_modem/modem_profile.h"
#include "wait_for.h"

namespace multirobot_audio {
namespace {

using testing::WaitFor;
// The links, named for the rate each sends at (its index).
const std::vector<std::string> kSenders = {"robust", "medium", "fast"};
const std::vector<std::string> kLinks = {"robust", "medium", "fast", "listener"};

// 64 bytes that differ for each sender and try, so that no frame is taken for another.
std::vector<std::uint8_t> Payload(std::size_t sender, int attempt) {
  std::vector<std::uint8_t> data(64);
  for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<std::uint8_t>(k * 37 + sender * 101 + attempt * 13);
  return data;
}

TEST(FramesAir, EachRateCarriesA64ByteFrameToEveryOtherLink) {
  ros::NodeHandle nh;
  std::map<std::string, ros::Publisher> tx;
  std::map<std::string, std::vector<AudioReception>> heard;
  std::map<std::string, bool> alive;
  std::vector<ros::Subscriber> subs;
  for (const std::string& link : kLinks) {
    tx[link] = nh.advertise<AudioPacket>(link + "/audio/tx", 10);
    subs.push_back(nh.subscribe<AudioReception>(link + "/audio/rx", 100,
                                                [&heard, link](const AudioReception::ConstPtr& m) { heard[link].push_back(*m); }));
    subs.push_back(nh.subscribe<CarrierSense>(link + "/audio/carrier", 10,
                                              [&alive, link](const CarrierSense::ConstPtr&) { alive[link] = true; }));
  }
  ASSERT_TRUE(WaitFor([&] {
    bool up = alive.size() == kLinks.size();
    for (const std::string& s : kSenders) up = up && tx[s].getNumSubscribers() > 0;
    return up;
  }, 60.0)) << "not every link came up";
  ros::WallDuration(2.0).sleep();  // calibrated

  for (std::size_t s = 0; s < kSenders.size(); ++s) {
    const int rate = static_cast<int>(s);
    const double airtime = nava_modem::FrameAirtime(nava_modem::Profile::kRoom, {}, 64, rate);
    // A link decodes on its audio thread, and while it decodes a long frame on a loaded machine it
    // falls behind (playback underruns, capture catch-ups) and may cut a frame: the first clean-
    // clone CI of 7acfa62 lost one try of rate 1 this way, and a quiet run here one of rate 2.
    // Until the receiver runs on a thread of its own, three tries are allowed, never a wrong frame.
    std::string missing;
    for (int attempt = 0; attempt < 3; ++attempt) {
      heard.clear();
      const std::vector<std::uint8_t> data = Payload(s, attempt);
      AudioPacket p;
      p.header.stamp = ros::Time::now();
      p.data = data;
      tx[kSenders[s]].publish(p);
      const auto got = [&](const std::string& link) {
        for (const AudioReception& r : heard[link]) {
          if (r.kind == AudioReception::PACKET && r.data == data) return static_cast<int>(r.rate) == rate;
        }
        return false;
      };
      const bool all = WaitFor([&] {
        for (const std::string& link : kLinks) {
          if (link != kSenders[s] && !got(link)) return false;
        }
        return true;
      }, airtime + 10.0);
      missing.clear();
      for (const std::string& link : kLinks) {
        if (link == kSenders[s]) continue;
        for (const AudioReception& r : heard[link]) {
          if (r.kind == AudioReception::PACKET && r.data.size() > 4) {
            EXPECT_EQ(r.data, data) << link << " decoded a wrong " << r.data.size() << "-byte frame";
          }
        }
        if (!got(link)) missing += " " + link;
      }
      std::printf("frames_air: rate %d, 64 bytes in %.2f s of air, try %d: %s\n", rate, airtime, attempt + 1,
                  missing.empty() ? "heard by every link" : ("missed by" + missing).c_str());
      if (all) break;
    }
    EXPECT_TRUE(missing.empty()) << "rate " << rate << ": the 64-byte frame was not heard, with its rate, by" << missing;
  }
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frames_air_rostest");
  return RUN_ALL_TESTS();
}
