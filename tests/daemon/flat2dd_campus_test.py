#!/usr/bin/env python3
"""flat2dd on the simulated campus, end to end, as on the vehicle: the campus mapping drive
built into a prior map; flat2dd started with a UDP LiDAR source on loopback and the
localization drive's candump log; that drive's capture replayed to loopback at twice real
time by `flat2d-inspect replay`, with a 5 s LiDAR outage in it; a `flat2d watch` subscriber
judged against the simulator's truth. On the way: a flood of malformed packets and API
requests, the outage (DEGRADED with a growing covariance, then LOCALIZED again), and a
kill -9 mid-drive with its warm start.

usage: flat2dd_campus_test.py FLAT2DD FLAT2D FLAT2D_SIM FLAT2D_MAP FLAT2D_INSPECT SOURCE_DIR WORK_DIR
"""
import math
import os
import socket
import subprocess
import sys
import time
import unittest

sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from flat2dd_harness import (RUNNING, Daemon, Tools, Truth, Watcher, build_map, calibrated_odometry, configure, errors,  # noqa: E402
                             finish_drive, flood, free_port, kill_and_warm_start, kill_running, percentile, run,
                             write_config)

FLAT2DD, FLAT2D, SIM, MAP, INSPECT, SOURCE, WORK = sys.argv[1:8]
configure(Tools(FLAT2DD, FLAT2D, SIM, MAP, INSPECT, SOURCE))

# The events fall where the drive itself is localizable: offline (`flat2d-localize` on this
# drive and map) tracking rejects matches at 29.4-30.2 s (DEGRADED on a slow revolution),
# 94.4-99.3 s and 115.7-120.6 s (open road, DEGRADED). A flood or a warm start there would
# be judged on the road, not on the service.
SPEED = 2            # the replay's rate; the daemon keeps up on one core (see docs/benchmarks.md)
OUTAGE_FROM_S = 60   # capture seconds: the LiDAR is silent from here ...
OUTAGE_S = 5         # ... for this long, while the CAN log runs on
FLOOD_AT_S = 20      # capture seconds: malformed datagrams and requests
KILL_AT_S = 80       # capture seconds: kill -9, then a warm start

# Accuracy on the campus (the localizer's targets, DESIGN.md): heading within 0.02 rad for
# 99 % of LOCALIZED poses. Position: with its scale from the survey GNSS the campus map is
# 0.04 m ATE from the truth (docs/benchmarks.md, prior maps); through the daemon, with the
# odometry that mapping drive calibrated, this drive measured p95 0.068 m (2026-12-04; 0.104 m
# with the uncalibrated odometry). The margin is for the replay's timing on a loaded
# machine: p95 <= 0.20 m, the lateral target.
HEADING_RAD = 0.02
HEADING_SHARE = 0.99
POSITION_P95_M = 0.20


def sigma_m(pose):
    c = pose.get("covariance", [])
    return math.sqrt(c[0] + c[4]) if len(c) >= 5 else 0.0


