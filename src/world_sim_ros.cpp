#include "world_sim_ros.h"

#include <cmath>
#include <cstdio>

#include <multirobot_audio/LockstepOrder.h>
#include <multirobot_audio/RobotPoses.h>
#include <multirobot_audio/RobotScans.h>

#include <multirobot_audio/FiducialArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/MarkerArray.h>

#include <ros/callback_queue.h>

#include "conversions.h"
#include "rviz_markers.h"
#include "input_checks.h"
#include "lockstep_participant.h"
#include "params.h"
#include "world_sim/world_file.h"

namespace multirobot_audio {
namespace {

constexpr std::uint64_t kClockSteps = 5;

}  // namespace
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
  o.lockstep = BoolParam(pnh, "lockstep", o.lockstep);
  o.lockstep_timeout = NumberParam(pnh, "lockstep_timeout", o.lockstep_timeout, 1e-3, 1e6);
  o.lockstep_start_timeout = NumberParam(pnh, "lockstep_start_timeout", o.lockstep_start_timeout, 1e-3, 1e6);
  o.lockstep_start_delay = NumberParam(pnh, "lockstep_start_delay", o.lockstep_start_delay, 0.0, 600.0);
  if (pnh.hasParam("lockstep_participants") && !pnh.getParam("lockstep_participants", o.participants)) {
    throw ParamError(pnh.resolveName("lockstep_participants") + ": expected a list of node names");
  }
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
  // What nobody reads is neither built nor sent (WatchedPublisher).
  markers_pub_ = WatchedPublisher::Advertise<visualization_msgs::MarkerArray>(pnh_, "markers", 2);
  robot_poses_pub_ = WatchedPublisher::Advertise<multirobot_audio::RobotPoses>(pnh_, "robot_poses", 10);
  robot_scans_pub_ = WatchedPublisher::Advertise<multirobot_audio::RobotScans>(pnh_, "robot_scans", 10);
  tf_pub_ = WatchedPublisher::Advertise<tf2_msgs::TFMessage>(nh_, "/tf", 100);

  io_.resize(world_->robots().size());
  for (std::size_t k = 0; k < io_.size(); ++k) {
    const std::string& name = world_->robots()[k].name;
    ros::NodeHandle rnh(nh_, name);
    RobotIo& io = io_[k];
    io.odom_frame = name + "/odom";
    io.base_frame = name + "/base_link";
    io.cmd_vel_topic = rnh.resolveName("cmd_vel");
    auto checked = guard_.Checked<geometry_msgs::Twist>(
        io.cmd_vel_topic, TwistProblem, [this, k](const geometry_msgs::Twist::ConstPtr& m) { OnCmdVel(k, *m); });
    io.cmd_vel = rnh.subscribe<geometry_msgs::Twist>("cmd_vel", 100,
                               boost::function<void(const ros::MessageEvent<geometry_msgs::Twist const>&)>(
                                   [this, k, checked](const ros::MessageEvent<geometry_msgs::Twist const>& e) {
                                     CountReceived(io_[k].cmd_vel_topic, e.getPublisherName());
                                     checked(e);
                                   }),
                               ros::VoidConstPtr(), LockstepTransport());
    io.scan = WatchedPublisher::Advertise<sensor_msgs::LaserScan>(rnh, "scan", 10);
    io.odom = WatchedPublisher::Advertise<nav_msgs::Odometry>(rnh, "odom", 10);
    io.ground_truth = WatchedPublisher::Advertise<nav_msgs::Odometry>(rnh, "ground_truth", 10);
    io.fiducials = WatchedPublisher::Advertise<multirobot_audio::FiducialArray>(rnh, "fiducials", 10);
    io.battery = WatchedPublisher::Advertise<sensor_msgs::BatteryState>(rnh, "battery", 2);
  }
  // The team's commands in one message (a controller driving many robots in one process).
  for (std::size_t k = 0; k < io_.size(); ++k) robot_index_[world_->robots()[k].name] = k;
  robot_commands_topic_ = pnh_.resolveName("robot_commands");
  auto checked = guard_.Checked<multirobot_audio::RobotCommands>(
      robot_commands_topic_,
      [this](const multirobot_audio::RobotCommands& m) {
        return RobotCommandsProblem(m, [this](const std::string& name) { return robot_index_.count(name) > 0; });
      },
      [this](const multirobot_audio::RobotCommands::ConstPtr& m) { OnRobotCommands(*m); });
  robot_commands_sub_ = pnh_.subscribe<multirobot_audio::RobotCommands>(
      "robot_commands", 100,
      boost::function<void(const ros::MessageEvent<multirobot_audio::RobotCommands const>&)>(
          [this, checked](const ros::MessageEvent<multirobot_audio::RobotCommands const>& e) {
            CountReceived(robot_commands_topic_, e.getPublisherName());
            checked(e);
          }),
      ros::VoidConstPtr(), LockstepTransport());
  if (options_.lockstep) SetUpLockstep();
  map_pub_.publish(ToOccupancyGrid(world_->map(), "map", ros::Time(world_->time())));
  ROS_INFO("world_sim: %zu robots on %s (%d x %d cells at %.3f m), step %.3f s, speed %g",
           io_.size(), world_->config().map_file.c_str(), world_->map().width(),
           world_->map().height(), world_->map().resolution(), options_.world.step, options_.speed);
}

