#include "task_monitor_ros.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>

#include "input_checks.h"
#include "params.h"

namespace multirobot_audio {
namespace {

// Wall seconds between checks that every controller is up; short beside a simulated second at
// the speeds the demo runs at.
constexpr double kUpCheckPeriod = 0.02;

}  // namespace

TaskMonitorOptions ReadTaskMonitorOptions(const ros::NodeHandle& pnh) {
  TaskMonitorOptions o;
  const int robots = RequiredIntParam(pnh, "robots", 1, 1000);
  for (int k = 0; k < robots; ++k) o.robots.push_back("robot_" + std::to_string(k));
  o.goal = IntParam(pnh, "goal", o.goal, 1, 1000000);
  return o;
}

TaskMonitorRos::TaskMonitorRos(ros::NodeHandle nh, const TaskMonitorOptions& options)
    : nh_(nh), options_(options), counts_(options.robots.size(), 0) {
  for (std::size_t k = 0; k < options_.robots.size(); ++k) {
    subs_.push_back(guard_.Subscribe<multirobot_audio::Job>(
        nh_, "/" + options_.robots[k] + "/jobs", 10, JobProblem,
        [this, k](const multirobot_audio::Job::ConstPtr& msg) { return OnJob(k, msg); }));
  }
  // A wall timer: the team may come up before the simulated clock does.
  up_timer_ = nh_.createWallTimer(ros::WallDuration(kUpCheckPeriod), &TaskMonitorRos::CheckTeamUp, this);
}

TaskMonitorRos::~TaskMonitorRos() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  if (!finished_) {
    std::printf("task_monitor: team finished %d of %d jobs by %.1f s\n", TeamJobs(), options_.goal,
                start_.isZero() ? 0.0 : Elapsed(ros::Time::now()));
  }
  std::printf("task_monitor summary: team jobs %d of %d; %s\n", TeamJobs(), options_.goal, guard_.Summary().c_str());
  std::fflush(stdout);
}

void TaskMonitorRos::CheckTeamUp(const ros::WallTimerEvent&) {
  const ros::Time now = ros::Time::now();
  if (now.isZero()) return;  // no clock yet
  for (const ros::Subscriber& sub : subs_) {
    if (sub.getNumPublishers() == 0) return;
  }
  start_ = now;
  up_timer_.stop();
  ROS_INFO("task_monitor: all %zu robots up at %.1f s; team time counts from here", subs_.size(), now.toSec());
}

double TaskMonitorRos::Elapsed(const ros::Time& t) const { return (t - start_).toSec(); }

int TaskMonitorRos::TeamJobs() const {
  return static_cast<int>(std::accumulate(counts_.begin(), counts_.end(), std::uint64_t{0}));
}

InputGuard::Verdict TaskMonitorRos::OnJob(std::size_t robot, const multirobot_audio::Job::ConstPtr& msg) {
  const std::string& name = options_.robots[robot];
  if (msg->count <= counts_[robot]) {
    return InputGuard::Verdict::Reject("count " + std::to_string(msg->count) + ", not above " + name + "'s last, " +
                                       std::to_string(counts_[robot]));
  }
  if (finished_) return InputGuard::Verdict::Accept();
  if (start_.isZero()) {
    // A robot finished a job before the check saw every controller up; count from now on.
    start_ = ros::Time::now();
    up_timer_.stop();
    ROS_WARN("task_monitor: a job arrived before every robot was seen up; team time counts from %.1f s",
             start_.toSec());
  }
  if (msg->count != counts_[robot] + 1) {
    // A peer that floods counts would otherwise fill the log with one line a message; the totals say it all.
    ++skips_;
    jobs_unheard_ += msg->count - counts_[robot] - 1;
    ROS_WARN_THROTTLE(5.0, "task_monitor: %s reports job %u after job %u (%lu jumps, %lu jobs not heard so far)",
                      name.c_str(), msg->count, counts_[robot], static_cast<unsigned long>(skips_),
                      static_cast<unsigned long>(jobs_unheard_));
  }
  // Each robot's own count is the truth: a lost message does not lose a job.
  counts_[robot] = msg->count;
  const int team = TeamJobs();
  const double t = Elapsed(msg->header.stamp);
  ROS_INFO("task_monitor: team jobs %d/%d at %.1f s: %s finished marker %u", team, options_.goal, t, name.c_str(),
           msg->marker);
  if (team < options_.goal) return InputGuard::Verdict::Accept();
  finished_ = true;
  std::printf("task_monitor: team finished %d jobs in %.1f s\n", options_.goal, t);
  std::fflush(stdout);
  ros::shutdown();
  return InputGuard::Verdict::Accept();
}

}  // namespace multirobot_audio
