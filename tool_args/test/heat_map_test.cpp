#include "tool_args/heat_map.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>

namespace multirobot_audio::tools {
namespace {

HeatPanel Ramp(const std::string& title, int width, int height) {
  HeatPanel p;
  p.title = title;
  p.width = width;
  p.height = height;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) p.values.push_back(i == j ? std::nan("") : 10.0 * i);
  return p;
}

TEST(HeatMaps, PanelsSideBySideAreWrittenAndBadOnesRefused) {
  const std::string path = ::testing::TempDir() + "/heat_map_test.png";
  std::filesystem::remove(path);
  HeatMaps maps;
  maps.unit = "dB";
  maps.low = 0.0;
  maps.high = 50.0;
  maps.panels = {Ramp("left", 6, 4), Ramp("right", 8, 3)};
  WriteHeatMaps(path, maps);
  EXPECT_GT(std::filesystem::file_size(path), 100u);

  HeatMaps short_panel = maps;
  short_panel.panels[1].values.pop_back();
  try {
    WriteHeatMaps(path, short_panel);
    FAIL() << "a panel short of values was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("panel 'right' has 23 values for 8 x 3 cells"), std::string::npos) << e.what();
  }
  HeatMaps flat = maps;
  flat.high = flat.low;
  EXPECT_THROW(WriteHeatMaps(path, flat), std::invalid_argument);
  EXPECT_THROW(WriteHeatMaps("/nonexistent-folder/heat.png", maps), std::runtime_error);
}

}  // namespace
}  // namespace multirobot_audio::tools
