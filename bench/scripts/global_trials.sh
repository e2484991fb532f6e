#!/bin/sh
# Issue 35's trials: N seeded global localizations from no prior per shared building, each
# from a held-out scan (standstill) and after a drive of at most D m (gridloc track --global
# --trials N --drive-m D on the held-out half, the map drawn from the other half). One JSON
# line per building on stdout: the summary `track` prints, the wrong `localized` answers
# (standstill or end of drive, with how far off), the first update's time (median and
# slowest) and the peak memory of the run; the trial lines stay in $OUT
# (default /tmp/gridloc-global-trials). The drive's odometry carries a seeded error of
# $NOISE (FRAC,DEG_PER_M; default 0.02,1: 2 % of the path and 1 deg per metre).
# usage: global_trials.sh GRIDLOC_BINARY TRIALS DRIVE_M BUILDING...
set -eu
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../../shared/datasets/acschaefer_ple
gridloc=$1 trials=$2 drive=$3
shift 3
out=${OUT:-/tmp/gridloc-global-trials}
mkdir -p "$out"
for b in "$@"; do
  log=$data/$b-corrected.log.gz
  [ -f "$out/$b.yaml" ] ||
    "$gridloc" map-from-log --log "$log" --map-out "$out/$b.yaml" --part map >/dev/null
  /usr/bin/time -f '%M' -o "$out/$b.rss" timeout 7200 "$gridloc" track --map "$out/$b.yaml" \
    --log "$log" --part held-out --global --truth-from-log --trials "$trials" \
    --drive-m "$drive" --odometry-noise "${NOISE:-0.02,1}" --seed 1 --json >"$out/$b.jsonl" 2>"$out/$b.err" || true
  python3 - "$b" "$out/$b.jsonl" "$out/$b.rss" <<'PY'
import json, sys
building, lines, rss = sys.argv[1], sys.argv[2], sys.argv[3]
rows = [json.loads(l) for l in open(lines) if l.startswith("{")]
trials = [r for r in rows if "trial" in r]
summary = next((r["summary"] for r in rows if "summary" in r), None)
off = lambda a: a["verdict"] == "localized" and (a["error_m"] > 0.3 or a["error_deg"] > 5)
wrong = [{"trial": t["trial"], "when": when, "error_m": round(t[key]["error_m"], 2),
          "error_deg": round(t[key]["error_deg"], 1)}
         for t in trials for when, key in (("standstill", "standstill"), ("drive", "end"))
         if off(t[key])]
first = sorted(t["standstill"]["timing_ms"] for t in trials)
try:
    peak_mb = int(open(rss).read().split()[-1]) / 1024.0
except (OSError, ValueError, IndexError):
    peak_mb = None
print(json.dumps({"building": building, "trials": len(trials), "summary": summary,
                  "wrong_beyond_0.3m_5deg": wrong,
                  "first_update_median_ms": first[len(first) // 2] if first else None,
                  "first_update_max_ms": first[-1] if first else None,
                  "peak_mb": peak_mb}))
PY
done
