#!/usr/bin/env python3
"""flat2d-graph as users' scripts call it: output file, --json keys and values, exit statuses,
for 2D (g2o, TORO) and 3D (g2o VERTEX_SE3:QUAT / EDGE_SE3:QUAT) graphs.

usage: graph_cli_test.py FLAT2D_GRAPH DATA_DIR WORK_DIR
Tests on the shared pose graphs skip when ../shared/data is absent; the others always run.
"""
import json
import math
import os
import subprocess
import sys
import unittest

TOOL, WORK = sys.argv[1], sys.argv[3]
DATA = os.environ.get("FLAT2D_DATA") or sys.argv[2]
POSEGRAPH = os.path.join(DATA, "posegraph")
HAVE_DATA = os.path.isdir(POSEGRAPH)
JSON_KEYS = ("input", "format", "dimension", "output", "nodes", "edges", "init", "solver", "cost",
             "initial", "final", "iterations", "stop_reason", "converged", "seconds")

# A square of 4 poses with one loop closure; the odometry says 1 m per side.
SQUARE = """VERTEX_SE2 0 0 0 0
VERTEX_SE2 1 1.2 0.1 1.5
VERTEX_SE2 2 0.9 1.1 3.0
VERTEX_SE2 3 -0.1 0.8 -1.6
EDGE_SE2 0 1 1 0 1.5707963267948966 100 0 0 100 0 1000
EDGE_SE2 1 2 1 0 1.5707963267948966 100 0 0 100 0 1000
EDGE_SE2 2 3 1 0 1.5707963267948966 100 0 0 100 0 1000
EDGE_SE2 3 0 1 0 1.5707963267948966 100 0 0 100 0 1000
"""



def unit(*q):
    """A quaternion (x y z w) scaled to unit norm, as g2o text."""
    norm = math.sqrt(sum(c * c for c in q))
    return " ".join(repr(c / norm) for c in q)


# The same square in 3D: each edge 1 m forward, then 90 degrees about z; the vertices start
# tilted and off the plane.
Q90 = "0 0 0.7071067811865476 0.7071067811865476"
INFO6 = "100 0 0 0 0 0 100 0 0 0 0 100 0 0 0 400 0 0 400 0 400"
CUBE = f"""VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1
VERTEX_SE3:QUAT 1 1.2 0.1 0.3 {unit(0.05, -0.1, 0.7, 0.7)}
VERTEX_SE3:QUAT 2 0.9 1.1 -0.2 {unit(0.1, 0, 1, 0.05)}
VERTEX_SE3:QUAT 3 -0.1 0.8 0.1 {unit(0, 0.1, -0.7, 0.7)}
FIX 0
EDGE_SE3:QUAT 0 1 1 0 0 {Q90} {INFO6}
EDGE_SE3:QUAT 1 2 1 0 0 {Q90} {INFO6}
EDGE_SE3:QUAT 2 3 1 0 0 {Q90} {INFO6}
EDGE_SE3:QUAT 3 0 1 0 0 {Q90} {INFO6}
"""


def run(*args):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, timeout=300)


def write(name, text):
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def records(path):
    with open(path) as f:
        return [line.split() for line in f if line.strip()]


