# Every third-party package ferret uses, found once. All come from Debian bookworm
# (scripts/install-deps installs them).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(octomap REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(URDFDOM REQUIRED IMPORTED_TARGET urdfdom)
# libxml2 (Debian libxml2-dev): the strict, iterative XML check a URDF passes before
# TinyXML's recursive parser sees it (urdf/src/xml_check.cpp).
pkg_check_modules(LIBXML2 REQUIRED IMPORTED_TARGET libxml-2.0)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d aruco videoio)
# AprilTag 3 (Debian libapriltag-dev): the UAV's marker detector (uav/), the simulator's tag bitmaps.
find_package(apriltag REQUIRED)     # target: apriltag::apriltag
find_package(JPEG REQUIRED)           # camera frames: libjpeg's messages go into ferret's errors
find_package(PNG REQUIRED)            # map images: libpng reports errors to ferret, not stderr
if(FERRET_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(FERRET_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# OctoMap's imported targets are `octomap` and `octomath` (no namespace).
find_package(ompl REQUIRED)          # variables only: OMPL_INCLUDE_DIRS, OMPL_LIBRARIES
find_package(fcl REQUIRED)           # target: fcl
pkg_check_modules(SERIALPORT REQUIRED IMPORTED_TARGET libserialport)
# The planner service (service/) and its tests: HTTP/JSON over cpp-httplib.
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET GLOBAL cpp-httplib)
# libgpiod 1.6 (Debian libgpiod-dev): the miniUGV's EPM on a GPIO line of its Pi (ugv/).
pkg_check_modules(GPIOD REQUIRED IMPORTED_TARGET libgpiod)
