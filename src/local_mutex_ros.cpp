#include "local_mutex_ros.h"

#include <cstdio>
#include <limits>

#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/LockState.h>

#include "input_checks.h"
#include "params.h"

namespace multirobot_audio {
namespace {

using local_mutex::State;

// Lamport events and timers are checked this often; the thesis's timers are seconds long.
constexpr double kTickPeriod = 0.1;
// A waiting goal hears how the lock stands at least this often (s).
constexpr double kFeedbackPeriod = 1.0;

double Now() { return ros::Time::now().toSec(); }

// LockState's constants are the algorithm's states, value for value.
static_assert(multirobot_audio::LockState::RELEASED == static_cast<int>(State::kReleased) &&
              multirobot_audio::LockState::WANTED == static_cast<int>(State::kWanted) &&
              multirobot_audio::LockState::SILENT == static_cast<int>(State::kSilent) &&
              multirobot_audio::LockState::HELD == static_cast<int>(State::kHeld));

bool Waiting(State s) { return s == State::kWanted || s == State::kSilent; }

unsigned long Count(std::uint64_t n) { return static_cast<unsigned long>(n); }

}  // namespace

LocalMutexNodeOptions ReadLocalMutexNodeOptions(const ros::NodeHandle& pnh) {
  LocalMutexNodeOptions o;
  local_mutex::MutexOptions& m = o.mutex;
  m.robot_id = RequiredIntParam(pnh, "robot_id", 1, 255);
  // Wide bounds here: ValidateMutexOptions says what the timers need of each other.
  m.grab_time = NumberParam(pnh, "grab_time", m.grab_time, 0.0, 1e6);
  m.request_mean = NumberParam(pnh, "request_mean", m.request_mean, 0.0, 1e6);
  m.request_sd = NumberParam(pnh, "request_sd", m.request_sd, 0.0, 1e6);
  m.lock_mean = NumberParam(pnh, "lock_mean", m.lock_mean, 0.0, 1e6);
  m.lock_sd = NumberParam(pnh, "lock_sd", m.lock_sd, 0.0, 1e6);
  m.echo_window = NumberParam(pnh, "echo_window", m.echo_window, 0.0, 1e6);
  // Robots differ by id, so their default seeds do too.
  m.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", m.robot_id, 0, std::numeric_limits<int>::max()));
  o.state_rate = NumberParam(pnh, "state_rate", o.state_rate, 0.0, 1000.0);
  local_mutex::ValidateMutexOptions(m);
  return o;
}

LocalMutexRos::LocalMutexRos(ros::NodeHandle nh, const LocalMutexNodeOptions& options)
    : nh_(nh),
      lockstep_(nh),
      options_(options),
      lock_(options.mutex, [this](const std::vector<std::uint8_t>& packet) {
        multirobot_audio::AudioPacket msg;
        msg.header.stamp = ros::Time::now();
        msg.data = packet;
        tx_pub_.publish(msg);
      }),
      acquire_server_(nh, "local_mutex/acquire", false) {
  state_since_ = Now();
  lock_.SetObserver([this](const local_mutex::MutexEvent& e) { OnEvent(e); });
  tx_pub_ = lockstep_.Advertise<multirobot_audio::AudioPacket>(nh_, "audio/tx", 10);
  state_pub_ = lockstep_.Advertise<multirobot_audio::LockState>(nh_, "local_mutex/state", 10, true);
  rx_sub_ = guard_.Subscribe<multirobot_audio::AudioReception>(
      lockstep_, nh_, "audio/rx", 50, ReceptionProblem,
      [this](const multirobot_audio::AudioReception::ConstPtr& m) { OnRx(m); });
  // The action server's own subscriptions: goals and cancels from any client.
  guard_.Watch(nh_.resolveName("local_mutex/acquire/goal"));
  guard_.Watch(nh_.resolveName("local_mutex/acquire/cancel"));
  release_srv_ = nh_.advertiseService("local_mutex/release", &LocalMutexRos::OnRelease, this);
  acquire_server_.registerGoalCallback([this] { OnGoal(); });
  acquire_server_.registerPreemptCallback([this] { OnPreempt(); });
  acquire_server_.start();
  tick_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(kTickPeriod), &LocalMutexRos::OnTick, this);
  if (options_.state_rate > 0.0) {
    state_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(1.0 / options_.state_rate), [this](const ros::TimerEvent&) { PublishState(); });
  }
  PublishState();
  const local_mutex::MutexOptions& m = options_.mutex;
  ROS_INFO("local_mutex[%d]: grab after %.1f s of silence; requests every %.1f +- %.1f s, lock announcements every "
           "%.1f +- %.1f s", m.robot_id, m.grab_time, m.request_mean, m.request_sd, m.lock_mean, m.lock_sd);
}

