#!/usr/bin/env python3
"""flat2d-map build --mode nicp DRIVE as users call it: a short simulated drive tracked by NICP
revolution to merged model (and to keyframe) with CAN odometry guesses, its files (TUM trajectory, PLY model,
prior map, preview), its trajectory against the simulator's truth, and exit statuses on bad
input; then a KITTI sequence directory (the real KITTI 00 excerpt) tracked the same way.

usage: nicp_drive_cli_test.py FLAT2D_MAP FLAT2D_EVAL FLAT2D_SIM SOURCE_DIR DATA_DIR WORK_DIR [quick]
The simulated drive needs no shared data; the KITTI test skips without it ($FLAT2D_DATA
overrides DATA_DIR). "quick" (the sanitizer build) tracks the first 20 revolutions of the
simulated drive and checks the files, not the accuracy.
"""
import json
import math
import os
import subprocess
import sys
import unittest

MAP, EVAL, SIM, SOURCE, DATA, WORK = sys.argv[1:7]
DATA = os.environ.get("FLAT2D_DATA") or DATA
QUICK = len(sys.argv) > 7 and sys.argv[7] == "quick"
KITTI = os.path.join(DATA, "lidar3d", "kitti_odometry_00_frames_000000-000015")
SIM_ODOMETRY = os.path.join(SOURCE, "packaging", "config", "odometry", "flat2d_sim.textproto")
# The first 8 s of the office mapping drive (VLP-16, seed 3, 7.9 m in a corridor), measured
# against the merged model ATE 0.020 m, RPE per revolution 0.005 m and 0.048 deg, drift
# 0.13 % of the distance (keyframes: 0.020 m, 0.013 m, 0.040 deg, 0.086 %; the
# CAN odometry's open loop: 0.49 %); the bounds leave a margin of 2.5x and more.
ATE_RMSE_M = 0.08
DRIFT_PERCENT = 0.5
RPE_ROT_DEG = 0.1


def run(tool, *args):
    return subprocess.run([tool, *args], capture_output=True, text=True, timeout=600)


_OFFICE = []


def office_drive():
    """The simulated drive both test classes use, made once: its folder and CAN arguments."""
    if not _OFFICE:
        os.makedirs(WORK, exist_ok=True)
        drive = os.path.join(WORK, "office")
        result = run(SIM, "--world", "office", "--drive", "0", "--seed", "3", "--sensor", "vlp16",
                     "--duration", "8", "--out", drive)
        assert result.returncode == 0, result.stderr
        can = ["--can", os.path.join(drive, "can.log"), "--dbc", os.path.join(drive, "vehicle.dbc"),
               "--odometry", SIM_ODOMETRY]
        _OFFICE.append((drive, can))
    return _OFFICE[0]


