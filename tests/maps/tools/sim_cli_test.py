#!/usr/bin/env python3
"""flat2d-sim as users run it: the files, their determinism, the errors and exit statuses,
and the other tools reading what it wrote (flat2d-inspect the pcap, flat2d-can the CAN log).

usage: sim_cli_test.py FLAT2D_SIM FLAT2D_INSPECT FLAT2D_CAN SOURCE_DIR WORK_DIR
Needs no real data: the simulator is its own data source.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import unittest

SIM, INSPECT, CAN, SOURCE, WORK = sys.argv[1:6]
FILES = ["can.log", "lidar.pcap", "truth.tum", "truth_map.pgm", "truth_map.png", "truth_map.yaml",
         "vehicle.dbc"]
# A coarse truth map keeps the campus runs quick; the default 5 cm map is tested in C++.
COARSE = ["--map-resolution", "0.25"]


def run(*args, timeout=600):
    return subprocess.run([*args], capture_output=True, text=True, timeout=timeout)


def sim(*args):
    return run(SIM, *args)


def out_dir(name):
    path = os.path.join(WORK, "sim_cli_" + name)
    shutil.rmtree(path, ignore_errors=True)
    return path


def read(path):
    with open(path, "rb") as f:
        return f.read()


def truth_rows(directory):
    with open(os.path.join(directory, "truth.tum")) as f:
        return [[float(v) for v in line.split()] for line in f if line.strip()]


def yaw(row):
    qx, qy, qz, qw = row[4:8]
    return math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))


class SimCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # One short occluders run shared by the file tests.
        cls.first = out_dir("first")
        cls.args = ["--world", "occluders", "--drive", "0", "--seed", "3", "--duration", "2",
                    "--sensor", "vlp16"]
        result = sim(*cls.args, "--out", cls.first, "--json")
        assert result.returncode == 0, result.stderr
        cls.summary = json.loads(result.stdout)

    def test_writes_every_file_and_a_json_summary(self):
        for name in FILES:
            path = os.path.join(self.first, name)
            self.assertTrue(os.path.isfile(path), name)
            self.assertGreater(os.path.getsize(path), 0, name)
        self.assertEqual(sorted(self.summary["files"]), FILES)
        for key in ("data_packets", "position_packets", "can_frames", "truth_poses", "simulated_s",
                    "wall_s", "real_time_factor"):
            self.assertIn(key, self.summary)
        self.assertEqual(self.summary["world"], "occluders")
        self.assertEqual(self.summary["sensor"], "VLP-16")
        self.assertEqual(self.summary["simulated_s"], 2)
        # 200 Hz truth over [0, 2] s, both ends included; a VLP-16 packet every 1.327 ms.
        self.assertEqual(self.summary["truth_poses"], 401)
        self.assertEqual(len(truth_rows(self.first)), 401)
        self.assertAlmostEqual(self.summary["data_packets"], 2 / 1.327e-3, delta=3)
        with open(os.path.join(self.first, "truth_map.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        with open(os.path.join(self.first, "truth_map.yaml")) as f:
            self.assertIn("truth_map.pgm", f.read())

    def test_same_arguments_give_identical_bytes(self):
        second = out_dir("second")
        result = sim(*self.args, "--out", second)
        self.assertEqual(result.returncode, 0, result.stderr)
        for name in FILES:
            self.assertEqual(read(os.path.join(self.first, name)), read(os.path.join(second, name)),
                             name + " differs between equal runs")

    def test_another_seed_changes_the_sensors_not_the_truth(self):
        other = out_dir("other_seed")
        args = list(self.args)
        args[args.index("--seed") + 1] = "4"
        result = sim(*args, "--out", other)
        self.assertEqual(result.returncode, 0, result.stderr)
        for name in ("lidar.pcap", "can.log"):
            self.assertNotEqual(read(os.path.join(self.first, name)), read(os.path.join(other, name)), name)
        self.assertEqual(read(os.path.join(self.first, "truth.tum")), read(os.path.join(other, "truth.tum")))

    def test_inspect_summarizes_the_pcap(self):
        result = run(INSPECT, "--json", os.path.join(self.first, "lidar.pcap"))
        self.assertEqual(result.returncode, 0, result.stderr)
        summary = json.loads(result.stdout)
        self.assertEqual(summary["product"], "VLP-16")
        self.assertEqual(summary["return_mode"], "strongest")
        self.assertEqual(summary["data_packets"], self.summary["data_packets"])
        self.assertEqual(summary["position_packets"], self.summary["position_packets"])
        self.assertEqual(summary["malformed"], 0)
        self.assertEqual(summary["lost_packets"], 0)
        self.assertTrue(18 <= summary["revolutions"] <= 20, summary["revolutions"])  # 2 s at 10 Hz

    def test_other_sensors_and_rotation_rates(self):
        for sensor, product, rotation in (("hdl32e", "HDL-32E", "5"), ("vlp32c", "VLP-32C", "20")):
            directory = out_dir(sensor)
            result = sim("--world", "ramps", "--duration", "0.5", "--sensor", sensor,
                         "--rotation-hz", rotation, "--out", directory, *COARSE, "--json")
            self.assertEqual(result.returncode, 0, result.stderr)
            inspected = json.loads(run(INSPECT, "--json", os.path.join(directory, "lidar.pcap")).stdout)
            self.assertEqual(inspected["product"], product)
            self.assertEqual(inspected["malformed"], 0)
            self.assertEqual(inspected["data_packets"], json.loads(result.stdout)["data_packets"])

    def test_can_dead_reckons_the_can_log_along_the_truth(self):
        directory = out_dir("campus")
        result = sim("--world", "campus", "--drive", "0", "--duration", "8", "--sensor", "vlp16",
                     "--odometry-noise", "mems", "--out", directory, *COARSE)
        self.assertEqual(result.returncode, 0, result.stderr)
        config = os.path.join(SOURCE, "packaging", "config", "odometry", "flat2d_sim.textproto")
        odom = run(CAN, "odom", "--dbc", os.path.join(directory, "vehicle.dbc"), "--config", config,
                   os.path.join(directory, "can.log"), "--tum", os.path.join(directory, "odom.tum"),
                   "--json")
        self.assertEqual(odom.returncode, 0, odom.stderr)
        summary = json.loads(odom.stdout)
        self.assertEqual(summary["malformed_lines"], 0)
        self.assertEqual(summary["checksum_failures"], 0)
        truth = truth_rows(directory)
        travelled = sum(math.dist(a[1:3], b[1:3]) for a, b in zip(truth, truth[1:]))
        self.assertGreater(travelled, 10)
        # MEMS wheel scale errors are a few per mille: 2% of the distance is generous.
        self.assertAlmostEqual(summary["distance_m"], travelled, delta=0.02 * travelled + 0.1)
        # Heading change: the gyro's bias over 8 s is far below 0.02 rad.
        turned = math.remainder(yaw(truth[-1]) - yaw(truth[0]), 2 * math.pi)
        self.assertAlmostEqual(summary["final_pose"]["theta"], turned, delta=0.02)

    def test_a_world_file(self):
        world = os.path.join(WORK, "sim_cli_world.textproto")
        with open(world, "w") as f:
            f.write('name: "strip"\n'
                    'walls { points { x: -5 y: -8 } points { x: 40 y: -8 } thickness_m: 0.3 height_m: 3 }\n'
                    'boxes { center { x: 15 y: 5 } length_m: 3 width_m: 2 height_m: 1.5 }\n'
                    'drives { name: "straight" waypoints { x: 0 y: 0 } waypoints { x: 30 y: 0 }\n'
                    '         speed_mps: 4 corner_radius_m: 3 }\n')
        directory = out_dir("world_file")
        result = sim("--world", world, "--duration", "1", "--sensor", "vlp16", "--out", directory, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(json.loads(result.stdout)["world"], "strip")
        broken = os.path.join(WORK, "sim_cli_broken.textproto")
        with open(broken, "w") as f:
            f.write('name: "x"\nno_such_field: 1\n')
        result = sim("--world", broken, "--out", out_dir("broken"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("no_such_field", result.stderr)

    def test_list_names_the_worlds_and_their_drives(self):
        result = sim("--list", "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        worlds = {w["name"]: w for w in json.loads(result.stdout)["worlds"]}
        self.assertEqual(set(worlds), {"office", "campus", "ramps", "occluders"})
        for world in worlds.values():
            self.assertGreaterEqual(len(world["drives"]), 3, world["name"])
            self.assertEqual(world["drives"][0]["name"], "mapping")
            for drive in world["drives"]:
                self.assertGreater(drive["length_m"], 0)
        self.assertGreater(worlds["campus"]["drives"][0]["length_m"], 1000)  # issue 5: >= 1 km loop

    def test_bad_arguments_are_usage_errors(self):
        out = out_dir("bad")
        cases = [
            (["--world", "atlantis", "--out", out], "campus"),             # lists the worlds
            (["--world", "campus", "--drive", "99", "--out", out], "3 drives"),
            (["--sensor", "hdl64e", "--out", out], "hdl64e"),
            (["--duration", "soon", "--out", out], "--duration"),
            (["--duration", "-1", "--out", out], "--duration"),
            (["--odometry-noise", "perfect", "--out", out], "perfect"),
            (["--rotation-hz", "50", "--out", out], "rotation"),
            (["--udp", "not-an-address"], "--udp"),
            (["--no-such-flag"], "--no-such-flag"),
            ([], "nothing to do"),
        ]
        for args, named in cases:
            result = sim(*args)
            self.assertEqual(result.returncode, 2, (args, result.stderr))
            self.assertIn(named, result.stderr, args)
        blocker = os.path.join(WORK, "sim_cli_blocker")
        with open(blocker, "w") as f:
            f.write("a file, not a directory")
        result = sim("--world", "occluders", "--duration", "0.2", "--out", os.path.join(blocker, "out"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("sim_cli_blocker", result.stderr)
        self.assertEqual(sim("--help").returncode, 0)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]])