LocalMutexRos::~LocalMutexRos() {
  const local_mutex::MutexCounters& c = lock_.counters();
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("local_mutex summary: robot %d, grants %lu, sent %lu, heard %lu, noise %lu, malformed %lu, "
              "duplicate ids %lu, echoes %lu; ended %s; %s\n",
              lock_.robot_id(), Count(c.grants), Count(c.sent), Count(c.heard), Count(c.noise), Count(c.malformed),
              Count(c.duplicate_ids), Count(c.echoes), local_mutex::StateName(lock_.state()), guard_.Summary().c_str());
  std::fflush(stdout);
}

void LocalMutexRos::OnRx(const multirobot_audio::AudioReception::ConstPtr& msg) {
  const double now = Now();
  if (msg->kind == multirobot_audio::AudioReception::PACKET) {
    lock_.HearPacket(msg->data, now);
  } else {
    lock_.HearNoise(now);
  }
  ServeGoal(now);
}

void LocalMutexRos::OnTick(const ros::TimerEvent&) {
  const double now = Now();
  lock_.Tick(now);
  ServeGoal(now);
}

void LocalMutexRos::OnEvent(const local_mutex::MutexEvent& e) {
  const int id = lock_.robot_id();
  const local_mutex::MutexCounters& c = lock_.counters();
  switch (e.kind) {
    case local_mutex::MutexEvent::Kind::kStateChange:
      ROS_INFO("local_mutex[%d]: %s -> %s (clock %u, request (%u, %d))", id, local_mutex::StateName(last_state_),
               local_mutex::StateName(e.state), e.clock, lock_.request().time, id);
      last_state_ = e.state;
      state_since_ = e.time;
      feedback_due_ = true;
      break;
    case local_mutex::MutexEvent::Kind::kDuplicateId:
      ROS_WARN("local_mutex[%d]: heard %s, which this robot did not send: another robot has id %d (%lu such packets "
               "so far)", id, local_mutex::Describe(e.message).c_str(), id, Count(c.duplicate_ids));
      break;
    case local_mutex::MutexEvent::Kind::kMalformed:
      ROS_DEBUG("local_mutex[%d]: a packet that is not a lock message, taken as noise (%lu so far)", id,
                Count(c.malformed));
      break;
    case local_mutex::MutexEvent::Kind::kNoise:
      ROS_DEBUG("local_mutex[%d]: noise (clock %u)", id, e.clock);
      break;
    default:  // sent, heard, echo
      ROS_DEBUG("local_mutex[%d]: %s %s (clock %u)", id, local_mutex::EventKindName(e.kind),
                local_mutex::Describe(e.message).c_str(), e.clock);
      break;
  }
  PublishState();
}

