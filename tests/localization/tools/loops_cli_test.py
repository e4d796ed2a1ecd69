#!/usr/bin/env python3
"""flat2d-eval loops as users call it: a TUM truth of two laps round a block, drifted by an
uncalibrated gyro, searched for loop-closure candidates by distance and by trajectory shape;
the JSON keys scripts read; exit statuses on bad input.

usage: loops_cli_test.py FLAT2D_EVAL WORK_DIR [quick]
Needs no shared data (the KITTI 00 run is localization_loops_test's). "quick" (the sanitizer
build) drives 1.3 laps, whose revisits are the first corner's.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import unittest

EVAL, WORK = sys.argv[1:3]
QUICK = len(sys.argv) > 3 and sys.argv[3] == "quick"
LAPS = 1.3 if QUICK else 2.2
KEYS = ("poses", "path_length_m", "final_drift_m", "maps", "informative_maps", "revisits",
        "informative_revisits", "opposite_revisits", "distance_candidates", "distance_correct",
        "distance_precision", "distance_recall", "shape_candidates", "shape_correct",
        "shape_precision", "shape_recall", "shape_seconds")


def run(*args):
    return subprocess.run([EVAL, "loops", *args], capture_output=True, text=True, timeout=900)


def block_pose(s):
    """The block of loop_candidates_test.cpp: straights 60, 40, 65, 39 m, left corners of
    radii 8, 12, 6, 15 m; the pose s metres along, in closed form (laps lie on one another)."""
    lap = [(60, 0), (math.pi * 4, 8), (40, 0), (math.pi * 6, 12), (65, 0), (math.pi * 3, 6),
           (39, 0), (math.pi * 7.5, 15)]
    s = math.fmod(s, sum(length for length, _ in lap))
    x = y = heading = 0.0
    for length, radius in lap:
        along = min(s, length)
        if radius == 0:
            x, y = x + along * math.cos(heading), y + along * math.sin(heading)
        else:
            turn = along / radius
            x += radius * (math.sin(heading + turn) - math.sin(heading))
            y += radius * (math.cos(heading) - math.cos(heading + turn))
            heading += turn
        s -= along
        if s <= 0:
            break
    return x, y, heading


def write_block_tum(path, laps=2.2, speed=5.0):
    with open(path, "w") as out:
        out.write("# t x y z qx qy qz qw\n")
        for k in range(int(laps * 343.2 / 0.5)):
            x, y, heading = block_pose(0.5 * k)
            out.write(f"{0.5 * k / speed:.3f} {x:.6f} {y:.6f} 0 0 0 {math.sin(heading / 2):.9f} "
                      f"{math.cos(heading / 2):.9f}\n")


class LoopsCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        cls.truth = os.path.join(WORK, "block.tum")
        write_block_tum(cls.truth, laps=LAPS)

    def test_shape_finds_the_revisits_distance_misses(self):
        result = run("--truth", self.truth, "--drift-yaw-bias", "0.03", "--drift-bound", "0.1", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        for key in KEYS:
            self.assertIn(key, report)
        print(json.dumps(report))
        self.assertGreater(report["informative_revisits"], 2 if QUICK else 10)
        self.assertGreater(report["final_drift_m"], 3.0 if QUICK else 10.0)
        self.assertGreaterEqual(report["shape_recall"], 0.9)
        self.assertGreaterEqual(report["shape_precision"], 0.9)
        self.assertLess(report["distance_recall"], 0.5)

    def test_text_report(self):
        short = os.path.join(WORK, "short.tum")
        write_block_tum(short, laps=1.0)
        result = run("--truth", short, "--drift-yaw-bias", "0.03", "--drift-bound", "0.1")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("trajectory shape", result.stdout)
        self.assertIn("local maps", result.stdout)

    def test_bad_input(self):
        missing = run("--kitti-poses", os.path.join(WORK, "none.txt"))
        self.assertEqual(missing.returncode, 2)
        self.assertIn("none.txt", missing.stderr)
        self.assertEqual(run().returncode, 1)
        self.assertEqual(run("--truth", self.truth, "--kitti-poses", self.truth).returncode, 1)
        self.assertEqual(run("--truth", self.truth, "--no-such-flag").returncode, 1)
        self.assertEqual(run("--truth", self.truth, "--piece-length", "0").returncode, 1)
        self.assertEqual(run("--truth", self.truth, "--radius", "ten").returncode, 1)
        bad = os.path.join(WORK, "bad.tum")
        with open(bad, "w") as out:
            out.write("0 0 0 0 0 0 0 1\n0.1 1 0 0 0 0 x 1\n")
        malformed = run("--truth", bad)
        self.assertEqual(malformed.returncode, 2)
        self.assertIn("bad.tum", malformed.stderr)
        kitti = os.path.join(WORK, "poses.txt")
        with open(kitti, "w") as out:
            out.write("1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n")
        short = run("--kitti-poses", kitti)
        self.assertEqual(short.returncode, 2)
        self.assertIn("poses.txt: line 2", short.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
