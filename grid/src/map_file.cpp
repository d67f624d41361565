#include "grid/map_file.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include "grid/file_path.h"
#include "grid/input_error.h"
#include "grid/yaml_fields.h"

namespace grid {
namespace {

struct MapFileFields {
  std::string image;
  double resolution = 0.0;
  Pose2D origin;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
};

MapFileFields ParseFields(const std::string& file) {
  // The thesis's map is not shipped: say how to get it rather than only that it is missing.
  if (file.find("maps/thesis/") != std::string::npos && !IsRegularFile(file)) {
    throw InputError(file, "", "map file not found; the thesis's map is not shipped: run scripts/get_thesis_map.sh");
  }
  const YamlFields root = YamlFields::Load(file, "map file");
  root.ExpectOnlyKeys(
      {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"});
  MapFileFields f;
  f.image = root.String("image");
  f.resolution = root.Number("resolution");
  if (!(f.resolution > 0.0) || !std::isfinite(f.resolution)) {
    root.Fail("resolution", "expected a positive number of metres per cell, got " +
                                root.String("resolution"));
  }
  const std::vector<double> origin = root.Numbers("origin", 3, "[x, y, yaw]");
  f.origin = {origin[0], origin[1], origin[2]};
  const double negate = root.Number("negate", 0.0);
  if (negate != 0.0 && negate != 1.0) root.Fail("negate", "expected 0 or 1");
  f.negate = negate == 1.0;
  f.occupied_thresh = root.Number("occupied_thresh", f.occupied_thresh);
  f.free_thresh = root.Number("free_thresh", f.free_thresh);
  if (!(f.occupied_thresh > 0.0 && f.occupied_thresh <= 1.0)) {
    root.Fail("occupied_thresh", "expected a number in (0, 1]");
  }
  if (!(f.free_thresh >= 0.0 && f.free_thresh < f.occupied_thresh)) {
    root.Fail("free_thresh", "expected a number in [0, occupied_thresh)");
  }
  if (root.Has("mode") && root.String("mode") != "trinary") {
    root.Fail("mode", "expected 'trinary' (the only mode supported)");
  }
  return f;
}

// One grey value per pixel, 0 (black) to 255 (white), averaging colour channels as map_server
// does and ignoring alpha.
cv::Mat ToGrey8(const cv::Mat& image) {
  cv::Mat img8;
  if (image.depth() == CV_16U) {
    image.convertTo(img8, CV_8U, 1.0 / 257.0);
  } else {
    image.convertTo(img8, CV_8U);
  }
  const int colour_channels = img8.channels() >= 3 ? 3 : 1;
  cv::Mat grey(img8.rows, img8.cols, CV_8UC1);
  for (int r = 0; r < img8.rows; ++r) {
    const std::uint8_t* in = img8.ptr<std::uint8_t>(r);
    std::uint8_t* out = grey.ptr<std::uint8_t>(r);
    for (int c = 0; c < img8.cols; ++c) {
      int sum = 0;
      for (int k = 0; k < colour_channels; ++k) sum += in[c * img8.channels() + k];
      out[c] = static_cast<std::uint8_t>(sum / colour_channels);
    }
  }
  return grey;
}

}  // namespace

OccupancyMap LoadMapFile(const std::string& yaml_path) {
  namespace fs = std::filesystem;
  const MapFileFields f = ParseFields(yaml_path);

  fs::path image_path(f.image);
  if (image_path.is_relative()) image_path = fs::path(yaml_path).parent_path() / image_path;
  std::string why;
  if (!IsRegularFile(image_path.string(), &why)) {
    throw InputError(yaml_path, "image", "file not found (" + why + "): " + image_path.string());
  }
  cv::Mat image;
  if (cv::haveImageReader(image_path.string())) {
    image = cv::imread(image_path.string(), cv::IMREAD_UNCHANGED);
  }
  if (image.empty()) {
    throw InputError(yaml_path, "image",
                     "expected a PGM or PNG image, cannot decode " + image_path.string());
  }
  const cv::Mat grey = ToGrey8(image);

  OccupancyMap map(grey.cols, grey.rows, f.resolution, f.origin);
  for (int r = 0; r < grey.rows; ++r) {
    const int j = grey.rows - 1 - r;  // image rows run top-down, map rows bottom-up
    const std::uint8_t* row = grey.ptr<std::uint8_t>(r);
    for (int i = 0; i < grey.cols; ++i) {
      const double value = f.negate ? row[i] : 255 - row[i];
      const double occupancy = value / 255.0;
      Cell c = Cell::kUnknown;
      if (occupancy > f.occupied_thresh) {
        c = Cell::kOccupied;
      } else if (occupancy < f.free_thresh) {
        c = Cell::kFree;
      }
      map.set(i, j, c);
    }
  }
  return map;
}

}  // namespace grid
