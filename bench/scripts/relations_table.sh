#!/bin/sh
# Issue 30's tables: gridloc relations on Intel's 106 benchmark pairs (seeds 1-5) and
# freiburg-079's 1141 (seeds 1-2) with every estimator, then relations_table.py's rows (one
# JSON line per log, estimator and configuration). EXTRA: more relations options for every
# run; NAME labels them (default "default"). The per-pair CSVs stay in $OUT.
# usage: relations_table.sh GRIDLOC_BINARY
#   before issue 30's changes: NAME=before EXTRA="--no-join-returns --covariance-cells 3
#   --covariance-temperature 1" relations_table.sh build/examples/gridloc
set -eu
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../../shared/datasets
gridloc=$1
out=${OUT:-/tmp/gridloc-relations-table}
name=${NAME:-default}
mkdir -p "$out"
run() {  # log estimator seed relations-options...
  log=$1 est=$2 seed=$3
  shift 3
  /usr/bin/time -f "%M" -o "$out/$name.$log.$est.$seed.kb" \
    "$gridloc" relations "$@" --estimator "$est" --seed "$seed" --json \
    --trials-out "$out/$name.$log.$est.$seed.csv" ${EXTRA:-} >"$out/$name.$log.$est.$seed.json"
}
for est in icp correlation correlation+icp; do
  for seed in 1 2 3 4 5; do
    run intel "$est" "$seed" --log "$data/xiaofeng419_SLAM-2D-LIDAR-SCAN/intel.gfs.log" \
      --relations "$data/xiaofeng419_SLAM-2D-LIDAR-SCAN/intel.relations" \
      --time-offset 976052857.337311
  done
  for seed in 1 2; do
    run fr079 "$est" "$seed" --log "$data/acschaefer_ple/freiburg-079-corrected.log.gz" \
      --relations "$data/xiaofeng419_SLAM-2D-LIDAR-SCAN/fr079.relations" \
      --time-offset 1211.44 --tolerance 0.05
  done
done
python3 "$here/relations_table.py" "$out" "$name"