class GraphCli(unittest.TestCase):
    def test_square_json_and_output(self):
        out = os.path.join(WORK, "square_out.g2o")
        result = run("optimize", write("square.g2o", SQUARE), out, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        for key in JSON_KEYS:
            self.assertIn(key, summary)
        self.assertEqual(summary["format"], "g2o")
        self.assertEqual((summary["nodes"], summary["edges"]), (4, 4))
        self.assertTrue(summary["converged"])
        self.assertGreater(summary["initial"]["g2o_chi2"], 1.0)
        self.assertLess(summary["final"]["g2o_chi2"], 1e-9)  # the measurements are consistent
        rows = records(out)
        vertices = {int(r[1]): [float(v) for v in r[2:5]] for r in rows if r[0] == "VERTEX_SE2"}
        self.assertEqual(len([r for r in rows if r[0] == "EDGE_SE2"]), 4)
        for vid, (x, y) in {1: (1, 0), 2: (1, 1), 3: (0, 1)}.items():
            self.assertAlmostEqual(vertices[vid][0], x, places=6)
            self.assertAlmostEqual(vertices[vid][1], y, places=6)

    def test_text_output_names_both_costs(self):
        result = run("optimize", write("square2.g2o", SQUARE), os.path.join(WORK, "o2.g2o"),
                     "--solver", "gn", "--init", "odometry")
        self.assertEqual(result.returncode, 0, result.stderr)
        for label in ("g2o chi2:", "SE-Sync f:", "iterations:", "time:"):
            self.assertIn(label, result.stdout)

    def test_bad_input_statuses(self):
        square = write("square3.g2o", SQUARE)
        out = os.path.join(WORK, "never.g2o")
        self.assertEqual(run().returncode, 1)
        self.assertEqual(run("frobnicate", square, out).returncode, 1)
        self.assertEqual(run("optimize", square).returncode, 1)  # no OUT
        self.assertEqual(run("optimize", square, out, "--solver", "newton").returncode, 1)
        self.assertEqual(run("optimize", square, out, "--max-iterations", "0").returncode, 1)
        self.assertEqual(run("optimize", square, out, "--init", "magic").returncode, 1)
        self.assertEqual(run("--help").returncode, 0)
        missing = run("optimize", os.path.join(WORK, "none.g2o"), out)
        self.assertEqual(missing.returncode, 2)
        self.assertIn("none.g2o", missing.stderr)
        broken = write("broken.g2o", SQUARE.replace("VERTEX_SE2 2 0.9 1.1 3.0", "VERTEX_SE2 2 0.9 x 3.0"))
        result = run("optimize", broken, out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("broken.g2o:3:", result.stderr)
        mixed = write("mixed.g2o", SQUARE + "VERTEX_SE3:QUAT 9 0 0 0 0 0 0 1\n")
        result = run("optimize", mixed, out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("mixed.g2o:9: 3D record VERTEX_SE3:QUAT in an SE(2) graph", result.stderr)
        self.assertFalse(os.path.exists(out))
        unwritable = run("optimize", square, os.path.join(WORK, "no_such_dir", "o.g2o"))
        self.assertEqual(unwritable.returncode, 2)

    def test_cube_json_and_output_in_3d(self):
        out = os.path.join(WORK, "cube_out.g2o")
        for cost in ("g2o", "sesync"):
            result = run("optimize", write("cube.g2o", CUBE), out, "--json", "--cost", cost)
            self.assertEqual(result.returncode, 0, result.stderr)
            summary = json.loads(result.stdout)
            for key in JSON_KEYS:
                self.assertIn(key, summary)
            self.assertEqual((summary["format"], summary["dimension"]), ("g2o_se3", 3))
            self.assertEqual((summary["nodes"], summary["edges"]), (4, 4))
            self.assertTrue(summary["converged"])
            self.assertGreater(summary["initial"]["sesync_f"], 1.0)
            self.assertLess(summary["final"]["g2o_chi2"], 1e-9)  # the measurements are consistent
            self.assertLess(summary["final"]["sesync_f"], 1e-9)
            rows = records(out)
            self.assertEqual({r[0] for r in rows}, {"VERTEX_SE3:QUAT", "EDGE_SE3:QUAT", "FIX"})
            self.assertIn(["FIX", "0"], rows)
            vertices = {int(r[1]): [float(v) for v in r[2:9]] for r in rows if r[0] == "VERTEX_SE3:QUAT"}
            for vid, (x, y) in {0: (0, 0), 1: (1, 0), 2: (1, 1), 3: (0, 1)}.items():
                self.assertAlmostEqual(vertices[vid][0], x, places=6)
                self.assertAlmostEqual(vertices[vid][1], y, places=6)
                self.assertAlmostEqual(vertices[vid][2], 0.0, places=6)
                self.assertAlmostEqual(abs(vertices[vid][5]), abs(math.sin(vid * math.pi / 4)), places=6)
            edges = [r for r in rows if r[0] == "EDGE_SE3:QUAT"]
            self.assertEqual(len(edges), 4)
            self.assertEqual(len(edges[0]), 3 + 7 + 21)

    def test_cube_text_and_chordal_start(self):
        result = run("optimize", write("cube2.g2o", CUBE), os.path.join(WORK, "cube2_out.g2o"),
                     "--init", "chordal", "--solver", "gn")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("(g2o_se3)", result.stdout)
        self.assertIn("iterations:", result.stdout)

    def test_bad_3d_input_names_file_and_line(self):
        out = os.path.join(WORK, "never3d.g2o")
        cases = {
            "short.g2o": (CUBE.replace("VERTEX_SE3:QUAT 2 0.9 1.1 -0.2", "VERTEX_SE3:QUAT 2 0.9 1.1"),
                          "short.g2o:3: VERTEX_SE3:QUAT needs 7 numbers"),
            "word.g2o": (CUBE.replace("EDGE_SE3:QUAT 1 2 1 0 0", "EDGE_SE3:QUAT 1 2 one 0 0"),
                         "word.g2o:7: field 4 'one' is not a finite number"),
            "unknown.g2o": (CUBE + f"EDGE_SE3:QUAT 3 8 1 0 0 {Q90} {INFO6}\n", "unknown.g2o:10: edge names vertex 8"),
            "quat.g2o": (CUBE.replace(unit(0.05, -0.1, 0.7, 0.7), "0.5 -0.1 0.7 0.7"),
                         "quat.g2o:2: quaternion norm 1.113553 is not 1"),
        }
        for name, (text, expected) in cases.items():
            result = run("optimize", write(name, text), out)
            self.assertEqual(result.returncode, 2, name)
            self.assertIn(expected, result.stderr)
        self.assertFalse(os.path.exists(out))

    @unittest.skipUnless(HAVE_DATA, "shared pose graphs absent")
    def test_garage_reaches_the_published_sesync_optimum_in_3d(self):
        out = os.path.join(WORK, "garage_out.g2o")
        result = run("optimize", os.path.join(POSEGRAPH, "g2o", "parking-garage.g2o"), out, "--cost", "sesync",
                     "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertEqual((summary["format"], summary["nodes"], summary["edges"]), ("g2o_se3", 1661, 6275))
        self.assertTrue(summary["converged"])
        self.assertEqual(float(f'{summary["final"]["sesync_f"]:.4g}'), 1.263)  # IJRR 2019 Table 2
        again = json.loads(run("optimize", out, os.path.join(WORK, "garage_again.g2o"), "--cost", "sesync",
                               "--json").stdout)
        self.assertAlmostEqual(again["initial"]["sesync_f"], summary["final"]["sesync_f"], delta=1e-6)

    @unittest.skipUnless(HAVE_DATA, "shared pose graphs absent")
    def test_intel_reaches_the_published_sesync_optimum(self):
        out = os.path.join(WORK, "intel_out.g2o")
        result = run("optimize", os.path.join(POSEGRAPH, "g2o", "intel.g2o"), out, "--init", "odometry",
                     "--cost", "sesync", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertTrue(summary["converged"])
        self.assertAlmostEqual(summary["final"]["sesync_f"], 52.35, delta=52.35e-3)  # IJRR 2019 f*
        self.assertGreater(summary["initial"]["sesync_f"], 1000 * summary["final"]["sesync_f"])
        # The written estimate is the optimum: re-optimizing it from the file starts there.
        again = json.loads(run("optimize", out, os.path.join(WORK, "intel_again.g2o"), "--cost", "sesync",
                               "--json").stdout)
        self.assertAlmostEqual(again["initial"]["sesync_f"], summary["final"]["sesync_f"], delta=1e-4)

    @unittest.skipUnless(HAVE_DATA, "shared pose graphs absent")
    def test_toro_input_writes_g2o(self):
        out = os.path.join(WORK, "m3500_out.g2o")
        result = run("optimize", os.path.join(POSEGRAPH, "toro", "M3500_P_toro.graph"), out, "--json",
                     "--cost", "sesync")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertEqual(summary["format"], "toro")
        self.assertAlmostEqual(summary["final"]["sesync_f"], 6432.0, delta=6.432)
        tags = {r[0] for r in records(out)}
        self.assertEqual(tags, {"VERTEX_SE2", "EDGE_SE2"})


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=[sys.argv[0]])
