#!/bin/sh
# clang-tidy over the library (engine, grids, sensors) with the project's .clang-tidy: a small
# set of bug and needless-copy checks, every finding an error. Configures a compile database
# in $TIDY_DIR (default build-tidy; no build) and runs run-clang-tidy on $JOBS cores (default
# 2). About 14 s a file on one core of the 2-core guest: some 13 minutes for the 116 files,
# so it is a developer's command, not a CI stage (issue 31).
# usage: cmake/tidy.sh [FILE_REGEX]   (default: every library source)
set -eu
cd "$(dirname "$0")/.."
if ! command -v run-clang-tidy >/dev/null 2>&1; then
  echo "cmake/tidy.sh: run-clang-tidy not found (Debian: apt-get install clang-tidy)" >&2
  exit 2
fi
dir=${TIDY_DIR:-build-tidy}
cmake -S . -B "$dir" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DGRIDLOC_BUILD_BENCH=OFF \
  -DGRIDLOC_BUILD_ROS=OFF >/dev/null
regex=${1:-"$(pwd)/(engine|grids|sensors)/src/.*\\.cpp\$"}
run-clang-tidy -j "${JOBS:-2}" -p "$dir" -quiet "$regex"
