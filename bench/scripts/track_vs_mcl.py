#!/usr/bin/env python3
"""gridloc's tracker and MRPT's particle filter on the same scans and the same odometry (issue 34).

Feeds ../shared/peers/mcl's harness (mcl_peer, built by its build.sh) with exactly the scans
and odometry poses of one `gridloc track --json --truth-from-log` run, as one trial from a
uniform start, and compares the two scan by scan against the log's corrected poses.

usage: track_vs_mcl.py LOG.gz MAP.yaml TRACK.jsonl MCL_PEER [--max-range 20] [--json]

right: within 0.1 m and 2 deg. gridloc's answer counts when its verdict is `localized`; the
filter has no verdict, so its answer counts when its cloud's position spread is under 0.35 m
(the peer README's rule). wrong: counted, and more than 0.3 m or 5 deg off.
Prints one summary line (or a JSON object with --json).
"""
import argparse, gzip, json, math, os, subprocess, sys, tempfile


def read_lasers(path):
    """Each FLASER line's ranges and pose, in order (the log's laser index)."""
    opener = gzip.open if path.endswith(".gz") else open
    lasers = []
    with opener(path, "rt", errors="replace") as f:
        for line in f:
            w = line.split()
            if not w or w[0] != "FLASER":
                continue
            n = int(w[1])
            lasers.append(([float(v) for v in w[2:2 + n]], tuple(float(v) for v in w[2 + n:5 + n])))
    return lasers


def write_steps(lasers, track, path, max_range):
    with open(path, "w") as out:
        out.write(f"T 0 {track[0]['index']}\n")
        for step in track:
            ranges, truth = lasers[step["index"]]
            o = step["odometry"]
            n = len(ranges)
            angle_step = math.pi / (n - 1 if n % 2 == 1 else n)
            r = [v if 0.0 < v < max_range else 0.0 for v in ranges]
            out.write("S %d %.6f %.6f %.6f %.6f %.6f %.6f %d %.9f %.9f %s\n" % (
                step["index"], *truth, o["x"], o["y"], o["theta"], n, -0.5 * math.pi, angle_step,
                " ".join("%.3f" % v for v in r)))


def tally(track, mcl):
    right = lambda e: e["error_m"] <= 0.1 and e["error_deg"] <= 2.0
    off = lambda e: e["error_m"] > 0.3 or e["error_deg"] > 5.0
    g_says = [s["verdict"] == "localized" for s in track]
    m_says = [m["std_xy_m"] < 0.35 for m in mcl]
    g_right = [a and right(s) for a, s in zip(g_says, track)]
    m_right = [a and right(m) for a, m in zip(m_says, mcl)]
    n = len(track)
    times = sorted(s["timing_ms"] for s in track)
    steps_ms = [mcl[0]["elapsed_ms"]] + [b["elapsed_ms"] - a["elapsed_ms"] for a, b in zip(mcl, mcl[1:])]
    return {
        "scans": n,
        "gridloc_localized_pct": 100.0 * sum(g_says) / n,
        "gridloc_right_pct": 100.0 * sum(g_right) / n,
        "gridloc_wrong": sum(a and off(s) for a, s in zip(g_says, track)),
        "mcl_converged_pct": 100.0 * sum(m_says) / n,
        "mcl_right_pct": 100.0 * sum(m_right) / n,
        "mcl_wrong": sum(a and off(m) for a, m in zip(m_says, mcl)),
        "gridloc_wrong_where_mcl_right": sum(g and off(s) and m for g, s, m in zip(g_says, track, m_right)),
        "gridloc_not_right_where_mcl_right": sum(m and not g for g, m in zip(g_right, m_right)),
        "mcl_not_right_where_gridloc_right": sum(g and not m for g, m in zip(g_right, m_right)),
        "gridloc_update_median_ms": times[n // 2],
        "gridloc_update_p99_ms": times[min(n - 1, int(0.99 * n))],
        "mcl_update_median_ms": sorted(steps_ms)[n // 2],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("log"); ap.add_argument("map"); ap.add_argument("track"); ap.add_argument("peer")
    ap.add_argument("--max-range", type=float, default=20.0)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    track = [json.loads(l) for l in open(a.track) if l.startswith("{")]
    track = [s for s in track if "verdict" in s]
    if not track or "odometry" not in track[0] or "error_m" not in track[0]:
        sys.exit("track_vs_mcl: the track needs gridloc track --json --truth-from-log lines")
    with tempfile.TemporaryDirectory() as tmp:
        steps = os.path.join(tmp, "steps.txt")
        write_steps(read_lasers(a.log), track, steps, a.max_range)
        env = dict(os.environ, MCL_TRACK="1")
        out = subprocess.run([a.peer, a.map, steps], env=env, capture_output=True, text=True,
                             check=True).stdout
    mcl = [json.loads(l) for l in out.splitlines() if l.startswith('{"step"')]
    if len(mcl) != len(track):
        sys.exit(f"track_vs_mcl: the peer answered {len(mcl)} of {len(track)} scans")
    t = tally(track, mcl)
    if a.json:
        print(json.dumps(t))
        return
    print(f"{t['scans']} scans: gridloc localized {t['gridloc_localized_pct']:.1f} %, right "
          f"{t['gridloc_right_pct']:.1f} %, wrong {t['gridloc_wrong']}; MCL converged "
          f"{t['mcl_converged_pct']:.1f} %, right {t['mcl_right_pct']:.1f} %, wrong {t['mcl_wrong']}; "
          f"gridloc wrong where MCL right {t['gridloc_wrong_where_mcl_right']}, not right where MCL "
          f"right {t['gridloc_not_right_where_mcl_right']}; update median {t['gridloc_update_median_ms']:.1f} "
          f"ms (p99 {t['gridloc_update_p99_ms']:.1f}) vs MCL {t['mcl_update_median_ms']:.1f} ms")


if __name__ == "__main__":
    main()
