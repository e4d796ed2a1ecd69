#!/usr/bin/env python3
"""flat2d-map and flat2d-eval (relations, traj) as users' scripts call them: a simulated
drive built into a prior map against its truth map and trajectory; the map's info and
renders; a real 2D laser log built and judged by the relations metric; traj --3d on a
written 3D trajectory and on the TUM RGB-D fr1/rpy truth; exit statuses on bad input.

usage: map_cli_test.py FLAT2D_MAP FLAT2D_EVAL FLAT2D_SIM DATA_DIR SOURCE_DIR WORK_DIR [quick]
The real-log test skips (with a message) when the shared data folder is absent. "quick"
(the sanitizer build) runs the same commands on the first 25 s of the drive and 60 scans of
the log, and checks what they write but not the accuracy, which the release build checks.
"""
import json
import math
import os
import subprocess
import sys
import unittest

MAP, EVAL, SIM, SOURCE, WORK = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[5], sys.argv[6]
DATA = os.environ.get("FLAT2D_DATA") or sys.argv[4]
SIM_ODOMETRY = os.path.join(SOURCE, "packaging", "config", "odometry", "flat2d_sim.textproto")
QUICK = len(sys.argv) > 7 and sys.argv[7] == "quick"
# The occluders map against the truth, measured 0.77 precision, 0.88 recall (1 cell) and
# 0.108 m ATE (docs/benchmarks.md); with the truth's poses the same revolutions give 1.00
# and 0.93, so the margin below is the builder's, not the grids'.
PRECISION, RECALL, ATE_RMSE_M = 0.70, 0.80, 0.15


def run(tool, *args):
    return subprocess.run([tool, *args], capture_output=True, text=True, timeout=1200)


