#include "lockstep_participant.h"

#include <cmath>
#include <limits>

#include <multirobot_audio/LockstepAck.h>
#include <multirobot_audio/LockstepHello.h>

namespace multirobot_audio {

LockstepParticipant::LockstepParticipant(ros::NodeHandle nh) : nh_(nh), node_(ros::this_node::getName()) {
  nh_.param("/lockstep", enabled_, false);
  if (!enabled_) return;
  ros::NodeHandle pnh("~");
  hello_pub_ = nh_.advertise<multirobot_audio::LockstepHello>("/lockstep/hello", 10);
  ack_pub_ = nh_.advertise<multirobot_audio::LockstepAck>("/lockstep/ack", 100);
  order_sub_ = pnh.subscribe("lockstep_order", 100, &LockstepParticipant::OnOrder, this, LockstepTransport());
  // Repeated until the first order: a message sent before the connection stands is lost.
  hello_timer_ = nh_.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { SayHello(); });
}

void LockstepParticipant::SayHello() {
  if (ordered_) {
    hello_timer_.stop();
    return;
  }
  multirobot_audio::LockstepHello hello;
  hello.node = node_;
  for (const auto& [topic, sub] : subscriptions_) {
    hello.subscribed.push_back(topic);
    hello.connected.push_back(static_cast<std::int32_t>(sub.getNumPublishers()));
  }
  for (const auto& [topic, count] : published_) hello.advertised.push_back(topic);
  hello.passive = passive_;
  hello.order_connected = order_sub_.getNumPublishers() > 0;
  hello_pub_.publish(hello);
}

void LockstepParticipant::Passive(ros::NodeHandle& nh, const std::string& topic) {
  if (enabled_) passive_.push_back(nh.resolveName(topic));
}

ros::Timer LockstepParticipant::CreateTimer(ros::NodeHandle& nh, ros::Duration period,
                                            std::function<void(const ros::TimerEvent&)> callback,
                                            std::function<double()> rest_until) {
  if (!enabled_) return nh.createTimer(period, [callback](const ros::TimerEvent& e) { callback(e); });
  auto last = std::make_shared<ros::Time>();
  inbox_.AddTimer(period.toSec(), ros::Time::now().toSec(), [callback, last](double expected, double now) {
    ros::TimerEvent e;
    e.current_expected = ros::Time(expected);
    e.current_real = ros::Time(now);
    e.last_expected = *last;
    e.last_real = *last;
    *last = e.current_real;
    callback(e);
  }, std::move(rest_until));
  return ros::Timer();
}

void LockstepParticipant::Arrive(const std::string& topic, const std::string& publisher,
                                 world_sim::LockstepInbox::Delivery d) {
  const std::uint64_t before = inbox_.overflow();
  inbox_.Arrive(world_sim::StreamId{topic, publisher}, std::move(d));
  if (inbox_.overflow() > before) {
    ROS_WARN_THROTTLE(5.0, "%s: lockstep: more than the inbox holds; handed a message on early (%lu so far)",
                      node_.c_str(), static_cast<unsigned long>(inbox_.overflow()));
  }
  TryRun();
}

void LockstepParticipant::OnOrder(const multirobot_audio::LockstepOrder::ConstPtr& msg) {
  world_sim::StepOrder order{node_, msg->step, msg->stamp.toSec(), {}};
  const std::size_t n = std::min({msg->topics.size(), msg->publishers.size(), msg->totals.size()});
  for (std::size_t i = 0; i < n; ++i) {
    order.totals.push_back(world_sim::StreamCount{{msg->topics[i], msg->publishers[i]}, msg->totals[i]});
  }
  ordered_ = true;
  inbox_.Order(order, msg->counted);
  TryRun();
}

void LockstepParticipant::TryRun() {
  if (!inbox_.Ready()) return;
  // The callbacks read ros::Time::now(): it must be the step's time. /clock comes from
  // world_sim before the order, on its own connection; wait the moment it may lag.
  const ros::Time due(inbox_.time());
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(2.0);
  while (ros::Time::now() < due && ros::ok() && ros::WallTime::now() < give_up) {
    ros::WallDuration(0.00005).sleep();
  }
  if (ros::Time::now() < due) {
    ROS_WARN_THROTTLE(5.0, "%s: lockstep: /clock is behind the step order (%.3f s < %.3f s)", node_.c_str(),
                      ros::Time::now().toSec(), due.toSec());
  }
  const std::uint64_t step = inbox_.step();
  inbox_.Run();
  multirobot_audio::LockstepAck ack;
  ack.node = node_;
  ack.step = step;
  for (const auto& [topic, count] : published_) {
    std::uint64_t& reported = reported_[topic];
    if (*count == reported) continue;
    reported = *count;
    ack.topics.push_back(topic);
    ack.totals.push_back(*count);
  }
  ack.next_due = inbox_.NextDue();
  ack_pub_.publish(ack);
}

}  // namespace multirobot_audio
