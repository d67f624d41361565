#include "charging_state_publisher.h"

#include <multirobot_audio/ChargingState.h>
#include <visualization_msgs/MarkerArray.h>

namespace multirobot_audio {

ChargingStatePublisher::ChargingStatePublisher(LockstepParticipant& lockstep, ros::NodeHandle pnh, double rate,
                                               double wait_distance, const std::string& robot_namespace)
    : state_pub_(lockstep.Advertise<multirobot_audio::ChargingState>(pnh, "state", 10)),
      markers_pub_(pnh.advertise<visualization_msgs::MarkerArray>("charger", 1)),
      rate_(rate),
      wait_distance_(wait_distance),
      label_(robot_namespace) {
  if (!label_.empty() && label_.front() == '/') label_.erase(0, 1);
}

void ChargingStatePublisher::Update(const charging_demo::ChargingController& controller, const ChargingStatus& status,
                                    const std::string& odom_frame, const ros::Time& now) {
  const charging_demo::ChargingBehaviour& b = controller.behaviour();
  const bool changed = !published_ || b.phase() != last_phase_ || status.lock != last_lock_ ||
                       status.docked != last_docked_ || status.want_lock != last_want_;
  const bool due = rate_ > 0.0 && (now - last_time_).toSec() >= 1.0 / rate_;
  if (!changed && !due) return;
  state_pub_.publish(ToChargingState(b, status, now.toSec(), odom_frame, now));
  if (markers_pub_.getNumSubscribers() > 0) {
    markers_pub_.publish(
        ToChargerMarkers(b, status, wait_distance_, label_, controller.navigator().pose(), odom_frame, now));
  }
  published_ = true;
  last_time_ = now;
  last_phase_ = b.phase();
  last_lock_ = status.lock;
  last_docked_ = status.docked;
  last_want_ = status.want_lock;
}

}  // namespace multirobot_audio