void WorldSimRos::CountReceived(const std::string& topic, const std::string& publisher) {
  if (!lockstep_) return;
  const world_sim::StreamId stream{topic, publisher};
  lockstep_->OwnReceived(stream, ++cmd_received_[stream]);
}

void WorldSimRos::OnCmdVel(std::size_t index, const geometry_msgs::Twist& msg) {
  world_->SetCommand(index, msg.linear.x, msg.angular.z);
  io_[index].last_cmd_time = world_->time();
}

void WorldSimRos::OnRobotCommands(const multirobot_audio::RobotCommands& msg) {
  for (std::size_t k = 0; k < msg.names.size(); ++k) OnCmdVel(robot_index_.at(msg.names[k]), msg.commands[k]);
}

void WorldSimRos::SetUpLockstep() {
  world_sim::LockstepOptions lo;
  lo.self = ros::this_node::getName();
  lo.timeout = options_.lockstep_timeout;
  lo.participants = options_.participants;
  // A participant inside a robot's namespace must be one of the world's robots.
  for (const std::string& name : lo.participants) {
    if (name.empty() || name[0] != '/') {
      throw ParamError(pnh_.resolveName("lockstep_participants") + ": expected node names from the root (/robot_0/wanderer), got '" + name + "'");
    }
    const std::size_t slash = name.find('/', 1);
    if (slash == std::string::npos) continue;
    const std::string robot = name.substr(1, slash - 1);
    bool known = false;
    for (const auto& r : world_->robots()) known = known || r.name == robot;
    if (!known) {
      throw ParamError(pnh_.resolveName("lockstep_participants") + ": " + name + " is in the namespace of robot '" + robot +
                       "', which is not in " + options_.world_file);
    }
  }
  lockstep_ = std::make_unique<world_sim::LockstepCoordinator>(lo);  // throws on a name given twice
  std::vector<std::string> subscribed, advertised;
  for (const RobotIo& io : io_) {
    subscribed.push_back(io.cmd_vel_topic);
    for (const WatchedPublisher* p : {&io.scan, &io.odom, &io.ground_truth, &io.fiducials, &io.battery}) {
      advertised.push_back(p->topic());
    }
  }
  subscribed.push_back(robot_commands_topic_);
  advertised.push_back(robot_poses_pub_.topic());
  advertised.push_back(robot_scans_pub_.topic());
  lockstep_->SetOwnStreams(subscribed, advertised);
  nh_.setParam("/lockstep", true);
  hello_sub_ = nh_.subscribe("/lockstep/hello", 100, &WorldSimRos::OnHello, this);
  ack_sub_ = nh_.subscribe("/lockstep/ack", 1000, &WorldSimRos::OnAck, this, LockstepTransport());
}

void WorldSimRos::Count(const WatchedPublisher& pub) {
  if (lockstep_) lockstep_->OwnPublished(pub.topic(), pub.sent());
}

void WorldSimRos::OnHello(const multirobot_audio::LockstepHello::ConstPtr& msg) {
  world_sim::ParticipantHello hello{msg->node, msg->subscribed, {}, msg->advertised, msg->order_connected != 0, msg->passive};
  hello.connected.assign(msg->connected.begin(), msg->connected.end());
  if (!lockstep_->Hello(hello)) {
    if (!lockstep_->IsParticipant(msg->node) && strangers_.insert(msg->node).second) {
      ROS_WARN("world_sim: lockstep: %s is not in ~lockstep_participants: it runs without the lockstep", msg->node.c_str());
    }
    return;
  }
  if (order_pubs_.count(msg->node) == 0) {
    order_pubs_[msg->node] = nh_.advertise<multirobot_audio::LockstepOrder>(msg->node + "/lockstep_order", 100);
  }
}

void WorldSimRos::OnAck(const multirobot_audio::LockstepAck::ConstPtr& msg) {
  std::vector<world_sim::StreamCount> published;
  for (std::size_t i = 0; i < msg->topics.size() && i < msg->totals.size(); ++i) {
    published.push_back(world_sim::StreamCount{{msg->topics[i], msg->node}, msg->totals[i]});
  }
  lockstep_->Ack(msg->node, msg->step, published, msg->next_due, ros::WallTime::now().toSec());
}

