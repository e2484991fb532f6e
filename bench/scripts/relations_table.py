#!/usr/bin/env python3
"""Summarizes relations_table.sh's per-pair CSVs: one JSON line per log and estimator.

usage: relations_table.py OUT_DIR NAME
Fields: pairs, failures (beyond 0.2 m or 5 deg), the mean errors over the pairs that
succeed, failures per overlap band, failures among the pairs overlapping >= 0.5, the answers
a consumer would use (localized; converged for icp) that fail (and of them those outside
their 2-sigma ellipse), the share of those answers
within their 2-sigma ellipse, the median ms per pair and the peak memory (MB) of the runs.
"""
import csv
import glob
import json
import statistics
import sys

out, name = sys.argv[1], sys.argv[2]
BANDS = [(0.0, 0.2), (0.2, 0.4), (0.4, 0.6), (0.6, 0.8), (0.8, 1.01)]
for log in ("intel", "fr079"):
    for est in ("icp", "correlation", "correlation+icp"):
        files = sorted(glob.glob(f"{out}/{name}.{log}.{est}.*.csv"))
        if not files:
            continue
        rows = [r for f in files for r in csv.DictReader(open(f))]
        failed = [r for r in rows if r["failed"] == "1"]
        good = [r for r in rows if r["failed"] == "0"]
        used = [r for r in rows
                if (r["verdict"] == "localized" if r["verdict"] else r["converged"] == "1")]
        overlapping = [r for r in rows if float(r["overlap"]) >= 0.5]
        bands = {}
        for lo, hi in BANDS:
            band = [r for r in rows if lo <= float(r["overlap"]) < hi]
            bands[f"{lo:g}-{min(hi, 1):g}"] = [len(band), sum(r["failed"] == "1" for r in band)]
        ms = [json.load(open(f.replace(".csv", ".json")))["median_ms"] for f in files]
        kb = [int(open(f.replace(".csv", ".kb")).read().split()[-1]) for f in files]
        print(json.dumps({
            "name": name, "log": log, "estimator": est, "seeds": len(files),
            "pairs": len(rows), "failures": len(failed),
            "ok_translation_m": round(statistics.mean(float(r["translation_error_m"]) for r in good), 4),
            "ok_rotation_deg": round(statistics.mean(float(r["rotation_error_deg"]) for r in good), 3),
            "by_overlap": bands,
            "overlapping": [len(overlapping), sum(r["failed"] == "1" for r in overlapping)],
            "used": len(used), "used_failures": sum(r["failed"] == "1" for r in used),
            "used_failures_outside_2sigma": sum(r["failed"] == "1" and r["within_2sigma"] == "0"
                                                for r in used),
            "within_2sigma": round(sum(r["within_2sigma"] == "1" for r in used) / max(1, len(used)), 3),
            "median_ms": round(statistics.median(ms), 2),
            "peak_mb": round(max(kb) / 1024.0, 1)}))