class NicpDrive(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.drive, cls.can = office_drive()
        d = cls.drive
        cls.out = os.path.join(WORK, "office_nicp")
        frames = ["--max-frames", "20"] if QUICK else []
        cls.build = run(MAP, "build", "--mode", "nicp", os.path.join(d, "lidar.pcap"), *cls.can,
                        "--anchor", os.path.join(d, "truth.tum"), *frames, "--out", cls.out, "--json")

    def test_summary_and_files(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        s = json.loads(self.build.stdout)
        for key in ("frames", "failures", "frame_ms_p50", "frame_ms_p95", "registration_ms_p50", "load_ms_p50",
                    "model_points", "method", "sensor", "guess", "tracking", "drift_percent",
                    "odometry_drift_percent"):
            self.assertIn(key, s)
        self.assertEqual(s["sensor"], "vlp16")
        self.assertEqual(s["guess"], "can")
        self.assertEqual(s["tracking"], "model")
        self.assertGreaterEqual(s["frames"], 20 if QUICK else 75)  # 10 Hz
        self.assertEqual(s["failures"], 0)
        with open(os.path.join(self.out, "trajectory.tum")) as f:
            lines = [l for l in f if not l.startswith("#")]
        self.assertEqual(len(lines), s["frames"])
        for name in ("odometry.tum", "model.ply", "map.f2m", "map.png"):
            self.assertGreater(os.path.getsize(os.path.join(self.out, name)), 100, name)
        info = json.loads(run(MAP, "info", os.path.join(self.out, "map.f2m"), "--json").stdout)
        self.assertGreater(info["mapped_area_m2"], 50)

    def test_trajectory_against_the_truth(self):
        self.assertEqual(self.build.returncode, 0, self.build.stderr)
        result = run(EVAL, "traj", "--3d", "--truth", os.path.join(self.drive, "truth.tum"),
                     "--est", os.path.join(self.out, "trajectory.tum"), "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        e = json.loads(result.stdout)
        s = json.loads(self.build.stdout)
        print(f"ATE {e['ate_rmse_m']:.4f} m, RPE per frame {e['rpe_frame_trans_rmse_m']:.4f} m "
              f"{e['rpe_frame_rot_rmse_deg']:.4f} deg, drift {s['drift_percent']:.3f} % "
              f"(odometry {s['odometry_drift_percent']:.3f} %) over {s['distance_m']:.2f} m", file=sys.stderr)
        if QUICK:
            return
        self.assertLess(e["ate_rmse_m"], ATE_RMSE_M, e)
        self.assertLess(e["rpe_frame_rot_rmse_deg"], RPE_ROT_DEG, e)
        self.assertLess(s["drift_percent"], DRIFT_PERCENT, s)
        self.assertGreater(s["distance_m"], 7.5)

    def test_keyframes(self):
        # The same drive against keyframe revolutions: measured ATE 0.020 m and drift 0.087 %
        # (the merged model: 0.020 m, 0.13 %); the same bounds.
        out = os.path.join(WORK, "office_keyframes")
        frames = ["--max-frames", "10"] if QUICK else []
        result = run(MAP, "build", "--mode", "nicp", os.path.join(self.drive, "lidar.pcap"), *self.can,
                     "--anchor", os.path.join(self.drive, "truth.tum"), "--tracking", "keyframe", "--no-map", *frames,
                     "--out", out, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        s = json.loads(result.stdout)
        self.assertEqual((s["tracking"], s["failures"]), ("keyframe", 0))
        if QUICK:
            return
        e = json.loads(run(EVAL, "traj", "--3d", "--truth", os.path.join(self.drive, "truth.tum"),
                           "--est", os.path.join(out, "trajectory.tum"), "--json").stdout)
        print(f"keyframes: ATE {e['ate_rmse_m']:.4f} m, drift {s['drift_percent']:.3f} %", file=sys.stderr)
        self.assertLess(e["ate_rmse_m"], ATE_RMSE_M, e)
        self.assertLess(s["drift_percent"], DRIFT_PERCENT, s)
        self.assertEqual(run(MAP, "build", "--mode", "nicp", os.path.join(self.drive, "lidar.pcap"), "--tracking",
                             "sideways", "--out", out).returncode, 1)

    def test_without_odometry(self):
        # Constant velocity guesses and deskewing, no map: the trajectory alone.
        out = os.path.join(WORK, "office_cv")
        result = run(MAP, "build", "--mode", "nicp", os.path.join(self.drive, "lidar.pcap"), "--max-frames", "15",
                     "--no-map", "--out", out, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        s = json.loads(result.stdout)
        self.assertEqual(s["guess"], "constant-velocity")
        self.assertEqual(s["frames"], 15)
        self.assertTrue(os.path.exists(os.path.join(out, "trajectory.tum")))
        self.assertFalse(os.path.exists(os.path.join(out, "map.f2m")))
        self.assertFalse(os.path.exists(os.path.join(out, "odometry.tum")))

    def test_bad_input(self):
        d, out = self.drive, os.path.join(WORK, "bad")
        pcap = os.path.join(d, "lidar.pcap")
        # A capture that is missing or garbled: status 2, naming the file.
        result = run(MAP, "build", "--mode", "nicp", "/nonexistent/drive.pcap", "--out", out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("/nonexistent/drive.pcap", result.stderr)
        garbled = os.path.join(WORK, "garbled.pcap")
        with open(garbled, "wb") as f:
            f.write(b"not a capture at all" * 10)
        result = run(MAP, "build", "--mode", "nicp", garbled, "--out", out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("garbled.pcap", result.stderr)
        # CAN log without its DBC and odometry: usage, 1.
        result = run(MAP, "build", "--mode", "nicp", pcap, "--can", os.path.join(d, "can.log"), "--out", out)
        self.assertEqual(result.returncode, 1)
        self.assertIn("--dbc", result.stderr)
        # A DBC that is not there: 2, naming it.
        result = run(MAP, "build", "--mode", "nicp", pcap, "--can", os.path.join(d, "can.log"),
                     "--dbc", "/nonexistent.dbc", "--odometry", SIM_ODOMETRY, "--out", out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("nonexistent.dbc", result.stderr)
        self.assertEqual(run(MAP, "build", "--mode", "nicp", pcap).returncode, 1)  # no --out
        self.assertEqual(run(MAP, "build", "--mode", "nicp", pcap, "--out", out, "--max-frames", "0").returncode, 1)
        self.assertEqual(run(MAP, "build", "--mode", "nicp", pcap, "--out", out, "--method", "x").returncode, 1)
        self.assertEqual(run(MAP, "build", "--mode", "nicp", pcap, "--out", out, "--frobnicate").returncode, 1)


def sensor_poses(path):
    """The 4x4 world_T_sensor of each line of a TUM file, as nested lists."""
    poses = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            x, y, z, qx, qy, qz, qw = (float(v) for v in line.split()[1:8])
            poses.append([[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw), x],
                          [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw), y],
                          [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy), z],
                          [0.0, 0.0, 0.0, 1.0]])
    return poses


def relative(a, b):
    """inv(a) b for rigid 4x4s."""
    r = [[a[j][i] for j in range(3)] for i in range(3)]
    t = [b[i][3] - a[i][3] for i in range(3)]
    rb = [[sum(r[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return [rb[i] + [sum(r[i][k] * t[k] for k in range(3))] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


class Export(unittest.TestCase):
    """flat2d-map export: revolutions as PCD with the truth's sensor poses, which a
    registration of two of them must reproduce (scripts/eval-register's simulated set)."""

    @classmethod
    def setUpClass(cls):
        cls.drive, cls.can = office_drive()
        cls.out = os.path.join(WORK, "office_export")
        cls.result = run(MAP, "export", os.path.join(cls.drive, "lidar.pcap"), *cls.can, "--truth",
                         os.path.join(cls.drive, "truth.tum"), "--every", "20", "--with-next", "--max-frames", "45",
                         "--out", cls.out, "--json")

    def test_files_and_poses(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        s = json.loads(self.result.stdout)
        self.assertEqual((s["revolutions"], s["written"], s["sensor"], s["poses"]), (45, 6, "VLP-16", "truth"))
        names = sorted(n for n in os.listdir(self.out) if n.endswith(".pcd"))
        self.assertEqual(names, ["revolution_%06d.pcd" % k for k in (0, 1, 20, 21, 40, 41)])
        poses = sensor_poses(os.path.join(self.out, "sensor_poses.tum"))
        self.assertEqual(len(poses), 6)
        # The simulator's office drive is level: the sensor stays at its mounting height.
        for pose in poses:
            self.assertAlmostEqual(pose[2][3], poses[0][2][3], delta=1e-6)
            self.assertAlmostEqual(pose[2][2], 1.0, delta=1e-9)

    def test_a_registered_pair_lands_on_the_truth(self):
        # Revolutions 20 and 21 of the office drive (0.107 m apart): measured 3.4 mm and
        # 0.12 deg from the truth (a VLP-16 in a corridor); 1 cm / 0.3 deg bound it, where a
        # pose one revolution off or a deskew the wrong way round would be 0.1 m out.
        # Deskewed points leave their lasers' cones, so the sensor is named (auto-detection
        # takes them as unorganized).
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        poses = sensor_poses(os.path.join(self.out, "sensor_poses.tum"))
        truth = relative(poses[2], poses[3])
        result = run(MAP, "register", os.path.join(self.out, "revolution_000021.pcd"),
                     os.path.join(self.out, "revolution_000020.pcd"), "--sensor", "vlp16", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        estimate = json.loads(result.stdout)["target_T_source"]
        error = relative(truth, estimate)
        distance = sum(error[i][3] ** 2 for i in range(3)) ** 0.5
        angle = math.degrees(math.acos(max(-1.0, min(1.0, (error[0][0] + error[1][1] + error[2][2] - 1) / 2))))
        print(f"export: pair 20-21 {1000 * distance:.2f} mm {angle:.4f} deg from the truth "
              f"({truth[0][3]:.3f} m apart)", file=sys.stderr)
        self.assertGreater(sum(truth[i][3] ** 2 for i in range(3)) ** 0.5, 0.05)
        self.assertLess(distance, 0.01)
        self.assertLess(angle, 0.3)

    def test_bad_input(self):
        pcap, out = os.path.join(self.drive, "lidar.pcap"), os.path.join(WORK, "export_bad")
        result = run(MAP, "export", pcap, "--out", out)  # deskewing needs the CAN odometry
        self.assertEqual(result.returncode, 1)
        self.assertIn("--can", result.stderr)
        result = run(MAP, "export", pcap, *self.can, "--truth", "/nonexistent/truth.tum", "--out", out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("/nonexistent/truth.tum", result.stderr)
        self.assertEqual(run(MAP, "export", pcap, *self.can, "--out", out, "--every", "0").returncode, 1)
        self.assertEqual(run(MAP, "export", pcap, *self.can).returncode, 1)  # no --out


class KittiSequence(unittest.TestCase):
    def test_scans_tracked_with_the_sequence_truth(self):
        if not os.path.isdir(KITTI):
            self.skipTest("real data not found: " + KITTI + " (set FLAT2D_DATA to the shared data folder)")
        out = os.path.join(WORK, "kitti_nicp")
        result = run(MAP, "build", "--mode", "nicp", KITTI, "--config",
                     os.path.join(SOURCE, "packaging", "config", "grid", "kitti_hdl64.textproto"), "--out", out, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        s = json.loads(result.stdout)
        self.assertEqual((s["sensor"], s["frames"], s["failures"]), ("kitti64", 16, 0))
        self.assertEqual((s["deskew"], s["guess"], s["viewpoints"]), (False, "constant-velocity", 0))
        self.assertAlmostEqual(s["tracked_distance_m"], 11.67, delta=0.25)  # lidar3d/README.md's ICP steps
        for name in ("trajectory.tum", "truth.tum"):
            with open(os.path.join(out, name)) as f:
                self.assertEqual(len([l for l in f if not l.startswith("#")]), 16, name)
        self.assertGreater(os.path.getsize(os.path.join(out, "model.ply")), 1000)
        self.assertFalse(os.path.exists(os.path.join(out, "map.f2m")))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
