#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <multirobot_audio/Job.h>
#include <ros/ros.h>

#include "input_guard.h"

namespace multirobot_audio {

// Options of the task_monitor node, filled from its private parameters.
struct TaskMonitorOptions {
  std::vector<std::string> robots;  // ~robots: a count n, for robot_0 ... robot_{n-1} (required)
  int goal = 20;                    // ~goal: team jobs that finish the task
};

// Throws ParamError naming the parameter for a missing or out-of-range value.
TaskMonitorOptions ReadTaskMonitorOptions(const ros::NodeHandle& pnh);

// Watches a Sounds Good team's transport task: subscribes to every /<robot>/jobs, logs each job
// and the team's total, and when the total reaches the goal prints
//   task_monitor: team finished G jobs in T s
// and shuts ROS down (a launch file that marks it required then stops). A team that stops
// short prints `task_monitor: team finished N of G jobs by T s` on exit. Either way it ends with
// a `task_monitor summary:` line of its input counts. A job count that is not above the robot's
// last is turned down (a repeat, or a peer gone wrong).
// T is simulated time counted from the moment every robot's controller is up (each jobs topic
// has a publisher), not from the clock's start: at high speed, controllers that take a wall
// second longer to start than the simulator would otherwise cost the team a minute.
class TaskMonitorRos {
 public:
  TaskMonitorRos(ros::NodeHandle nh, const TaskMonitorOptions& options);
  ~TaskMonitorRos();

 private:
  InputGuard::Verdict OnJob(std::size_t robot, const multirobot_audio::Job::ConstPtr& msg);
  void CheckTeamUp(const ros::WallTimerEvent&);
  double Elapsed(const ros::Time& t) const;  // s since the team came up
  int TeamJobs() const;

  ros::NodeHandle nh_;
  TaskMonitorOptions options_;
  InputGuard guard_;  // before the subscriptions whose callbacks it checks
  std::vector<ros::Subscriber> subs_;
  std::vector<std::uint32_t> counts_;  // each robot's latest job count
  std::uint64_t skips_ = 0;            // reports whose count jumped past the one expected
  std::uint64_t jobs_unheard_ = 0;     // the jobs those jumps passed over
  ros::WallTimer up_timer_;
  ros::Time start_;  // zero until the team is up
  bool finished_ = false;
};

}  // namespace multirobot_audio