std::map<std::string, int> WorldSimRos::OwnConnected() const {
  std::map<std::string, int> connected;
  for (const RobotIo& io : io_) connected[io.cmd_vel_topic] = static_cast<int>(io.cmd_vel.getNumPublishers());
  connected[robot_commands_topic_] = static_cast<int>(robot_commands_sub_.getNumPublishers());
  return connected;
}

void WorldSimRos::StartLockstep() {
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(options_.lockstep_start_timeout);
  std::string missing;
  ros::WallTime next_note = ros::WallTime::now() + ros::WallDuration(5.0);
  while (ros::ok() && !lockstep_->Ready(OwnConnected(), &missing)) {
    if (ros::WallTime::now() > give_up) {
      for (const std::string& name : lockstep_->DropUnready(OwnConnected())) {
        ROS_WARN("world_sim: lockstep: %s not ready after %.0f s (wall): dropped from the lockstep", name.c_str(),
                 options_.lockstep_start_timeout);
      }
      break;
    }
    if (ros::WallTime::now() > next_note) {
      ROS_INFO("world_sim: lockstep: waiting for the participants: %s", missing.c_str());
      next_note = ros::WallTime::now() + ros::WallDuration(5.0);
    }
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
  }
  // What is outside the lockstep (a recorder) connects to the team's publishers meanwhile; a
  // message sent before a subscriber's connection stands is lost to it.
  const ros::WallTime start = ros::WallTime::now() + ros::WallDuration(options_.lockstep_start_delay);
  while (ros::ok() && ros::WallTime::now() < start) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
  ROS_INFO("world_sim: lockstep with %zu participants", options_.participants.size() - lockstep_->dropped().size());
}

void WorldSimRos::PublishClock(const ros::Time& now) {
  rosgraph_msgs::Clock clock;
  clock.clock = now;
  clock_pub_.publish(clock);
}

void WorldSimRos::RunStepWithParticipants() {
  const double wall_start = ros::WallTime::now().toSec();
  const auto orders = lockstep_->BeginStep(++lockstep_step_, world_->time(), wall_start);
  // /clock goes to every node of the team: in lockstep it is sent when someone takes part in the
  // step (a participant's callbacks run at the step's time) and at least every kClockSteps
  // steps for the nodes outside the lockstep (rviz, rosbag).
  if (!orders.empty() || world_->steps() % kClockSteps == 0) PublishClock(ros::Time(world_->time()));
  for (const world_sim::StepOrder& o : orders) {
    multirobot_audio::LockstepOrder msg;
    msg.step = o.step;
    msg.stamp = ros::Time(o.time);
    if (ordered_.insert(o.node).second) msg.counted = lockstep_->CountedPublishers();
    for (const world_sim::StreamCount& c : o.totals) {
      msg.topics.push_back(c.stream.topic);
      msg.publishers.push_back(c.stream.publisher);
      msg.totals.push_back(c.total);
    }
    order_pubs_[o.node].publish(msg);
  }
  bool warned = false;
  while (ros::ok() && (!lockstep_->Pending().empty() || !lockstep_->OwnCaughtUp())) {
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.001));
    const double wall = ros::WallTime::now().toSec();
    for (const std::string& name : lockstep_->DropLate(wall)) {
      ROS_WARN("world_sim: lockstep: %s has not answered step %lu (t = %.2f s) for %.1f s (wall): dropped from the lockstep",
               name.c_str(), static_cast<unsigned long>(lockstep_step_), world_->time(), options_.lockstep_timeout);
    }
    if (lockstep_->Pending().empty() && !lockstep_->OwnCaughtUp() && wall - wall_start > options_.lockstep_timeout) {
      if (!warned) ROS_WARN("world_sim: lockstep: commands reported sent have not arrived after %.1f s: going on", options_.lockstep_timeout);
      warned = true;
      break;
    }
  }
  lockstep_->EndStep(ros::WallTime::now().toSec());
}

