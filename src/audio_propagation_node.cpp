// audio_propagation: every simulated robot's audio link. See docs/nodes.md for topics and parameters.
#include <cstdio>

#include <ros/ros.h>

#include "audio_propagation_ros.h"
#include "params.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "audio_propagation");
  try {
    ros::NodeHandle pnh("~");
    multirobot_audio::AudioPropagationRos node(ros::NodeHandle(), pnh,
                                               multirobot_audio::ReadAudioPropagationOptions(pnh));
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "audio_propagation: %s\n", e.what());
    return 1;
  }
  return 0;
}