class DriveMap(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # The occluders world's mapping drive: round a row of boxes in a walled room, 101 m,
        # with a survey GNSS receiver's fixes in the position packets (the LiDAR data is the
        # same with or without them).
        os.makedirs(WORK, exist_ok=True)
        cls.drive = os.path.join(WORK, "occluders")
        duration = ["--duration", "25"] if QUICK else []
        result = run(SIM, "--world", "occluders", "--drive", "0", "--seed", "5", "--sensor", "vlp16",
                     "--gnss-rtk", *duration, "--out", cls.drive)
        assert result.returncode == 0, result.stderr
        cls.map = os.path.join(WORK, "occluders.f2m")
        d = cls.drive
        cls.build = run(MAP, "build", "--pcap", os.path.join(d, "lidar.pcap"), "--can", os.path.join(d, "can.log"),
                        "--dbc", os.path.join(d, "vehicle.dbc"), "--odometry", SIM_ODOMETRY,
                        "--anchor", os.path.join(d, "truth.tum"), "--out", cls.map,
                        "--png", os.path.join(WORK, "occluders_map.png"),
                        "--trajectory", os.path.join(WORK, "occluders_map.tum"),
                        "--enu", "48.0125,7.8345,280", "--json")

    def test_build_summary(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        summary = json.loads(self.build.stdout)
        for key in ("map", "scans", "keyframes", "tracking_accepted", "loop_closures", "loop_closures_switched_off",
                    "loop_closures_gated", "loop_closures_drift",
                    "viewpoints", "odometry_scale"):
            self.assertIn(key, summary)
        self.assertGreater(summary["keyframes"], 40 if QUICK else 150)  # 101 m, a keyframe per 0.5 m or more
        self.assertGreater(summary["tracking_accepted"], 0.9 * summary["keyframes"])
        self.assertGreater(summary["viewpoints"], 2 if QUICK else 8)
        self.assertAlmostEqual(summary["odometry_scale"], 1.0, delta=0.02)
        self.assertTrue(os.path.getsize(os.path.join(WORK, "occluders_map.png")) > 1000)

    def test_map_matches_the_truth_map(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        stem = os.path.join(WORK, "occluders_render")
        result = run(MAP, "render", self.map, "--out", stem + ".yaml")
        self.assertEqual(result.returncode, 0, result.stderr)
        result = run(EVAL, "grid", "--truth", os.path.join(self.drive, "truth_map.yaml"), "--grid", stem + ".yaml",
                     "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        grid = json.loads(result.stdout)
        if QUICK:
            return
        self.assertGreater(grid["precision"], PRECISION, grid)
        self.assertGreater(grid["recall"], RECALL, grid)

    def test_trajectory_against_the_truth(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        result = run(EVAL, "traj", "--truth", os.path.join(self.drive, "truth.tum"),
                     "--est", os.path.join(WORK, "occluders_map.tum"), "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        ate = json.loads(result.stdout)
        self.assertFalse(ate["aligned"])
        self.assertGreater(ate["poses"], 1000)
        self.assertEqual(sum(ate["heading_histogram"]), ate["poses"])
        self.assertEqual(ate["heading_histogram_bin_rad"], 0.005)
        self.assertLessEqual(ate["heading_within_0_02"], ate["heading_within_0_025"])
        for part in ("position", "longitudinal", "lateral"):
            self.assertLessEqual(ate[part + "_p50_m"], ate[part + "_p95_m"])
            self.assertLessEqual(ate[part + "_p99_m"], ate["ate_max_m"] + 1e-6)
        aligned = json.loads(run(EVAL, "traj", "--truth", os.path.join(self.drive, "truth.tum"),
                                 "--est", os.path.join(WORK, "occluders_map.tum"), "--align", "--json").stdout)
        self.assertTrue(aligned["aligned"])
        self.assertLessEqual(aligned["ate_rmse_m"], ate["ate_rmse_m"] + 1e-9)  # the best fit is no worse
        if not QUICK:
            self.assertLess(ate["ate_rmse_m"], ATE_RMSE_M, ate)

    def test_scale_from_the_gnss_in_the_position_packets(self):
        d = self.drive
        common = ["build", "--pcap", os.path.join(d, "lidar.pcap"), "--can", os.path.join(d, "can.log"),
                  "--dbc", os.path.join(d, "vehicle.dbc"), "--odometry", SIM_ODOMETRY,
                  "--anchor", os.path.join(d, "truth.tum")]
        scaled = os.path.join(WORK, "occluders_scaled")
        calibrated = scaled + ".odometry.textproto"
        result = run(MAP, *common, "--scale-from-gnss", "--out", scaled + ".f2m", "--trajectory", scaled + ".tum",
                     "--calibrated-odometry-out", calibrated, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertGreaterEqual(summary["track_scale_fixes"], 20 if QUICK else 60)  # one fix a second
        self.assertAlmostEqual(summary["track_scale"], 1.0, delta=0.01)
        # The calibrated odometry: the builder's scale times the GNSS correction, which is the
        # simulated wheels' error (they read 0.57 % long: 0.9945), and flat2d-can reads it.
        with open(calibrated) as f:
            text = f.read()
        scale = float(text.split("wheel_speed_scale:")[1].split()[0])
        self.assertAlmostEqual(scale, summary["odometry_scale"] * summary["track_scale"], delta=1e-5)
        if not QUICK:
            self.assertAlmostEqual(scale, 0.9945, delta=0.003)
        result = run(MAP.replace("flat2d-map", "flat2d-can"), "odom", "--dbc", os.path.join(d, "vehicle.dbc"),
                     "--config", calibrated, os.path.join(d, "can.log"), "--tum", scaled + ".odom.tum")
        self.assertEqual(result.returncode, 0, result.stderr)
        ate = json.loads(run(EVAL, "traj", "--truth", os.path.join(d, "truth.tum"), "--est", scaled + ".tum",
                             "--json").stdout)
        if not QUICK:
            self.assertLess(ate["ate_rmse_m"], ATE_RMSE_M, ate)
        # Exclusive, for drives only, and a capture must hold fixes.
        self.assertEqual(run(MAP, *common, "--scale-from-gnss", "--scale-from", os.path.join(d, "truth.tum"),
                             "--out", scaled + "_x.f2m").returncode, 1)
        result = run(MAP, "build", "--carmen", "a.log", "--scale-from-gnss", "--out", scaled + "_x.f2m")
        self.assertEqual(result.returncode, 1)
        self.assertIn("--scale-from-gnss", result.stderr)
        silent = os.path.join(WORK, "occluders_no_gnss")
        self.assertEqual(run(SIM, "--world", "occluders", "--drive", "0", "--seed", "5", "--sensor", "vlp16",
                             "--duration", "5", "--out", silent).returncode, 0)
        result = run(MAP, "build", "--pcap", os.path.join(silent, "lidar.pcap"), "--can", os.path.join(silent, "can.log"),
                     "--dbc", os.path.join(silent, "vehicle.dbc"), "--odometry", SIM_ODOMETRY, "--scale-from-gnss",
                     "--out", scaled + "_x.f2m")
        self.assertEqual(result.returncode, 2)
        self.assertIn("GNSS fixes", result.stderr)

    def test_info_and_renders(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        result = run(MAP, "info", self.map, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        info = json.loads(result.stdout)
        for key in ("tiles", "mapped_area_m2", "file_bytes", "resolution_m", "georeference"):
            self.assertIn(key, info)
        self.assertEqual(info["file_bytes"], os.path.getsize(self.map))
        self.assertAlmostEqual(info["resolution_m"], 0.05)
        self.assertTrue(info["georeference"].startswith("ENU 48.0125"), info["georeference"])
        self.assertGreater(info["mapped_area_m2"], 500)  # the room is 57 x 30 m
        text = run(MAP, "info", self.map)
        self.assertIn("mapped area:", text.stdout)
        png = os.path.join(WORK, "occluders_region.png")
        result = run(MAP, "render", self.map, "--out", png, "--region", "0,0,10,10")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_bad_input(self):
        self.assertEqual(run(MAP, "build", "--out", os.path.join(WORK, "x.f2m")).returncode, 1)
        self.assertEqual(run(MAP, "build", "--carmen", "/nonexistent.log", "--out", os.path.join(WORK, "x.f2m")).returncode, 2)
        self.assertEqual(run(MAP, "info", "/nonexistent.f2m").returncode, 2)
        d = self.drive
        result = run(MAP, "build", "--pcap", os.path.join(d, "lidar.pcap"), "--can", os.path.join(d, "can.log"),
                     "--dbc", "/nonexistent.dbc", "--odometry", SIM_ODOMETRY, "--out", os.path.join(WORK, "x.f2m"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("nonexistent.dbc", result.stderr)
        self.assertEqual(run(MAP, "frobnicate").returncode, 1)
        self.assertEqual(run(MAP, "build", "--carmen", "a", "--out", "b", "--keyframe-distance", "x").returncode, 1)
        for scale in ("x", "0", "-1", "3"):
            result = run(MAP, "build", "--carmen", "a", "--out", "b", "--odometry-scale", scale)
            self.assertEqual(result.returncode, 1, scale)
            self.assertIn("--odometry-scale", result.stderr)
        damaged = os.path.join(WORK, "damaged.f2m")
        with open(damaged, "wb") as f:
            f.write(b"FLAT2DMP" + b"\x01\x00\x00\x00" + b"\xff\xff\x00\x00" + b"\x00" * 8)
        result = run(MAP, "info", damaged)
        self.assertEqual(result.returncode, 2)
        self.assertIn("header length", result.stderr)
        self.assertEqual(run(MAP, "render", self.map, "--out", os.path.join(WORK, "r.png"),
                             "--region", "1000,1000,1010,1010").returncode, 2)
        self.assertEqual(run(EVAL, "relations", "--trajectory", "/nonexistent.tum",
                             "--reference", "/nonexistent.tum").returncode, 2)
        self.assertEqual(run(EVAL, "relations", "--trajectory", "a.tum").returncode, 1)


class LaserLogMap(unittest.TestCase):
    def test_csail_log_with_noisy_odometry(self):
        log = os.path.join(DATA, "slam2d", "corrected_logs", "csail-corrected.log.gz")
        if not os.path.exists(log):
            self.skipTest(f"no 2D laser logs at {log} (set FLAT2D_DATA to the shared data folder)")
        out = os.path.join(WORK, "csail")
        scans = 60 if QUICK else 150
        result = run(MAP, "build", "--carmen", log, "--max-scans", str(scans), "--out", out + ".f2m",
                     "--trajectory", out + ".tum", "--reference-out", out + ".ref.tum",
                     "--odometry-out", out + ".odom.tum", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(json.loads(result.stdout)["scans"], scans)
        relations = os.path.join(WORK, "csail.relations")
        scores = {}
        for name in ("", ".odom"):
            result = run(EVAL, "relations", "--trajectory", out + name + ".tum", "--reference", out + ".ref.tum",
                         "--write-relations", relations, "--json")
            self.assertEqual(result.returncode, 0, result.stderr)
            scores[name] = json.loads(result.stdout)
        # The builder removes most of the noise it was given.
        if not QUICK:
            self.assertLess(scores[""]["translation_mean_m"], 0.05, scores)
            self.assertGreater(scores[".odom"]["translation_mean_m"], 3 * scores[""]["translation_mean_m"], scores)
        # The relations it wrote (6 decimals) read back in the Freiburg format and score the same.
        result = run(EVAL, "relations", "--trajectory", out + ".tum", "--relations", relations, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertAlmostEqual(json.loads(result.stdout)["translation_mean_m"], scores[""]["translation_mean_m"], 3)


TRAJ_3D_KEYS = {"ate_rmse_m", "ate_mean_m", "ate_median_m", "ate_max_m", "rpe_frame_trans_rmse_m",
                "rpe_frame_rot_rmse_deg", "rpe_frame_trans_median_m", "rpe_frame_rot_median_deg", "rpe_delta_s",
                "rpe_delta_trans_rmse_m", "rpe_delta_rot_rmse_deg", "rpe_delta_trans_median_m",
                "rpe_delta_rot_median_deg", "poses_matched", "pairs_frame", "pairs_delta"}


def write_helix(path, times_ns, turn=0.0, shift=(0.0, 0.0, 0.0)):
    """A climbing circle turning with its heading, moved by `turn` about z and by `shift`;
    the times in integer nanoseconds from fr1's epoch, printed exactly."""
    c, s = math.cos(turn), math.sin(turn)
    with open(path, "w") as f:
        f.write("# t x y z qx qy qz qw\n")
        for ns in times_ns:
            t = ns * 1e-9
            x, y, z = math.cos(0.5 * t), math.sin(0.5 * t), 0.1 * t
            yaw = 0.5 * t + turn
            f.write(f"{1305031225 + ns // 10**9}.{ns % 10**9:09d} {c * x - s * y + shift[0]:.9f} "
                    f"{s * x + c * y + shift[1]:.9f} {z + shift[2]:.9f} 0 0 {math.sin(yaw / 2):.12f} "
                    f"{math.cos(yaw / 2):.12f}\n")


def every(step_ns, count, start_ns=0):
    return [start_ns + i * step_ns for i in range(count)]


class Trajectory3d(unittest.TestCase):
    def traj(self, *args):
        result = run(EVAL, "traj", *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout

    def test_moved_estimate_at_its_own_rate(self):
        # Truth at 100 Hz for 4 s; the estimate at 30 Hz, 5 ms off the truth's times, turned
        # 90 degrees and 5 m away: interpolated and aligned, nothing is left but the chords.
        os.makedirs(WORK, exist_ok=True)
        truth, estimate = os.path.join(WORK, "helix_truth.tum"), os.path.join(WORK, "helix_est.tum")
        write_helix(truth, every(10**7, 400))
        write_helix(estimate, [5 * 10**6 + i * 10**9 // 30 for i in range(119)], turn=math.pi / 2,
                    shift=(5.0, -2.0, 1.0))
        e = json.loads(self.traj("--truth", truth, "--est", estimate, "--3d", "--json"))
        self.assertEqual(set(e), TRAJ_3D_KEYS)
        self.assertEqual(e["poses_matched"], 119)
        self.assertEqual(e["pairs_frame"], 118)
        self.assertEqual(e["pairs_delta"], 119 - 30)
        self.assertEqual(e["rpe_delta_s"], 1.0)
        self.assertLess(e["ate_rmse_m"], 1e-4, e)
        self.assertLessEqual(e["ate_median_m"], e["ate_max_m"])
        for key in ("rpe_frame_trans_rmse_m", "rpe_delta_trans_rmse_m"):
            self.assertLess(e[key], 1e-4, e)
        for key in ("rpe_frame_rot_rmse_deg", "rpe_delta_rot_rmse_deg"):
            self.assertLess(e[key], 1e-3, e)
        half = json.loads(self.traj("--truth", truth, "--est", estimate, "--3d", "--delta", "0.5", "--json"))
        self.assertEqual(half["rpe_delta_s"], 0.5)
        self.assertEqual(half["pairs_delta"], 119 - 15)
        text = self.traj("--truth", truth, "--est", estimate, "--3d")
        for line in ("poses: 119 matched", "ATE (SE(3)-aligned)", "RPE per frame (118 pairs)", "RPE over 1 s"):
            self.assertIn(line, text)
        # The planar evaluation of the same files is unchanged: it samples the estimate.
        planar = json.loads(self.traj("--truth", truth, "--est", estimate, "--align", "--json"))
        self.assertIn("heading_histogram", planar)
        self.assertNotIn("rpe_delta_s", planar)

    def test_tum_fr1_rpy_truth_10_ms_late(self):
        truth = os.path.join(DATA, "depth", "tum_rgbd_fr1_rpy_first200", "groundtruth.txt")
        if not os.path.exists(truth):
            self.skipTest(f"no TUM RGB-D truth at {truth} (set FLAT2D_DATA to the shared data folder)")
        same = json.loads(self.traj("--truth", truth, "--est", truth, "--3d", "--json"))
        self.assertEqual(same["poses_matched"], 2742)
        self.assertEqual(same["ate_max_m"], 0.0)
        self.assertEqual(same["rpe_frame_rot_rmse_deg"], 0.0)
        late = os.path.join(WORK, "fr1_rpy_late.tum")
        with open(truth) as f, open(late, "w") as out:
            for line in f:
                if not line.startswith("#"):
                    t, rest = line.split(" ", 1)
                    out.write(f"{float(t) + 0.01:.4f} {rest}")
        # The library test computes these figures independently (0.001043 m, 0.220053 deg).
        e = json.loads(self.traj("--truth", truth, "--est", late, "--3d", "--json"))
        self.assertEqual(e["poses_matched"], 2734)  # the last pose and 7 in the truth's gaps
        self.assertAlmostEqual(e["ate_rmse_m"], 0.001043, delta=2e-6)
        self.assertAlmostEqual(e["rpe_frame_rot_rmse_deg"], 0.220053, delta=2e-6)

    def test_bad_input(self):
        os.makedirs(WORK, exist_ok=True)
        truth, later = os.path.join(WORK, "bad_truth.tum"), os.path.join(WORK, "bad_later.tum")
        write_helix(truth, every(10**7, 100))
        write_helix(later, every(10**7, 100, start_ns=100 * 10**9))
        common = ["traj", "--truth", truth, "--est", truth]
        self.assertEqual(run(EVAL, *common, "--delta", "1").returncode, 1)  # --delta goes with --3d
        for bad in (["--delta", "0"], ["--delta", "nan"], ["--max-gap", "-1"], ["--plot", "x"], ["--no-align"]):
            self.assertEqual(run(EVAL, *common, "--3d", *bad).returncode, 1, bad)
        self.assertEqual(run(EVAL, "traj", "--truth", truth, "--est", "/nonexistent.tum", "--3d").returncode, 2)
        result = run(EVAL, "traj", "--truth", truth, "--est", later, "--3d")
        self.assertEqual(result.returncode, 2)
        self.assertIn("none of the estimate's 100 poses", result.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
