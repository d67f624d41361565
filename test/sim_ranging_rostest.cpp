// rostest for the simulated team's ranging (test/sim_ranging.test): audio_propagation with
// ~ranging measured gives a reception's path_length only once its receiver and sender have
// exchanged packets both ways, then the length of the way the sound took (in line of sight and
// round the wall) within centimetres, and says the same on each robot's audio/teammates.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/Teammates.h>
#include <ros/ros.h>

#include "wait_for.h"

namespace {

using multirobot_audio::AudioReception;
using multirobot_audio::Teammate;
using multirobot_audio::Teammates;
using multirobot_audio::testing::WaitFor;

// m: one exchange, its two packets seconds apart, with the teammate's clock rate known only as
// the room receiver measures it (30 ppm of noise, as the real one): a few centimetres of error,
// 15 cm is several standard deviations.
constexpr double kTolerance = 0.15;
// From the world file: robot_1 2 m from robot_0 in line of sight, robot_2 round the wall's corners.
const double kToRobot1 = 2.0;
const double kToRobot2 = std::hypot(1.5, 1.5) + 0.15 + std::hypot(1.05, 0.5);

class Team {
 public:
  Team() {
    for (int k = 0; k < 3; ++k) {
      const std::string robot = "/robot_" + std::to_string(k);
      subs_.push_back(nh_.subscribe<AudioReception>(robot + "/audio/rx", 20, [this, k](const AudioReception::ConstPtr& m) {
        if (m->kind == AudioReception::PACKET) heard_[k].push_back(*m);
      }));
      subs_.push_back(nh_.subscribe<Teammates>(robot + "/audio/teammates", 20,
                                               [this, k](const Teammates::ConstPtr& m) { teammates_[k] = *m; }));
      tx_.push_back(nh_.advertise<multirobot_audio::AudioPacket>(robot + "/audio/tx", 10));
    }
  }
  bool Ready() const {
    for (const auto& tx : tx_) {
      if (tx.getNumSubscribers() == 0) return false;
    }
    return true;
  }
  // `sender` sends a packet; the reception of it by `listener`, once heard.
  const AudioReception* Exchange(int sender, std::uint8_t id, int listener) {
    multirobot_audio::AudioPacket p;
    p.data = {static_cast<std::uint8_t>(sender), id, 0x5A, 0xA5};
    const std::size_t before = heard_[listener].size();
    tx_[sender].publish(p);
    if (!WaitFor([&] { return heard_[listener].size() > before; }, 60.0)) return nullptr;
    WaitFor([] { return false; }, 1.0);  // the other listeners' receptions of it
    return &heard_[listener].back();
  }
  // `robot`'s latest word on `teammate`.
  const Teammate* Said(int robot, const std::string& teammate) const {
    const auto it = teammates_.find(robot);
    if (it == teammates_.end()) return nullptr;
    for (const Teammate& t : it->second.teammates) {
      if (t.name == teammate) return &t;
    }
    return nullptr;
  }

 private:
  ros::NodeHandle nh_;
  std::vector<ros::Subscriber> subs_;
  std::vector<ros::Publisher> tx_;
  std::map<int, std::vector<AudioReception>> heard_;
  std::map<int, Teammates> teammates_;
};

TEST(SimulatedRanging, RangesComeAfterAnExchangeBothWaysAndMatchThePaths) {
  Team team;
  ASSERT_TRUE(WaitFor([&] { return team.Ready(); }, 60.0));
  ros::WallDuration(1.0).sleep();  // let the node read every robot's pose

  // One way only: robot_1 knows no range to robot_0 yet.
  const AudioReception* first = team.Exchange(0, 1, 1);
  ASSERT_TRUE(first);
  EXPECT_TRUE(std::isnan(first->path_length)) << first->path_length;
  EXPECT_TRUE(std::isnan(first->path_length_std));

  // Back: robot_0 now has robot_1's range, in line of sight.
  const AudioReception* back = team.Exchange(1, 1, 0);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->path_length, kToRobot1, kTolerance);
  EXPECT_GT(back->path_length_std, 0.0f);
  EXPECT_LT(back->path_length_std, 0.5f);

  // robot_2 behind the wall heard robot_0's packet; its own reaches robot_0 round the corners.
  const AudioReception* round = team.Exchange(2, 1, 0);
  ASSERT_TRUE(round);
  EXPECT_NEAR(round->path_length, kToRobot2, kTolerance);

  // audio/teammates says the same, with the bearing of each teammate's latest packet.
  ASSERT_TRUE(WaitFor(
      [&] {
        const Teammate* t1 = team.Said(0, "robot_1");
        const Teammate* t2 = team.Said(0, "robot_2");
        return t1 && t2 && std::isfinite(t1->range) && std::isfinite(t2->range);
      },
      30.0));
  const Teammate& t1 = *team.Said(0, "robot_1");
  EXPECT_NEAR(t1.range, kToRobot1, kTolerance);
  EXPECT_GT(t1.range_std, 0.0f);
  EXPECT_EQ(t1.range_samples, 1u);
  EXPECT_GE(t1.range_age, 0.0f);
  EXPECT_NEAR(t1.bearing, M_PI / 2, 1e-3);  // robot_1 is straight to robot_0's left
  EXPECT_NEAR(team.Said(0, "robot_2")->range, kToRobot2, kTolerance);
  ASSERT_TRUE(WaitFor([&] { return team.Said(1, "robot_0") && std::isfinite(team.Said(1, "robot_0")->range); }, 30.0));
  EXPECT_NEAR(team.Said(1, "robot_0")->range, kToRobot1, kTolerance);
  // robot_3 never sent anything: no one has a range to it.
  const Teammate* none = team.Said(1, "robot_3");
  EXPECT_TRUE(!none || std::isnan(none->range));
}

}  // namespace
