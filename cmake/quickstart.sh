#!/bin/sh
# gridloc quick start on Debian 12: installs the missing Debian packages (only those the build
# needs), builds Release into build/, then runs the demo or the whole test suite.
#   cmake/quickstart.sh demo   # set up, build, run `gridloc demo` on the bundled map and ring
#   cmake/quickstart.sh test   # set up, build, run every test (ctest)
set -eu
cd "$(dirname "$0")/.."

job=${1:-demo}
case "$job" in
  demo | test) ;;
  *) echo "usage: $0 demo|test" >&2; exit 2 ;;
esac

packages="cmake make g++ libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev \
  libgtest-dev libbenchmark-dev libopencv-core-dev libopencv-imgcodecs-dev libopencv-imgproc-dev \
  liboctomap-dev zlib1g-dev libpng-dev libboost-dev"
# The test job also builds and runs the ROS 1 node's end-to-end test (examples/gridloc_ros).
if [ "$job" = test ]; then
  packages="$packages pkg-config ros-core-dev libroscpp-dev libtf2-ros-dev libtf2-geometry-msgs-dev \
  libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libstd-srvs-dev libdiagnostic-msgs-dev \
  python3-rospy python3-roslaunch python3-sensor-msgs python3-nav-msgs python3-std-srvs \
  python3-tf2-msgs python3-geometry-msgs"
fi
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "== installing:$missing"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
  $sudo apt-get update -qq
  # shellcheck disable=SC2086  # the list is meant to split
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $missing
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release

if [ "$job" = demo ]; then
  cmake --build build -j"$jobs" --target gridloc  # the tool only, not the tests and benchmarks
  ./build/examples/gridloc demo
  echo "== the gridloc tool is $(pwd)/build/examples/gridloc ('gridloc --help' lists its commands)"
else
  cmake --build build -j"$jobs"
  cd build && ctest --output-on-failure -j"$jobs"
fi
