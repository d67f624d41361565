#include "tool_args/heat_map.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

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

// A map's bottom row is drawn at the bottom, NaN black, the scale's top bright (viridis: yellow).
TEST(HeatMaps, RowZeroAtTheBottomAndNaNBlack) {
  const std::string path = ::testing::TempDir() + "/heat_map_cells.png";
  HeatMaps maps;
  maps.low = 0.0;
  maps.high = 1.0;
  maps.pixels_per_cell = 10;
  HeatPanel p;
  p.width = 2;
  p.height = 2;
  p.values = {std::nan(""), 0.0,   // row 0: the bottom
              0.0, 1.0};           // row 1: the top
  maps.panels = {p};
  WriteHeatMaps(path, maps);
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  // The panel starts 30 pixels from the left and 24 from the top; cell (i, j) is drawn at
  // column i, row (height - 1 - j).
  const auto at = [&](int i, int row) { return image.at<cv::Vec3b>(24 + 10 * row + 5, 30 + 10 * i + 5); };
  const cv::Vec3b nan = at(0, 1), high = at(1, 0), low = at(0, 0);
  EXPECT_EQ(nan, cv::Vec3b(0, 0, 0));
  EXPECT_GT(high[1] + high[2], 400);        // yellow: green and red high (BGR)
  EXPECT_GT(low[0], low[1]);                // viridis's dark violet: more blue than green
  EXPECT_GT(static_cast<int>(low[0]) + low[1] + low[2], 0);  // and not black
}

}  // namespace
}  // namespace multirobot_audio::tools
