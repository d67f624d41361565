#pragma once

namespace nava_modem {

// A microphone's position in the robot's frame (REP-103: x forward, y left), metres from the
// array's origin. Shared by the array renderer (room_array.h) and the direction estimator.
struct Microphone2D {
  double x = 0.0, y = 0.0;
};

}  // namespace nava_modem
