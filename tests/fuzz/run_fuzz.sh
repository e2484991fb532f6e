#!/bin/sh
# Runs the fuzz harnesses of a GRIDLOC_BUILD_FUZZ build one after the other and prints, per
# harness, its executions, executions per second, corpus size and findings.
#
#   run_fuzz.sh BUILD_DIR [SECONDS] [PARSER...]
#
# BUILD_DIR/tests/fuzz/harnesses.txt lists the harnesses (written by CMake); SECONDS (default
# 60) is each one's -max_total_time; PARSER names (map_pgm, octomap_bt, ...) restrict the run.
# FUZZ_KEEP_GOING=1 runs each in libFuzzer's fork mode, which carries on past a finding and
# saves every one (the recorded 10-minute runs); otherwise a harness stops at its first.
# FUZZ_RSS_LIMIT_MB (default 2048) is libFuzzer's memory limit. A harness with a dictionary,
# tests/fuzz/dict/<parser>.dict, gets it (-dict). Each harness's output goes to
# BUILD_DIR/tests/fuzz/logs/<parser>.log; findings to BUILD_DIR/tests/fuzz/findings/<parser>/.
# Exit status 1 when any harness had a finding.
set -u
build=${1:?usage: run_fuzz.sh BUILD_DIR [SECONDS] [PARSER...]}
seconds=${2:-60}
[ $# -ge 2 ] && shift 2 || shift $#
manifest=$build/tests/fuzz/harnesses.txt
[ -f "$manifest" ] || { echo "run_fuzz.sh: no $manifest (configure with -DGRIDLOC_BUILD_FUZZ=ON)" >&2; exit 2; }
logs=$build/tests/fuzz/logs
mkdir -p "$logs"
dicts=$(cd "$(dirname "$0")" && pwd)/dict
status=0
while read -r parser bin max_len corpus findings; do
  if [ $# -gt 0 ]; then
    case " $* " in *" $parser "*) ;; *) continue ;; esac
  fi
  mkdir -p "$corpus" "$findings"
  before=$(ls "$findings" | wc -l)
  if [ "${FUZZ_KEEP_GOING:-0}" = 1 ]; then
    mode="-fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1"
  else
    mode=""
  fi
  dict=""
  [ -f "$dicts/$parser.dict" ] && dict="-dict=$dicts/$parser.dict"
  # shellcheck disable=SC2086
  "$bin" $mode $dict -max_total_time="$seconds" -max_len="$max_len" \
    -rss_limit_mb="${FUZZ_RSS_LIMIT_MB:-2048}" -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$corpus" </dev/null >"$logs/$parser.log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$logs/$parser.log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$logs/$parser.log" | tail -n 1)
  if [ -z "$execs" ]; then  # fork mode: the last status line, "#N: ... time: Ts ..."
    last=$(grep -a '^#[0-9]*: ' "$logs/$parser.log" | tail -n 1)
    execs=$(echo "$last" | sed -n 's/^#\([0-9]*\):.*/\1/p')
    time_s=$(echo "$last" | sed -n 's/.* time: \([0-9]*\)s.*/\1/p')
    [ -n "$execs" ] && [ "${time_s:-0}" -gt 0 ] && rate=$((execs / time_s))
  fi
  found=$(($(ls "$findings" | wc -l) - before))
  if [ "$rc" -eq 0 ] && [ "$found" -eq 0 ]; then
    verdict=clean
  else
    verdict="FINDINGS: $found new in $findings (exit $rc)"
    status=1
  fi
  printf '%-15s execs %-10s exec/s %-7s corpus %-5s %s\n' "$parser" "${execs:-?}" "${rate:-?}" \
    "$(ls "$corpus" | wc -l)" "$verdict"
done <"$manifest"
exit $status
