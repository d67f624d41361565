# OpenCV, found once for every component. Debian's core, imgcodecs and imgproc -dev packages
# ship no CMake config (that comes only with the whole of libopencv-dev), so the libraries the
# project uses are found directly and wrapped in imported targets: a component that draws or
# reads images links OpenCV::imgproc or OpenCV::imgcodecs by name, and gets the headers (as
# system headers, whose warnings are not ours) with them.
find_path(OPENCV_INCLUDE_DIR opencv2/imgcodecs.hpp PATH_SUFFIXES opencv4 REQUIRED)
foreach(module core imgproc imgcodecs)
  find_library(OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
  add_library(OpenCV::${module} UNKNOWN IMPORTED)
  set_target_properties(OpenCV::${module} PROPERTIES
    IMPORTED_LOCATION ${OPENCV_${module}_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${OPENCV_INCLUDE_DIR}
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES ${OPENCV_INCLUDE_DIR})
endforeach()
set_target_properties(OpenCV::imgproc PROPERTIES INTERFACE_LINK_LIBRARIES OpenCV::core)
set_target_properties(OpenCV::imgcodecs PROPERTIES INTERFACE_LINK_LIBRARIES OpenCV::core)
