// rostest for a Sounds Good team (test/sounds_good.test): three sounds_good_explorer nodes in
// the test room carry out the transport task between markers 1 and 2. The tests share the one
// run; everything is subscribed before the first test so that no early job is missed.
#include <algorithm>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/Job.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/master.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <visualization_msgs/Marker.h>

#include "wait_for.h"

namespace multirobot_audio::testing {
namespace {

const std::vector<std::string> kRobots = {"robot_0", "robot_1", "robot_2"};
// Simulated seconds from the clock's start by which the team must have done the jobs: each job
// is 30 s of work, and one robot doing two of them with a 6 m walk between the markers needs
// some 90 s.
constexpr double kSimLimit = 400.0;
// Wall seconds allowed for that at 20x real time, with room for a loaded machine.
constexpr double kWallLimit = 60.0;

struct RobotWatch {
  std::vector<multirobot_audio::Job> jobs;
  // The local map with the most walls in it so far: what a robot has seen at one instant
  // depends on where it happens to stand (in mid-room its rangers reach no wall).
  nav_msgs::OccupancyGrid::ConstPtr map;
  int map_occupied = -1;
  int maps = 0;
  int plans = 0, nonempty_plans = 0;
  std::string plan_frame;
  int frontiers = 0;
};

std::string Describe(const std::vector<multirobot_audio::Job>& jobs) {
  std::ostringstream s;
  for (const auto& j : jobs) s << "\n  job " << j.count << " at marker " << j.marker << ", " << j.header.stamp.toSec() << " s";
  return s.str();
}

class SoundsGoodTeam : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    for (const std::string& robot : kRobots) {
      RobotWatch* w = &watch_[robot];
      const std::string node = "/" + robot + "/sounds_good_explorer/";
      subs_.push_back(nh.subscribe<multirobot_audio::Job>(
          "/" + robot + "/jobs", 100, [w](const multirobot_audio::Job::ConstPtr& j) { w->jobs.push_back(*j); }));
      subs_.push_back(nh.subscribe<nav_msgs::OccupancyGrid>(node + "local_map", 1,
                                                            [w](const nav_msgs::OccupancyGrid::ConstPtr& m) {
                                                              ++w->maps;
                                                              const int occupied = static_cast<int>(
                                                                  std::count(m->data.begin(), m->data.end(), 100));
                                                              if (occupied > w->map_occupied) {
                                                                w->map = m;
                                                                w->map_occupied = occupied;
                                                              }
                                                            }));
      subs_.push_back(nh.subscribe<nav_msgs::Path>(node + "plan", 10, [w](const nav_msgs::Path::ConstPtr& p) {
        ++w->plans;
        if (p->poses.size() >= 2) ++w->nonempty_plans;
        w->plan_frame = p->header.frame_id;
      }));
      subs_.push_back(nh.subscribe<visualization_msgs::Marker>(
          node + "frontier", 10, [w](const visualization_msgs::Marker::ConstPtr&) { ++w->frontiers; }));
    }
    subs_.push_back(nh.subscribe("/rosout", 1000, &SoundsGoodTeam::OnLog));
  }
  static void TearDownTestSuite() { subs_.clear(); }
  static void OnLog(const rosgraph_msgs::Log::ConstPtr& l) {
    if (l->name == "/task_monitor") monitor_log_.push_back(l->msg);
  }

  // The robots' own counts, so that a job done before this node subscribed still counts.
  static int TeamJobs() {
    int n = 0;
    for (const auto& [robot, w] : watch_) n += w.jobs.empty() ? 0 : static_cast<int>(w.jobs.back().count);
    return n;
  }

  static std::map<std::string, RobotWatch> watch_;
  static std::vector<ros::Subscriber> subs_;
  static std::vector<std::string> monitor_log_;
};
std::map<std::string, RobotWatch> SoundsGoodTeam::watch_;
std::vector<ros::Subscriber> SoundsGoodTeam::subs_;
std::vector<std::string> SoundsGoodTeam::monitor_log_;