void LocalMutexRos::OnGoal() {
  const double now = Now();
  const auto goal = acquire_server_.acceptNewGoal();
  goal_since_ = now;
  goal_timeout_ = goal->timeout;
  last_feedback_ = now;
  feedback_due_ = true;
  if (acquire_server_.isPreemptRequested()) {  // cancelled before it was accepted
    OnPreempt();
    return;
  }
  // While WANTED or SILENT the request of an earlier goal stands, and this goal takes it over:
  // asking again would lose the robot its place in the order.
  if (lock_.state() == State::kReleased) lock_.Request(now);
  ServeGoal(now);
}

void LocalMutexRos::OnPreempt() {
  // A new goal preempts the waiting one; OnGoal follows and keeps the request standing.
  if (acquire_server_.isNewGoalAvailable() || !acquire_server_.isActive()) return;
  const double now = Now();
  if (Waiting(lock_.state())) lock_.Release(now);
  acquire_server_.setPreempted(GoalResult(false, now), "cancelled; the request was withdrawn");
  ROS_INFO("local_mutex[%d]: acquire cancelled after %.1f s", lock_.robot_id(), now - goal_since_);
}

bool LocalMutexRos::OnRelease(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  const double now = Now();
  const State before = lock_.state();
  res.success = true;
  if (!lock_.Release(now)) {
    ROS_WARN("local_mutex[%d]: release asked, but the lock was not held (already RELEASED)", lock_.robot_id());
    res.message = "not held: the lock was already released";
    return true;
  }
  res.message = before == State::kHeld ? "released" : "not yet held: the request was withdrawn";
  ServeGoal(now);  // a goal still waiting ends: its request is gone
  return true;
}

void LocalMutexRos::ServeGoal(double now) {
  if (!acquire_server_.isActive()) return;
  const State state = lock_.state();
  if (state == State::kHeld) {
    acquire_server_.setSucceeded(GoalResult(true, now), "the lock is held");
    ROS_INFO("local_mutex[%d]: lock acquired after %.1f s", lock_.robot_id(), now - goal_since_);
    return;
  }
  if (state == State::kReleased) {
    acquire_server_.setAborted(GoalResult(false, now), "the request was withdrawn by local_mutex/release");
    return;
  }
  if (goal_timeout_ > 0.0 && now - goal_since_ >= goal_timeout_) {
    lock_.Release(now);  // a robot that gave up must not take the lock later
    acquire_server_.setAborted(GoalResult(false, now), "timed out; the request was withdrawn");
    ROS_INFO("local_mutex[%d]: acquire timed out after %.1f s", lock_.robot_id(), now - goal_since_);
    return;
  }
  if (feedback_due_ || now - last_feedback_ >= kFeedbackPeriod) {
    multirobot_audio::AcquireLockFeedback feedback;
    feedback.state = static_cast<std::uint8_t>(state);
    feedback.clock = lock_.clock();
    feedback.waited = now - goal_since_;
    acquire_server_.publishFeedback(feedback);
    feedback_due_ = false;
    last_feedback_ = now;
  }
}

multirobot_audio::AcquireLockResult LocalMutexRos::GoalResult(bool acquired, double now) const {
  multirobot_audio::AcquireLockResult result;
  result.acquired = acquired;
  result.waited = now - goal_since_;
  return result;
}

void LocalMutexRos::PublishState() {
  const ros::Time now = ros::Time::now();
  const local_mutex::MutexCounters& c = lock_.counters();
  multirobot_audio::LockState msg;
  msg.header.stamp = now;
  msg.state = static_cast<std::uint8_t>(lock_.state());
  msg.robot_id = static_cast<std::uint8_t>(lock_.robot_id());
  msg.clock = lock_.clock();
  msg.request_time = lock_.request().time;
  msg.time_in_state = now.toSec() - state_since_;
  msg.sent = c.sent;
  msg.heard = c.heard;
  msg.noise = c.noise;
  msg.malformed = c.malformed;
  msg.duplicate_ids = c.duplicate_ids;
  msg.echoes = c.echoes;
  msg.grants = c.grants;
  state_pub_.publish(msg);
}

}  // namespace multirobot_audio
