#!/bin/sh
# Issue 34's table: gridloc track --global through the held-out half of shared buildings under
# each odometry model, and MRPT's particle filter on the same scans and odometry
# (track_vs_mcl.py). One JSON line per building and model on stdout; the track JSON Lines
# stay in $OUT (default /tmp/gridloc-track-buildings).
# usage: track_buildings.sh GRIDLOC_BINARY MCL_PEER BUILDING...
#   MCL_PEER: ../shared/peers/mcl/build.sh prints its path; "none" runs gridloc alone.
# Models: a = 2 % + 1 deg/m, b = 5 % + 5 deg/m, c = 2 % + 1 deg/m with a 0.3 m / 10 deg slip
# every ~50 m (seeded), raw = the robot's own odometry (csail only: its GMapping .gfs).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../../shared/datasets
gridloc=$1 peer=$2
shift 2
out=${OUT:-/tmp/gridloc-track-buildings}
mkdir -p "$out"
row() {  # building model track-options...
  b=$1 m=$2
  shift 2
  log=$data/acschaefer_ple/$b-corrected.log.gz
  start=$(date +%s.%N)
  timeout 3600 "$gridloc" track --map "$out/$b.yaml" --log "$log" --part held-out --global \
    --truth-from-log --json "$@" >"$out/$b.$m.jsonl" 2>"$out/$b.$m.err" || true
  wall=$(echo "$(date +%s.%N) - $start" | bc | sed "s/^\./0./")
  if [ "$peer" = none ]; then
    side=$(python3 - "$out/$b.$m.jsonl" <<'PY'
import json, sys
t = [json.loads(l) for l in open(sys.argv[1]) if l.startswith("{")]
n = max(1, len(t)); off = lambda s: s["error_m"] > 0.3 or s["error_deg"] > 5
print(json.dumps({"scans": len(t),
  "gridloc_localized_pct": 100.0 * sum(s["verdict"] == "localized" for s in t) / n,
  "gridloc_right_pct": 100.0 * sum(s["verdict"] == "localized" and s["error_m"] <= 0.1 and s["error_deg"] <= 2 for s in t) / n,
  "gridloc_wrong": sum(s["verdict"] == "localized" and off(s) for s in t)}))
PY
)
  else
    side=$(python3 "$here/track_vs_mcl.py" "$log" "$out/$b.yaml" "$out/$b.$m.jsonl" "$peer" --json)
  fi
  echo "{\"building\":\"$b\",\"model\":\"$m\",\"wall_s\":$wall,\"result\":$side}"
}
for b in "$@"; do
  [ -f "$out/$b.yaml" ] ||
    "$gridloc" map-from-log --log "$data/acschaefer_ple/$b-corrected.log.gz" --map-out "$out/$b.yaml" \
      --part map >/dev/null
  row "$b" a --odometry-noise 0.02,1 --seed 1
  row "$b" b --odometry-noise 0.05,5 --seed 1
  row "$b" c --odometry-noise 0.02,1,50 --seed 1
  if [ "$b" = csail ]; then
    row "$b" raw --raw-odometry "$data/xiaofeng419_SLAM-2D-LIDAR-SCAN/csail.corrected.gfs"
  fi
done
