#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include <ros/ros.h>

namespace multirobot_audio {

// A publisher that knows whether anyone listens without asking roscpp, and counts what it sent.
// roscpp answers getNumSubscribers() and every publish() with a search by name through all the
// topics a node publishes: a simulator with hundreds of robot topics spent a third of its time
// there. This one keeps its own count from roscpp's connect and disconnect callbacks, so a topic
// nobody reads costs nothing: the caller asks Heard() before it builds the message.
class WatchedPublisher {
 public:
  WatchedPublisher() = default;

  template <class M>
  static WatchedPublisher Advertise(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                                    bool latch = false) {
    WatchedPublisher p;
    auto listeners = p.listeners_;
    p.pub_ = nh.advertise<M>(
        topic, queue, [listeners](const ros::SingleSubscriberPublisher&) { ++*listeners; },
        [listeners](const ros::SingleSubscriberPublisher&) { --*listeners; }, ros::VoidConstPtr(), latch);
    p.topic_ = p.pub_.getTopic();
    return p;
  }

  bool Heard() const { return *listeners_ > 0; }
  template <class M>
  void publish(const M& msg) {
    pub_.publish(msg);
    ++sent_;
  }
  const std::string& topic() const { return topic_; }
  std::uint64_t sent() const { return sent_; }

 private:
  ros::Publisher pub_;
  // Changed by roscpp's callbacks (on the node's callback queue).
  std::shared_ptr<std::atomic<int>> listeners_ = std::make_shared<std::atomic<int>>(0);
  std::string topic_;
  std::uint64_t sent_ = 0;
};

}  // namespace multirobot_audio