TEST_F(SoundsGoodTeam, EachRobotPublishesItsLocalMapPlanAndGoalInItsOdomFrame) {
  ASSERT_TRUE(WaitFor(
      [] {
        for (const auto& [robot, w] : watch_) {
          if (w.maps < 2 || w.nonempty_plans < 1 || w.frontiers < 1) return false;
          if (w.map_occupied <= 3) return false;  // until its rangers have met the room's walls
        }
        return true;
      },
      kWallLimit));
  for (const auto& [robot, w] : watch_) {
    SCOPED_TRACE(robot);
    const nav_msgs::OccupancyGrid& map = *w.map;
    EXPECT_EQ(map.header.frame_id, robot + "/odom");
    EXPECT_EQ(w.plan_frame, robot + "/odom");
    EXPECT_EQ(map.info.width, map.info.height);
    ASSERT_EQ(map.data.size(), static_cast<std::size_t>(map.info.width) * map.info.height);
    int free = 0, occupied = 0, unknown = 0;
    for (std::int8_t c : map.data) {
      free += c == 0;
      occupied += c == 100;
      unknown += c == -1;
    }
    EXPECT_EQ(free + occupied + unknown, static_cast<int>(map.data.size())) << "values other than -1, 0, 100";
    // The rangers have seen open floor and the room's walls, and most of the map is beyond them.
    EXPECT_GT(free, 20);
    EXPECT_GT(occupied, 3);
    EXPECT_GT(unknown, free);
  }
}

TEST_F(SoundsGoodTeam, TheTeamDoesJobsAlternatingSourceAndSinkWithRisingCounts) {
  const int wanted = [] {
    int n = 4;
    ros::NodeHandle("~").getParam("jobs", n);
    return n;
  }();
  WaitFor([&] { return TeamJobs() >= wanted || ros::Time::now().toSec() > kSimLimit; }, kWallLimit);
  std::ostringstream all;
  for (const auto& [robot, w] : watch_) all << "\n" << robot << ":" << Describe(w.jobs);
  ASSERT_GE(TeamJobs(), wanted) << "by " << ros::Time::now().toSec() << " s of simulated time" << all.str();

  for (const auto& [robot, w] : watch_) {
    SCOPED_TRACE(robot + Describe(w.jobs));
    for (std::size_t k = 0; k < w.jobs.size(); ++k) {
      const multirobot_audio::Job& j = w.jobs[k];
      // Seek the source first, then the sink, and so on.
      EXPECT_EQ(j.marker, j.count % 2 == 1 ? 1u : 2u);
      EXPECT_EQ(j.header.frame_id, robot + "/base_link");
      EXPECT_LE(j.header.stamp.toSec(), kSimLimit);
      if (k > 0) {
        EXPECT_EQ(j.count, w.jobs[k - 1].count + 1) << "counts must rise by one per job";
        // A job is 30 s of work after the previous one ended.
        EXPECT_GE((j.header.stamp - w.jobs[k - 1].header.stamp).toSec(), 30.0);
      }
    }
  }
}

TEST_F(SoundsGoodTeam, TheTaskMonitorCountsTheTeamsJobsAndStopsAtItsGoal) {
  // Its goal in the .test file is 4 team jobs: it logs each job with the team's total, and
  // after the fourth it shuts down (so its last line may not reach /rosout).
  auto running = [] {
    std::vector<std::string> nodes;
    ros::master::getNodes(nodes);
    return std::find(nodes.begin(), nodes.end(), "/task_monitor") != nodes.end();
  };
  EXPECT_TRUE(WaitFor([&] { return !running(); }, 10.0)) << "task_monitor is still up after the team's fourth job";
  std::ostringstream log;
  for (const std::string& line : monitor_log_) log << "\n  " << line;
  for (const char* total : {"team jobs 1/4", "team jobs 2/4", "team jobs 3/4"}) {
    EXPECT_TRUE(std::any_of(monitor_log_.begin(), monitor_log_.end(),
                            [&](const std::string& line) { return line.find(total) != std::string::npos; }))
        << "no '" << total << "'; task_monitor said:" << log.str();
  }
}

}  // namespace
}  // namespace multirobot_audio::testing
