#!/usr/bin/env python3
"""flat2d-inspect as users' scripts call it: JSON keys, values and exit statuses.

usage: inspect_cli_test.py FLAT2D_INSPECT DATA_DIR WORK_DIR
Exits 77 (ctest: skipped) when the shared data folder is absent.
"""
import json
import os
import subprocess
import sys
import unittest

INSPECT, WORK = sys.argv[1], sys.argv[3]
DATA = os.environ.get("FLAT2D_DATA") or sys.argv[2]  # the environment wins, as in the C++ tests
REQUIRED_KEYS = {"product", "return_mode", "data_packets", "position_packets", "revolutions",
                 "points", "malformed"}


def run(*args):
    return subprocess.run([INSPECT, *args], capture_output=True, text=True, timeout=120)


def capture(relative):
    return os.path.join(DATA, "velodyne", relative)


class InspectCli(unittest.TestCase):
    def test_json_of_a_gps_vlp16_capture(self):
        result = run("--json", capture("vlp16/mrpt_sample_velodyne_vlp16_gps.pcap"))
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertTrue(REQUIRED_KEYS <= summary.keys(), summary.keys())
        self.assertEqual(summary["product"], "VLP-16")
        self.assertEqual(summary["return_mode"], "strongest")
        self.assertEqual(summary["data_packets"], 293)
        self.assertEqual(summary["position_packets"], 57)
        self.assertEqual(summary["revolutions"], 3)
        self.assertEqual(summary["malformed"], 0)
        self.assertEqual(summary["time_source"], "gps")
        complete = [r for r in summary["revolution_list"] if r["complete"]]
        self.assertEqual(len(complete), 3)
        self.assertEqual(summary["points"], sum(r["points"] for r in summary["revolution_list"]))

    def test_dual_return_counts_both_returns(self):
        summary = json.loads(run("--json", capture(
            "vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap")).stdout)
        self.assertEqual(summary["return_mode"], "dual")
        self.assertEqual(summary["data_packets"], 603)
        self.assertEqual(summary["revolutions"], 3)

    def test_unsupported_model_is_named_with_status_3(self):
        result = run("--json", capture("vls128/DERIVED_nebula_vls128_1614315746471294674.pcap"))
        self.assertEqual(result.returncode, 3)
        summary = json.loads(result.stdout)
        self.assertEqual(summary["product"], "VLS-128")
        self.assertFalse(summary["supported"])
        self.assertIn("VLS-128", summary["error"])
        self.assertIn("VLS-128", result.stderr)

    def test_png_of_a_revolution(self):
        png = os.path.join(WORK, "inspect_cli_test.png")
        result = run("--png", png, "--revolution", "1",
                     capture("hdl32e/rust-lidar-utils_hdl32_example.pcap"))
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_bad_input_statuses(self):
        self.assertEqual(run("--no-such-option", "x").returncode, 1)
        self.assertEqual(run("--data-port", "70000", "x").returncode, 1)
        self.assertEqual(run("--model", "HDL-64E", "x").returncode, 1)
        missing = run(os.path.join(WORK, "does-not-exist.pcap"))
        self.assertEqual(missing.returncode, 2)
        self.assertIn("does-not-exist.pcap", missing.stderr)
        truncated = os.path.join(WORK, "truncated.pcap")
        with open(capture("vlp16/rust-lidar-utils_velodyne_example.pcap"), "rb") as f:
            data = f.read()
        with open(truncated, "wb") as f:
            f.write(data[: len(data) // 2 + 7])
        result = run("--json", truncated)
        summary = json.loads(result.stdout)
        self.assertTrue(summary["capture"]["file_truncated"])
        self.assertGreater(summary["data_packets"], 0)


if __name__ == "__main__":
    if not os.path.isdir(os.path.join(DATA, "velodyne")):
        print(f"real data not found: {DATA}/velodyne (set FLAT2D_DATA)")
        sys.exit(77)
    unittest.main(argv=[sys.argv[0]])
