# Finds OpenCV's core and imgcodecs from Debian's per-module -dev packages, which ship no
# OpenCVConfig.cmake (that comes only with the heavy libopencv-dev). Prefers the config
# package when present. Defines imported targets opencv_core and opencv_imgcodecs, and
# opencv_imgproc when it is installed (optional: only the gridloc tool's heatmaps draw with it).
find_package(OpenCV QUIET COMPONENTS core imgcodecs OPTIONAL_COMPONENTS imgproc)
if(NOT OpenCV_FOUND)
  find_path(OpenCVModules_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
  foreach(module core imgcodecs imgproc)
    find_library(OpenCVModules_${module}_LIBRARY opencv_${module})
    if(OpenCVModules_${module}_LIBRARY AND NOT TARGET opencv_${module})
      add_library(opencv_${module} UNKNOWN IMPORTED)
      set_target_properties(opencv_${module} PROPERTIES
        IMPORTED_LOCATION ${OpenCVModules_${module}_LIBRARY}
        INTERFACE_INCLUDE_DIRECTORIES ${OpenCVModules_INCLUDE_DIR})
    endif()
  endforeach()
endif()
include(FindPackageHandleStandardArgs)
if(OpenCV_FOUND)
  set(OpenCVModules_FOUND TRUE)
else()
  find_package_handle_standard_args(OpenCVModules
    REQUIRED_VARS OpenCVModules_INCLUDE_DIR OpenCVModules_core_LIBRARY
                  OpenCVModules_imgcodecs_LIBRARY)
endif()
