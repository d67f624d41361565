#include "grid/map_file.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "grid/input_error.h"

namespace grid {
namespace {

namespace fs = std::filesystem;

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("grid_map_file_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  // A 4 x 3 image: top row black (wall), middle row mid grey (unknown), bottom row white.
  std::string WriteImage(const std::string& name) {
    cv::Mat img(3, 4, CV_8UC1, cv::Scalar(255));
    img.row(0).setTo(0);
    img.row(1).setTo(128);
    const fs::path p = dir_ / name;
    EXPECT_TRUE(cv::imwrite(p.string(), img));
    return p.string();
  }

  // Expects loading to fail with a message that names the file and contains `words`.
  void ExpectError(const std::string& yaml, const std::string& words) {
    try {
      LoadMapFile(yaml);
      FAIL() << "expected an InputError for " << yaml;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(yaml), std::string::npos) << msg;
      EXPECT_NE(msg.find(words), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line expected: " << msg;
    }
  }

  fs::path dir_;
};

constexpr char kGood[] =
    "image: room.pgm\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n";

TEST_F(MapFileTest, LoadsPgmWithMapServerSemantics) {
  WriteImage("room.pgm");
  const OccupancyMap map = LoadMapFile(Write("room.yaml", kGood));
  EXPECT_EQ(map.width(), 4);
  EXPECT_EQ(map.height(), 3);
  EXPECT_DOUBLE_EQ(map.resolution(), 0.5);
  EXPECT_DOUBLE_EQ(map.origin().x, 1.0);
  EXPECT_DOUBLE_EQ(map.origin().y, 2.0);
  // Image row 0 (top) is map row 2; the bottom image row is map row 0.
  EXPECT_EQ(map.at(0, 2), Cell::kOccupied);
  EXPECT_EQ(map.at(3, 1), Cell::kUnknown);
  EXPECT_EQ(map.at(2, 0), Cell::kFree);
}

TEST_F(MapFileTest, LoadsPngAndNegate) {
  WriteImage("room.png");
  const OccupancyMap map = LoadMapFile(Write(
      "room.yaml", "image: room.png\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\nmode: trinary\n"));
  EXPECT_EQ(map.at(0, 2), Cell::kFree);
  EXPECT_EQ(map.at(0, 0), Cell::kOccupied);
}

TEST_F(MapFileTest, LoadsColourImageByChannelAverage) {
  cv::Mat img(2, 2, CV_8UC3, cv::Scalar(255, 255, 255));
  img.at<cv::Vec3b>(0, 0) = cv::Vec3b(0, 0, 0);
  ASSERT_TRUE(cv::imwrite((dir_ / "c.png").string(), img));
  const OccupancyMap map =
      LoadMapFile(Write("c.yaml", "image: c.png\nresolution: 1\norigin: [0, 0, 0]\n"));
  EXPECT_EQ(map.at(0, 1), Cell::kOccupied);
  EXPECT_EQ(map.at(1, 1), Cell::kFree);
}

TEST_F(MapFileTest, MissingYaml) { ExpectError((dir_ / "nope.yaml").string(), "not found"); }

TEST_F(MapFileTest, AMissingThesisMapSaysHowToGetIt) {
  ExpectError((dir_ / "maps" / "thesis" / "hospital_section.yaml").string(), "run scripts/get_thesis_map.sh");
}

TEST_F(MapFileTest, MalformedYaml) {
  ExpectError(Write("bad.yaml", "image: [unclosed\nresolution: 0.1\n"), "malformed YAML");
}

TEST_F(MapFileTest, NotAMapping) { ExpectError(Write("bad.yaml", "- 1\n- 2\n"), "mapping"); }

TEST_F(MapFileTest, UnknownKey) {
  WriteImage("room.pgm");
  ExpectError(Write("bad.yaml", std::string(kGood) + "colour: blue\n"), "colour: unknown key");
}

TEST_F(MapFileTest, MissingField) {
  ExpectError(Write("bad.yaml", "image: room.pgm\norigin: [0, 0, 0]\n"), "resolution: missing");
}

TEST_F(MapFileTest, NonPositiveResolution) {
  WriteImage("room.pgm");
  ExpectError(Write("bad.yaml", "image: room.pgm\nresolution: 0\norigin: [0, 0, 0]\n"),
              "resolution: expected a positive number");
  ExpectError(Write("bad2.yaml", "image: room.pgm\nresolution: -0.1\norigin: [0, 0, 0]\n"),
              "resolution: expected a positive number");
  ExpectError(Write("bad3.yaml", "image: room.pgm\nresolution: abc\norigin: [0, 0, 0]\n"),
              "resolution: expected a number");
}

TEST_F(MapFileTest, BadOrigin) {
  WriteImage("room.pgm");
  ExpectError(Write("bad.yaml", "image: room.pgm\nresolution: 1\norigin: [0, 0]\n"),
              "origin: expected [x, y, yaw]");
}

TEST_F(MapFileTest, BadThresholdsNegateAndMode) {
  WriteImage("room.pgm");
  const std::string head = "image: room.pgm\nresolution: 1\norigin: [0, 0, 0]\n";
  ExpectError(Write("a.yaml", head + "occupied_thresh: 1.5\n"), "occupied_thresh");
  ExpectError(Write("b.yaml", head + "free_thresh: 0.9\n"), "free_thresh");
  ExpectError(Write("c.yaml", head + "negate: 2\n"), "negate: expected 0 or 1");
  ExpectError(Write("d.yaml", head + "mode: scale\n"), "mode: expected 'trinary'");
}

// Found by fuzz/world_file.cpp: a key that is a list or a mapping, not text, escaped as
// yaml-cpp's bad conversion instead of an InputError.
TEST_F(MapFileTest, KeyThatIsNotTextIsRefused) {
  WriteImage("room.pgm");
  ExpectError(Write("list_key.yaml", std::string(kGood) + "[a, b]: 1\n"), "expected text keys");
  ExpectError(Write("map_key.yaml", std::string(kGood) + "? {a: 1}\n: 2\n"), "expected text keys, got a mapping");
  ExpectError(Write("null_key.yaml", std::string(kGood) + "~: 2\n"), "expected text keys, got an empty key");
}

TEST_F(MapFileTest, MissingImage) {
  ExpectError(Write("bad.yaml", "image: gone.pgm\nresolution: 1\norigin: [0, 0, 0]\n"),
              "image: file not found");
}

TEST_F(MapFileTest, ImageThatIsNotAnImage) {
  Write("text.pgm", "this is not a picture\n");
  ExpectError(Write("bad.yaml", "image: text.pgm\nresolution: 1\norigin: [0, 0, 0]\n"),
              "image: expected a PGM or PNG image");
}

TEST(MapFileShipped, OurMapsLoad) {
  for (const char* name : {"office.yaml", "test_room.yaml"}) {
    const OccupancyMap map = LoadMapFile(std::string(PROJECT_MAPS_DIR) + "/" + name);
    EXPECT_GT(map.width(), 0) << name;
  }
  const OccupancyMap office = LoadMapFile(std::string(PROJECT_MAPS_DIR) + "/office.yaml");
  EXPECT_NEAR(office.width_m(), 34.0, 0.1);
  EXPECT_NEAR(office.height_m(), 14.0, 0.1);
}

TEST(MapFileShipped, ThesisHospitalSectionLoadsByPath) {
  const std::string path = std::string(SHARED_MAPS_DIR) + "/hospital_section.yaml";
  if (!fs::exists(path)) GTEST_SKIP() << "no shared maps beside the project at " << path;
  const OccupancyMap map = LoadMapFile(path);
  EXPECT_EQ(map.width(), 1086);
  EXPECT_EQ(map.height(), 443);
  EXPECT_NEAR(map.width_m(), 34.0, 0.1);  // "34 x 14 m" at 0.0313 m per pixel
  EXPECT_NEAR(map.height_m(), 14.0, 0.2);
  int free_cells = 0;
  for (Cell c : map.cells()) free_cells += c == Cell::kFree;
  EXPECT_GT(free_cells, map.width() * map.height() / 2);
}

}  // namespace
}  // namespace grid