class CampusEndToEnd(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        cls.mapping = os.path.join(WORK, "campus_mapping")
        cls.drive = os.path.join(WORK, "campus_drive1")
        # The mapping vehicle carries a survey GNSS receiver, which sets the map's scale.
        for out, drive, seed, extra in ((cls.mapping, "0", "1", ["--gnss-rtk"]), (cls.drive, "1", "2", ["--gnss"])):
            if not os.path.exists(os.path.join(out, "truth.tum")):
                result = run(SIM, "--world", "campus", "--drive", drive, "--seed", seed, "--sensor", "hdl32e",
                             *extra, "--out", out)
                assert result.returncode == 0, result.stderr
        cls.map = os.path.join(WORK, "campus.f2m")
        if not os.path.exists(calibrated_odometry(cls.map)):
            build_map(cls.mapping, cls.map, timeout=900, scale_from_gnss=True)
        cls.truth = Truth(os.path.join(cls.drive, "truth.tum"))

    def tearDown(self):
        kill_running()

    def wait_capture_time(self, replay_started, capture_s):
        """Sleeps until the replay reaches capture_s into the drive."""
        delay = replay_started + capture_s / SPEED - time.monotonic()
        if delay > 0:
            time.sleep(delay)

    def test_campus_drive_over_udp(self):
        name = "campus"
        config, sock, pose_file = (os.path.join(WORK, name + ext) for ext in (".textproto", ".sock", ".pose.textproto"))
        for p in (sock, pose_file, config + ".log"):
            if os.path.exists(p):
                os.remove(p)
        port = free_port(socket.SOCK_DGRAM)
        start = self.truth.at(self.truth.t[1])
        write_config(config, 'lidar { udp { bind_address: "127.0.0.1" port: %d position_port: %d } }' % (port, port),
                     'can { candump { path: "%s" } }' % os.path.join(self.drive, "can.log"),
                     self.drive, self.map, sock, pose_file, initial=start, odometry=calibrated_odometry(self.map))
        daemon = Daemon(config, sock)
        daemon.wait_ready()
        watcher = Watcher(sock)
        replay = subprocess.Popen([INSPECT, "replay", "--to", "127.0.0.1:%d" % port, "--speed", str(SPEED),
                                   "--outage", "%d:%d" % (OUTAGE_FROM_S, OUTAGE_S),
                                   os.path.join(self.drive, "lidar.pcap")],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        replay_started = time.monotonic()
        RUNNING.append(replay)
        self.assertTrue(daemon.wait_state("LOCALIZED", 5), "not LOCALIZED within 5 s of the replay")
        localized_s = time.monotonic() - replay_started

        # The flood: counted, the state and the poses unaffected.
        self.wait_capture_time(replay_started, FLOOD_AT_S)
        flood(self, daemon, port, sock)

        # The outage: the state through it, as the subscriber saw it.
        self.wait_capture_time(replay_started, OUTAGE_FROM_S + OUTAGE_S + 3)
        self.assertEqual(daemon.status()["state"], "LOCALIZED", "not LOCALIZED 3 s after the outage")

        # kill -9 mid-drive, then a warm start from the persisted pose.
        self.wait_capture_time(replay_started, KILL_AT_S)
        restarted, relocalized_s = kill_and_warm_start(self, daemon, config, sock)
        final = finish_drive(self, replay, restarted, watcher, config, timeout=300)

        self.check_outage([p for _, p in watcher.poses])
        judged = errors(watcher.poses, self.truth)
        position = [e for e, _ in judged]
        heading_ok = sum(1 for _, h in judged if h <= HEADING_RAD) / max(1, len(judged))
        duration = self.truth.t[-1] - self.truth.t[0]
        print("campus udp x%d: LOCALIZED %.2f s after the replay began; warm start LOCALIZED after %.2f s; "
              "%d LOCALIZED poses, position p50 %.3f m p95 %.3f m, heading within %.2f rad %.1f %%, worst %.4f rad; "
              "lidar received %s dropped %s malformed %s" %
              (SPEED, localized_s, relocalized_s, len(judged), percentile(position, 0.5),
               percentile(position, 0.95), HEADING_RAD, 100 * heading_ok, max(h for _, h in judged),
               final["lidar"]["received"], final["lidar"]["dropped"], final["lidar"]["malformed"]))
        self.assertGreater(len(judged), 0.7 * 20 * duration / SPEED)  # 20 Hz, most of the drive LOCALIZED
        self.assertLessEqual(percentile(position, 0.95), POSITION_P95_M)
        self.assertGreaterEqual(heading_ok, HEADING_SHARE)

    def check_outage(self, poses):
        """DEGRADED through the outage with a growing covariance, LOCALIZED within 2 s after it."""
        t0 = self.truth.t[0]
        outage_from, outage_to = t0 + OUTAGE_FROM_S, t0 + OUTAGE_FROM_S + OUTAGE_S
        inside = [p for p in poses if outage_from + 1.0 <= int(p["time_ns"]) * 1e-9 < outage_to]
        self.assertGreater(len(inside), 10, "no poses through the outage: the CAN log stopped with the LiDAR")
        states = {p["state"] for p in inside}
        self.assertEqual(states, {"DEGRADED"}, "states through the outage: %s" % [
            (round(int(p["time_ns"]) * 1e-9 - outage_from, 2), p["state"], round(sigma_m(p), 3),
             round(p.get("since_accepted_match_s", 0), 2)) for p in inside[::5]])
        sigmas = [sigma_m(p) for p in inside]
        self.assertGreater(sigmas[-1], 1.5 * sigmas[0], "the covariance did not grow: %s" % sigmas[::10])
        back = [int(p["time_ns"]) * 1e-9 - outage_to for p in poses
                if int(p["time_ns"]) * 1e-9 >= outage_to and p["state"] == "LOCALIZED"]
        self.assertTrue(back and back[0] < 2.0, "not LOCALIZED within 2 s of the LiDAR's return")
        print("campus outage: %d poses DEGRADED, sigma %.3f m -> %.3f m; LOCALIZED %.2f s after the LiDAR returned" %
              (len(inside), sigmas[0], sigmas[-1], back[0]))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