void WorldSimRos::Publish() {
  const world_sim::World& w = *world_;
  const ros::Time now(w.time());
  if (!lockstep_) PublishClock(now);

  tf2_msgs::TFMessage transforms;
  multirobot_audio::RobotPoses poses;
  // Built only for a listener: a team in one process (the wanderer's ~robots).
  const bool team_scans = robot_scans_pub_.Heard();
  multirobot_audio::RobotScans scans;
  for (std::size_t k = 0; k < io_.size(); ++k) {
    const world_sim::RobotState& r = w.robots()[k];
    RobotIo& io = io_[k];
    if (r.odom_step == w.steps()) {
      if (tf_pub_.Heard()) {
        // map -> odom is whatever makes map -> odom -> base_link the true pose.
        const grid::Pose2D map_to_odom = grid::Compose(r.pose, grid::Inverse(r.odom));
        transforms.transforms.push_back(ToTransform(map_to_odom, "map", io.odom_frame, now));
        transforms.transforms.push_back(ToTransform(r.odom, io.odom_frame, io.base_frame, now));
      }
      if (io.odom.Heard()) {
        io.odom.publish(ToOdometry(r.odom, r.v, r.w, io.odom_frame, io.base_frame, now));
        Count(io.odom);
      }
      if (io.ground_truth.Heard()) {
        io.ground_truth.publish(ToOdometry(r.pose, r.v, r.w, "map", io.base_frame, now));
        Count(io.ground_truth);
      }
      poses.names.push_back(r.name);
      geometry_msgs::Pose2D p;
      p.x = r.pose.x;
      p.y = r.pose.y;
      p.theta = r.pose.yaw;
      poses.poses.push_back(p);
    }
    if (r.scan_step == w.steps() && (io.scan.Heard() || team_scans)) {
      sensor_msgs::LaserScan scan = ToLaserScan(r.scan, w.config().model, io.base_frame, now);
      if (io.scan.Heard()) {
        io.scan.publish(scan);
        Count(io.scan);
      }
      if (team_scans) {
        scans.names.push_back(r.name);
        scans.scans.push_back(std::move(scan));
      }
    }
    if (r.fiducials_step == w.steps() && io.fiducials.Heard()) {
      io.fiducials.publish(ToFiducialArray(r.fiducials, io.base_frame, now));
      Count(io.fiducials);
    }
    if (w.steps() % battery_every_ == 0 && io.battery.Heard()) {
      io.battery.publish(ToBatteryState(r.battery, r.docked, w.config().model.battery, io.base_frame, now));
      Count(io.battery);
    }
  }
  if (!scans.names.empty()) {
    scans.header.stamp = now;
    robot_scans_pub_.publish(scans);
    Count(robot_scans_pub_);
  }
  if (!transforms.transforms.empty()) tf_pub_.publish(transforms);
  if (!poses.names.empty() && robot_poses_pub_.Heard()) {
    poses.header.stamp = now;
    poses.header.frame_id = "map";
    robot_poses_pub_.publish(poses);
    Count(robot_poses_pub_);
  }
  if (w.steps() % markers_every_ == 0 && markers_pub_.Heard()) {
    markers_pub_.publish(ToWorldMarkers(w, "map", now));
  }
}

std::string WorldSimRos::Run() {
  // In lockstep nothing is published before every participant is listening: a message sent
  // before its subscriber is connected would be lost and never counted.
  if (lockstep_) StartLockstep();
  const ros::WallTime wall_start = ros::WallTime::now();
  Publish();
  if (lockstep_) RunStepWithParticipants();
  while (ros::ok()) {
    ros::spinOnce();
    for (std::size_t k = 0; k < io_.size(); ++k) {
      if (world_->time() - io_[k].last_cmd_time > options_.cmd_vel_timeout) world_->SetCommand(k, 0.0, 0.0);
    }
    world_->Step();
    Publish();
    if (lockstep_) RunStepWithParticipants();
    if (options_.duration > 0.0 && world_->elapsed() >= options_.duration - 1e-9) break;
    if (options_.speed > 0.0) {
      const ros::WallTime due = wall_start + ros::WallDuration(world_->elapsed() / options_.speed);
      if (due > ros::WallTime::now()) ros::WallTime::sleepUntil(due);
    }
  }
  const double wall = (ros::WallTime::now() - wall_start).toSec();
  char line[512];
  std::snprintf(line, sizeof line,
                "world_sim summary: robots %zu, simulated %.1f s, distance driven %.3f m, collisions %d; ",
                io_.size(), world_->elapsed(), world_->TotalDistance(), world_->TotalCollisions());
  // The inputs' part names every robot with a rejection or a drop: no fixed length.
  std::string summary = line + guard_.Summary();
  std::snprintf(line, sizeof line, "\nworld_sim timing: wall %.1f s, real-time factor %.1f", wall,
                wall > 0 ? world_->elapsed() / wall : 0.0);
  summary += line;
  if (lockstep_) {
    double slowest_s = 0.0;
    const std::string slowest = lockstep_->Slowest(&slowest_s);
    std::snprintf(line, sizeof line, ", lockstep waiting %.1f s (slowest %s: %.1f s), dropped %zu",
                  lockstep_->waiting_wall(), slowest.empty() ? "none" : slowest.c_str(), slowest_s,
                  lockstep_->dropped().size());
    summary += line;
    // What each participant kept the world waiting (from an order to its answer), for benches.
    summary += "\nworld_sim lockstep waits (wall s):";
    for (const auto& [name, seconds] : lockstep_->AnswerTimes()) {
      std::snprintf(line, sizeof line, " %s %.2f", name.c_str(), seconds);
      summary += line;
    }
  }
  return summary;
}

}  // namespace multirobot_audio
