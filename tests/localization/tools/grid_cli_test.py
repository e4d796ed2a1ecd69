#!/usr/bin/env python3
"""flat2d-grid and flat2d-eval as users' scripts call them: a simulated drive gridded over
its truth poses and over its own CAN odometry, judged against its truth map; every real
Velodyne capture gridded (PNG and map_server files); exit statuses on bad input.

usage: grid_cli_test.py FLAT2D_GRID FLAT2D_EVAL FLAT2D_SIM DATA_DIR SOURCE_DIR WORK_DIR
The real-capture test skips (with a message) when the shared data folder is absent.
"""
import glob
import json
import os
import subprocess
import sys
import unittest

GRID, EVAL, SIM, SOURCE, WORK = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[5], sys.argv[6]
DATA = os.environ.get("FLAT2D_DATA") or sys.argv[4]
SIM_ODOMETRY = os.path.join(SOURCE, "packaging", "config", "odometry", "flat2d_sim.textproto")


def run(tool, *args):
    return subprocess.run([tool, *args], capture_output=True, text=True, timeout=600)


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, size, maxval, pixels = data.split(b"\n", 3)
    width, height = map(int, size.split())
    return magic, width, height, int(maxval), pixels


class GridCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # 12 s of the ramps world's mapping drive: walls, crates, posts and three ramps.
        cls.drive = os.path.join(WORK, "ramps")
        result = run(SIM, "--world", "ramps", "--drive", "0", "--seed", "3", "--duration", "12",
                     "--sensor", "vlp16", "--out", cls.drive)
        assert result.returncode == 0, result.stderr

    def test_accumulated_over_truth_finds_the_true_structure(self):
        stem = os.path.join(WORK, "ramps_truth_grid")
        result = run(GRID, os.path.join(self.drive, "lidar.pcap"), "--poses", os.path.join(self.drive, "truth.tum"),
                     "--out", stem, "--png", stem + ".png", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        for key in ("product", "return_mode", "method", "revolutions", "revolutions_accumulated", "width", "height",
                    "resolution_m", "origin", "cells"):
            self.assertIn(key, summary)
        self.assertEqual(summary["product"], "VLP-16")
        self.assertTrue(summary["accumulated"])
        self.assertGreaterEqual(summary["revolutions_accumulated"], 100)  # 12 s at 10 Hz, less the ends
        self.assertEqual(summary["fans_without_pose"], 0)
        self.assertGreater(summary["cells"]["slammable"], 1000)
        magic, width, height, maxval, pixels = read_pgm(stem + ".pgm")
        self.assertEqual((magic, width, height, maxval), (b"P5", summary["width"], summary["height"], 255))
        self.assertEqual(set(pixels) - {0, 128, 254, 205}, set())
        self.assertEqual(pixels.count(0), summary["cells"]["slammable"])
        with open(stem + ".yaml") as f:
            yaml = f.read()
        self.assertIn("resolution: 0.05", yaml)
        self.assertIn("mode: trinary", yaml)
        with open(stem + ".png", "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

        judged = run(EVAL, "grid", "--truth", os.path.join(self.drive, "truth_map.yaml"), "--grid", stem + ".yaml",
                     "--tolerance", "1", "--json")
        self.assertEqual(judged.returncode, 0, judged.stderr)
        figures = json.loads(judged.stdout)
        print("ramps, 12 s, VLP-16, truth poses: precision %.4f recall %.4f" % (figures["precision"], figures["recall"]))
        self.assertGreaterEqual(figures["precision"], 0.95)
        self.assertGreaterEqual(figures["recall"], 0.8)
        self.assertEqual(figures["grid_structure"], summary["cells"]["slammable"] - figures["grid_outside"])
        # The text form says the same.
        text = run(EVAL, "grid", "--truth", os.path.join(self.drive, "truth_map.yaml"), "--grid", stem + ".yaml")
        self.assertIn("precision: %.4f" % figures["precision"], text.stdout)

    def test_one_revolution_motion_compensated_by_can_odometry(self):
        result = run(GRID, os.path.join(self.drive, "lidar.pcap"), "--can", os.path.join(self.drive, "can.log"),
                     "--dbc", os.path.join(self.drive, "vehicle.dbc"), "--odometry", SIM_ODOMETRY,
                     "--revolution", "50", "--json", "--png", os.path.join(WORK, "ramps_rev50.png"))
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertFalse(summary["accumulated"])
        self.assertTrue(summary["complete"])
        self.assertEqual(summary["revolution"], 50)
        self.assertEqual(summary["fans_without_pose"], 0)
        self.assertAlmostEqual(summary["end_time"] - summary["start_time"], 0.1, delta=0.005)  # 10 Hz
        # The odometry frame starts at the first CAN sample: 5 s at 3 m/s later, metres away.
        pose = summary["reference_pose"]
        self.assertGreater(abs(pose["x"]) + abs(pose["y"]), 5.0)
        self.assertGreater(summary["cells"]["slammable"], 100)

    def test_methods_and_options(self):
        pcap = os.path.join(self.drive, "lidar.pcap")
        counts = {}
        for method in ("slope", "cartesian", "polar"):
            result = run(GRID, pcap, "--method", method, "--revolution", "10", "--json")
            self.assertEqual(result.returncode, 0, result.stderr)
            summary = json.loads(result.stdout)
            self.assertEqual(summary["method"], method)
            counts[method] = summary["cells"]
        self.assertGreater(min(c["slammable"] for c in counts.values()), 50)
        steep = json.loads(run(GRID, pcap, "--revolution", "10", "--json", "--slammable-deg", "60").stdout)
        self.assertGreaterEqual(steep["cells"]["slammable"], counts["slope"]["slammable"])
        no_fill = json.loads(run(GRID, pcap, "--revolution", "10", "--json", "--fill-in", "off").stdout)
        self.assertFalse(no_fill["fill_in"])
        self.assertLessEqual(no_fill["cells"]["slammable"], counts["slope"]["slammable"])

    def test_bad_input_exit_statuses(self):
        pcap = os.path.join(self.drive, "lidar.pcap")
        self.assertEqual(run(GRID, pcap).returncode, 1)  # nothing to write
        self.assertEqual(run(GRID, pcap, "--json", "--bogus", "1").returncode, 1)
        self.assertEqual(run(GRID, pcap, "--json", "--method", "magic").returncode, 1)
        bad = run(GRID, pcap, "--json", "--hazard-deg", "95")
        self.assertEqual(bad.returncode, 1)
        self.assertIn("hazard_slope_deg", bad.stderr)
        self.assertEqual(run(GRID, pcap, "--json", "--accumulate").returncode, 1)
        self.assertEqual(run(GRID, os.path.join(WORK, "missing.pcap"), "--json").returncode, 2)
        broken = os.path.join(WORK, "broken.textproto")
        with open(broken, "w") as f:
            f.write("method: METHOD_SLOPE\nresolution_m: 0.05\nno_such_field: 3\n")
        bad = run(GRID, pcap, "--json", "--config", broken)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("broken.textproto:3", bad.stderr)
        bad = run(GRID, pcap, "--json", "--revolution", "100000")
        self.assertEqual(bad.returncode, 3)
        self.assertIn("complete revolutions", bad.stderr)
        tum = os.path.join(WORK, "bad.tum")
        with open(tum, "w") as f:
            f.write("1 0 0 0 0 0 0 1\nnot a pose\n")
        bad = run(GRID, pcap, "--json", "--poses", tum)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("bad.tum:2", bad.stderr)
        # flat2d-eval
        self.assertEqual(run(EVAL, "grid", "--truth", os.path.join(self.drive, "truth_map.yaml")).returncode, 1)
        self.assertEqual(run(EVAL, "nothing").returncode, 1)
        self.assertEqual(run(EVAL, "grid", "--truth", tum, "--grid", tum).returncode, 2)

    def test_real_captures(self):
        captures = sorted(glob.glob(os.path.join(DATA, "velodyne", "*", "*.pcap")) +
                          glob.glob(os.path.join(DATA, "velodyne", "raw_payloads", "*.bin")))
        if not captures:
            self.skipTest("no Velodyne captures under %s (set FLAT2D_DATA)" % os.path.join(DATA, "velodyne"))
        for capture in captures:
            name = os.path.splitext(os.path.basename(capture))[0]
            png = os.path.join(WORK, "real_" + name + ".png")
            result = run(GRID, capture, "--json", "--png", png, "--out", os.path.join(WORK, "real_" + name))
            if "vls128" in capture:
                self.assertEqual(result.returncode, 3, name)  # unsupported model, named
                self.assertIn("VLS-128", result.stderr)
                continue
            self.assertEqual(result.returncode, 0, name + ": " + result.stderr)
            summary = json.loads(result.stdout)
            cells = summary["cells"]
            print("%-55s %-8s %s revolution 0: slammable %6d hazard %6d free %7d" % (
                name[:55], summary["product"], "complete" if summary["complete"] else "partial ",
                cells["slammable"], cells["hazard"], cells["free"]))
            self.assertEqual(summary["malformed"], 0, name)
            self.assertGreater(cells["slammable"], 100, name)
            self.assertGreater(cells["free"], 500, name)
            self.assertTrue(os.path.getsize(png) > 1000, name)


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=[sys.argv[0], "-v"])
