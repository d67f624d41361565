#include "world_sim_ros.h"

#include <cmath>
#include <cstdio>

#include <multirobot_audio/FiducialArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "params.h"
#include "world_sim/world_file.h"

namespace multirobot_audio {
WorldSimOptions ReadWorldSimOptions(const ros::NodeHandle& pnh) {
  WorldSimOptions o;
  o.world_file = RequiredStringParam(pnh, "world");
  o.map_file = StringParam(pnh, "map", "");
  o.speed = NumberParam(pnh, "speed", o.speed, 0.0, 1e6);
  o.duration = NumberParam(pnh, "duration", o.duration, 0.0, 1e9);
  o.cmd_vel_timeout = NumberParam(pnh, "cmd_vel_timeout", o.cmd_vel_timeout, 0.0, 1e9);
  o.seed = IntParam(pnh, "seed", o.seed, -1, 2147483647);
  o.world.step = NumberParam(pnh, "step", o.world.step, 1e-4, 1.0);
  // Sensor rates may not exceed the step rate: a reading per step at most.
  const double max_rate = 1.0 / o.world.step;
  o.world.scan_period = 1.0 / NumberParam(pnh, "scan_rate", 1.0 / o.world.scan_period, 1e-3, max_rate);
  o.world.camera_period =
      1.0 / NumberParam(pnh, "camera_rate", 1.0 / o.world.camera_period, 1e-3, max_rate);
  o.world.odom_period = 1.0 / NumberParam(pnh, "odom_rate", 1.0 / o.world.odom_period, 1e-3, max_rate);
  o.markers_rate = NumberParam(pnh, "markers_rate", o.markers_rate, 1e-3, max_rate);
  return o;
}

WorldSimRos::WorldSimRos(ros::NodeHandle nh, ros::NodeHandle pnh, const WorldSimOptions& options)
    : nh_(nh), pnh_(pnh), options_(options) {
  world_sim::LoadedWorld loaded = world_sim::LoadWorldFile(options_.world_file, options_.map_file);
  if (options_.seed >= 0) loaded.config.seed = static_cast<std::uint32_t>(options_.seed);
  world_ = std::make_unique<world_sim::World>(std::move(loaded.map), std::move(loaded.config),
                                              options_.world);
  markers_every_ = world_sim::StepsPerPeriod(1.0 / options_.markers_rate, options_.world.step);
  battery_every_ = world_sim::StepsPerPeriod(1.0, options_.world.step);

  // Everything else in the team runs on our clock.
  nh_.setParam("/use_sim_time", true);
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  map_pub_ = nh_.advertise<nav_msgs::OccupancyGrid>("/map", 1, true);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 2);

  io_.resize(world_->robots().size());
  for (std::size_t k = 0; k < io_.size(); ++k) {
    const std::string& name = world_->robots()[k].name;
    ros::NodeHandle rnh(nh_, name);
    RobotIo& io = io_[k];
    io.odom_frame = name + "/odom";
    io.base_frame = name + "/base_link";
    io.cmd_vel = rnh.subscribe<geometry_msgs::Twist>(
        "cmd_vel", 10, [this, k](const geometry_msgs::Twist::ConstPtr& m) { OnCmdVel(k, m); });
    io.scan = rnh.advertise<sensor_msgs::LaserScan>("scan", 10);
    io.odom = rnh.advertise<nav_msgs::Odometry>("odom", 10);
    io.ground_truth = rnh.advertise<nav_msgs::Odometry>("ground_truth", 10);
    io.fiducials = rnh.advertise<multirobot_audio::FiducialArray>("fiducials", 10);
    io.battery = rnh.advertise<sensor_msgs::BatteryState>("battery", 2);
  }
  map_pub_.publish(ToOccupancyGrid(world_->map(), "map", ros::Time(world_->time())));
  ROS_INFO("world_sim: %zu robots on %s (%d x %d cells at %.3f m), step %.3f s, speed %g",
           io_.size(), world_->config().map_file.c_str(), world_->map().width(),
           world_->map().height(), world_->map().resolution(), options_.world.step, options_.speed);
}

void WorldSimRos::OnCmdVel(std::size_t index, const geometry_msgs::Twist::ConstPtr& msg) {
  if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z)) {
    ROS_WARN_THROTTLE(5.0, "world_sim: %s/cmd_vel: ignoring a non-finite command",
                      world_->robots()[index].name.c_str());
    return;
  }
  world_->SetCommand(index, msg->linear.x, msg->angular.z);
  io_[index].last_cmd_time = world_->time();
}

void WorldSimRos::Publish() {
  const world_sim::World& w = *world_;
  const ros::Time now(w.time());
  rosgraph_msgs::Clock clock;
  clock.clock = now;
  clock_pub_.publish(clock);

  std::vector<geometry_msgs::TransformStamped> transforms;
  for (std::size_t k = 0; k < io_.size(); ++k) {
    const world_sim::RobotState& r = w.robots()[k];
    RobotIo& io = io_[k];
    if (r.odom_step == w.steps()) {
      // map -> odom is whatever makes map -> odom -> base_link the true pose.
      const grid::Pose2D map_to_odom = grid::Compose(r.pose, grid::Inverse(r.odom));
      transforms.push_back(ToTransform(map_to_odom, "map", io.odom_frame, now));
      transforms.push_back(ToTransform(r.odom, io.odom_frame, io.base_frame, now));
      io.odom.publish(ToOdometry(r.odom, r.v, r.w, io.odom_frame, io.base_frame, now));
      io.ground_truth.publish(ToOdometry(r.pose, r.v, r.w, "map", io.base_frame, now));
    }
    if (r.scan_step == w.steps()) {
      io.scan.publish(ToLaserScan(r.scan, w.config().model, io.base_frame, now));
    }
    if (r.fiducials_step == w.steps()) {
      io.fiducials.publish(ToFiducialArray(r.fiducials, io.base_frame, now));
    }
    if (w.steps() % battery_every_ == 0) {
      io.battery.publish(ToBatteryState(r.battery, r.docked, w.config().model.battery, io.base_frame, now));
    }
  }
  if (!transforms.empty()) tf_.sendTransform(transforms);
  if (w.steps() % markers_every_ == 0 && markers_pub_.getNumSubscribers() > 0) {
    markers_pub_.publish(ToWorldMarkers(w, "map", now));
  }
}

std::string WorldSimRos::Run() {
  const ros::WallTime wall_start = ros::WallTime::now();
  Publish();
  while (ros::ok()) {
    ros::spinOnce();
    for (std::size_t k = 0; k < io_.size(); ++k) {
      if (world_->time() - io_[k].last_cmd_time > options_.cmd_vel_timeout) world_->SetCommand(k, 0.0, 0.0);
    }
    world_->Step();
    Publish();
    if (options_.duration > 0.0 && world_->elapsed() >= options_.duration - 1e-9) break;
    if (options_.speed > 0.0) {
      const ros::WallTime due = wall_start + ros::WallDuration(world_->elapsed() / options_.speed);
      if (due > ros::WallTime::now()) ros::WallTime::sleepUntil(due);
    }
  }
  const double wall = (ros::WallTime::now() - wall_start).toSec();
  char line[256];
  std::snprintf(line, sizeof line,
                "world_sim summary: robots %zu, simulated %.1f s, wall %.1f s, real-time factor "
                "%.1f, distance driven %.1f m, collisions %d",
                io_.size(), world_->elapsed(), wall, wall > 0 ? world_->elapsed() / wall : 0.0,
                world_->TotalDistance(), world_->TotalCollisions());
  return line;
}

}  // namespace multirobot_audio
