#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <multirobot_audio/LockstepOrder.h>
#include <ros/ros.h>

#include "world_sim/lockstep_inbox.h"

namespace multirobot_audio {

// How lockstep messages travel: TCP without Nagle's algorithm. A step's small messages (orders,
// answers, commands) each wait for the one before to be acknowledged otherwise, and a step then
// takes milliseconds of waiting instead of tens of microseconds.
inline ros::TransportHints LockstepTransport() { return ros::TransportHints().tcpNoDelay(); }

// A publisher whose messages are counted for the lockstep (lockstep_coordinator.h); used like
// a ros::Publisher.
class CountedPublisher {
 public:
  CountedPublisher() = default;
  template <class M>
  void publish(const M& msg) const {
    pub_.publish(msg);
    if (count_) ++*count_;
  }
  explicit operator bool() const { return static_cast<bool>(pub_); }
  std::uint32_t getNumSubscribers() const { return pub_.getNumSubscribers(); }

 private:
  friend class LockstepParticipant;
  ros::Publisher pub_;
  std::shared_ptr<std::uint64_t> count_;
};

// What makes a node a lockstep participant without touching its control logic: the node
// subscribes, advertises and sets up its periodic timers through this object instead of its
// NodeHandle. With the global parameter /lockstep false (the default) everything goes straight
// to roscpp. With it true, messages of counted streams wait in a LockstepInbox until world_sim's
// order for a step covers them, the timers run when the order does, at the step's time, and the
// node answers each order on /lockstep/ack (docs/simulation.md, "Lockstep").
class LockstepParticipant {
 public:
  // `nh` is any handle of the node (for the global parameter and topics).
  explicit LockstepParticipant(ros::NodeHandle nh);
  bool enabled() const { return enabled_; }

  template <class M>
  ros::Subscriber Subscribe(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                            std::function<void(const boost::shared_ptr<M const>&)> callback) {
    return SubscribeEvents<M>(nh, topic, queue,
                              [callback](const ros::MessageEvent<M const>& e) { callback(e.getConstMessage()); });
  }
  // The same for a callback that wants to know the publisher (an InputGuard's checked callback).
  template <class M>
  ros::Subscriber SubscribeEvents(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                                  std::function<void(const ros::MessageEvent<M const>&)> callback);
  template <class M>
  CountedPublisher Advertise(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue, bool latch = false);
  // Messages on `topic` (subscribed through this object) do not by themselves call the node to
  // a step: it gets them whenever it takes part for another reason (a timer due, a message on
  // another topic). For what a node only reads when it works anyway (robots' poses).
  void Passive(ros::NodeHandle& nh, const std::string& topic);
  // A periodic timer on ROS time. In lockstep the returned ros::Timer is empty: the inbox runs it.
  // With `rest_until`, in lockstep the timer need not run before the simulated time it returns
  // (+inf: until a message comes), and the world does not wait for the node meanwhile; without
  // the lockstep it runs every period (the callback must then return quickly when idle).
  ros::Timer CreateTimer(ros::NodeHandle& nh, ros::Duration period,
                         std::function<void(const ros::TimerEvent&)> callback,
                         std::function<double()> rest_until = {});
  template <class T>
  ros::Timer CreateTimer(ros::NodeHandle& nh, ros::Duration period, void (T::*method)(const ros::TimerEvent&), T* object) {
    return CreateTimer(nh, period, [object, method](const ros::TimerEvent& e) { (object->*method)(e); });
  }

  std::uint64_t overflow() const { return inbox_.overflow(); }

 private:
  void Arrive(const std::string& topic, const std::string& publisher, world_sim::LockstepInbox::Delivery d);
  void OnOrder(const multirobot_audio::LockstepOrder::ConstPtr& msg);
  void SayHello();
  void TryRun();

  bool enabled_ = false;
  ros::NodeHandle nh_;
  std::string node_;
  world_sim::LockstepInbox inbox_;
  ros::Subscriber order_sub_;
  ros::Publisher hello_pub_, ack_pub_;
  ros::WallTimer hello_timer_;
  bool ordered_ = false;
  // Counted subscriptions (topic -> subscriber) and publications (topic -> count).
  std::vector<std::pair<std::string, ros::Subscriber>> subscriptions_;
  std::vector<std::string> passive_;
  std::map<std::string, std::shared_ptr<std::uint64_t>> published_;
  std::map<std::string, std::uint64_t> reported_;
};

template <class M>
ros::Subscriber LockstepParticipant::SubscribeEvents(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                                                     std::function<void(const ros::MessageEvent<M const>&)> callback) {
  using Callback = boost::function<void(const ros::MessageEvent<M const>&)>;
  if (!enabled_) return nh.subscribe<M>(topic, queue, Callback(callback));
  const std::string resolved = nh.resolveName(topic);
  ros::Subscriber sub = nh.subscribe<M>(
      topic, std::max<std::uint32_t>(queue, 1000),
      Callback([this, resolved, callback](const ros::MessageEvent<M const>& event) {
        Arrive(resolved, event.getPublisherName(), [callback, event] { callback(event); });
      }),
      ros::VoidConstPtr(), LockstepTransport());
  subscriptions_.emplace_back(resolved, sub);
  return sub;
}

template <class M>
CountedPublisher LockstepParticipant::Advertise(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                                                bool latch) {
  CountedPublisher p;
  p.pub_ = nh.advertise<M>(topic, queue, latch);
  if (enabled_) {
    auto& count = published_[nh.resolveName(topic)];
    if (!count) count = std::make_shared<std::uint64_t>(0);
    p.count_ = count;
  }
  return p;
}

}  // namespace multirobot_audio
