#pragma once

#include <string>

#include "local_mutex/team_sim.h"

namespace local_mutex {

// Draws a recorded run like the thesis's Figure 7.5 and writes it as an image (PNG by the
// file's extension): a lane per robot, a thin line while WANTED, a thick one while HELD, a
// dashed one while SILENT; a down arrow for each message sent, labelled (type, T, id), an up
// arrow for each packet heard and a cross for each noise, with the Lamport clock after the
// event in brackets. Throws std::runtime_error when the file cannot be written, or when the
// run was not recorded (TeamSimOptions::record).
void DrawTimeline(const TeamSim& sim, const std::string& path);

}  // namespace local_mutex
