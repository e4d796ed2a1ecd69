#!/usr/bin/env python3
"""flat2d-can as users' scripts call it: CSV columns, JSON keys, TUM output, exit statuses.

usage: can_cli_test.py FLAT2D_CAN DATA_DIR SOURCE_DIR WORK_DIR
Exits 77 (ctest: skipped) when the shared data folder is absent.
"""
import csv
import io
import json
import math
import os
import subprocess
import sys
import unittest

TOOL, SOURCE, WORK = sys.argv[1], sys.argv[3], sys.argv[4]
DATA = os.environ.get("FLAT2D_DATA") or sys.argv[2]
RAV4 = os.path.join(DATA, "can", "toyota_rav4h_comma2k19")
DBC = os.path.join(RAV4, "toyota_rav4_hybrid_2017_pt_generated.dbc")
LOG = os.path.join(RAV4, "DERIVED_comma2k19_rav4h_seg40_bus0.candump.log")
CONFIG = os.path.join(SOURCE, "packaging", "config", "odometry", "toyota_rav4_hybrid_2017.textproto")


def run(*args):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, timeout=120)


class CanCli(unittest.TestCase):
    def test_decode_csv_selects_signals(self):
        result = run("decode", "--dbc", DBC, LOG, "--csv", "--signals", "WHEEL_SPEEDS.WHEEL_SPEED_FL,YAW_RATE")
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = list(csv.DictReader(io.StringIO(result.stdout)))
        self.assertEqual(list(rows[0].keys()), ["time", "message", "signal", "value"])
        fl = [r for r in rows if r["signal"] == "WHEEL_SPEED_FL"]
        yaw = [r for r in rows if r["signal"] == "YAW_RATE"]
        self.assertEqual(len(fl), 4974)
        self.assertEqual(len(yaw), 4974)
        self.assertEqual(len(rows), len(fl) + len(yaw))
        speeds = [float(r["value"]) for r in fl]  # km/h, PROVENANCE.md: 28.5-71.8 km/h
        self.assertAlmostEqual(min(speeds), 28.5, delta=0.6)
        self.assertAlmostEqual(max(speeds), 71.8, delta=0.6)

    def test_decode_json_summary(self):
        result = run("decode", "--dbc", DBC, LOG, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        for key in ("frames", "frames_per_id", "malformed_lines", "checksum_failures", "duration_s"):
            self.assertIn(key, summary)
        self.assertEqual(summary["frames"], 53800)
        self.assertEqual(summary["frames_per_id"]["0AA"], 4974)
        self.assertEqual(summary["frames_per_id"]["0B4"], 2487)
        self.assertEqual(summary["malformed_lines"], 0)
        self.assertEqual(summary["checksum_failures"], 0)
        self.assertAlmostEqual(summary["duration_s"], 60.0, delta=0.1)

    def test_odom_writes_tum(self):
        tum = os.path.join(WORK, "rav4.tum")
        result = run("odom", "--dbc", DBC, "--config", CONFIG, LOG, "--tum", tum, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertAlmostEqual(summary["distance_m"], 1002.8, delta=1.0)
        with open(tum) as f:
            lines = [line.split() for line in f]
        self.assertEqual(len(lines), summary["samples"])
        self.assertTrue(all(len(line) == 8 for line in lines))
        times = [float(line[0]) for line in lines]
        self.assertEqual(times, sorted(times))
        x, y, qz, qw = (float(lines[-1][i]) for i in (1, 2, 6, 7))
        self.assertAlmostEqual(qz * qz + qw * qw, 1.0, places=6)
        self.assertAlmostEqual(math.hypot(x, y), math.hypot(summary["final_pose"]["x"], summary["final_pose"]["y"]), 3)

    def test_malformed_lines_are_counted_with_their_numbers(self):
        log = os.path.join(WORK, "damaged.log")
        with open(LOG) as f:
            head = [next(f) for _ in range(100)]
        head[10] = "(46408.6) can0 0AA#XYZ\n"
        head[20] = "garbage\n"
        with open(log, "w") as f:
            f.writelines(head)
        summary = json.loads(run("decode", "--dbc", DBC, log, "--json").stdout)
        self.assertEqual(summary["frames"], 98)
        self.assertEqual(summary["malformed_lines"], 2)
        self.assertEqual(summary["first_malformed_lines"], [11, 21])

    def test_bad_input_statuses(self):
        self.assertEqual(run("decode", LOG).returncode, 1)  # no --dbc
        self.assertEqual(run("frobnicate", "--dbc", DBC, LOG).returncode, 1)
        self.assertEqual(run("decode", "--dbc", DBC, LOG, "--csv", "--json").returncode, 1)
        missing = run("decode", "--dbc", os.path.join(WORK, "none.dbc"), LOG)
        self.assertEqual(missing.returncode, 2)
        self.assertIn("none.dbc", missing.stderr)
        bad_config = os.path.join(WORK, "bad.textproto")
        with open(bad_config, "w") as f:
            f.write("mapping {\n  wheel_speed_front_lft { }\n}\n")
        result = run("odom", "--dbc", DBC, "--config", bad_config, LOG, "--tum", os.path.join(WORK, "x.tum"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("bad.textproto:2:", result.stderr)
        self.assertIn("wheel_speed_front_lft", result.stderr)


if __name__ == "__main__":
    if not os.path.isdir(RAV4):
        print(f"real data not found: {RAV4} (set FLAT2D_DATA)")
        sys.exit(77)
    unittest.main(argv=[sys.argv[0]])
