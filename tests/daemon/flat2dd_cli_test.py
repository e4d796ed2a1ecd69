#!/usr/bin/env python3
"""flat2dd end to end, as a vehicle integrator runs it: a simulated world's mapping drive
built into a prior map, the daemon started on another drive of the world, poses read by the
`flat2d` client and judged against the simulator's truth. Covers the pcap replay source, the
live UDP source (the capture sent to loopback by flat2d-inspect replay) with the candump log
following the LiDAR's clock, malformed API requests and packets, SIGHUP reload with a
subscriber connected, kill -9 and a warm start, SIGTERM, and bad configurations.

usage: flat2dd_cli_test.py FLAT2DD FLAT2D FLAT2D_SIM FLAT2D_MAP FLAT2D_INSPECT SOURCE_DIR WORK_DIR [quick]
"quick" (the sanitizer build) runs a 12 s drive through the pcap source at real time and
checks the service's behaviour, not the accuracy, which the release build checks.
"""
import json
import os
import signal
import socket
import subprocess
import sys
import time
import unittest

sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from flat2dd_harness import (RUNNING, Daemon, Tools, Truth, Watcher, accuracy, build_map, configure,  # noqa: E402
                             finish_drive, flood, free_port, kill_and_warm_start, kill_running, percentile, run,
                             write_config)

FLAT2DD, FLAT2D, SIM, MAP, INSPECT, SOURCE, WORK = sys.argv[1:8]
QUICK = len(sys.argv) > 8 and sys.argv[8] == "quick"
configure(Tools(FLAT2DD, FLAT2D, SIM, MAP, INSPECT, SOURCE))


class DaemonEndToEnd(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        cls.mapping = os.path.join(WORK, "mapping")
        cls.drive = os.path.join(WORK, "drive2")
        drive_extra = ["--duration", "12"] if QUICK else []
        mapping_extra = ["--duration", "30"] if QUICK else []
        for out, drive, seed, extra in ((cls.mapping, "0", "5", mapping_extra),
                                        (cls.drive, "2", "6", ["--gnss"] + drive_extra)):
            result = run(SIM, "--world", "occluders", "--drive", drive, "--seed", seed, "--sensor", "vlp16",
                         *extra, "--out", out)
            assert result.returncode == 0, result.stderr
        cls.map = os.path.join(WORK, "occluders.f2m")
        build_map(cls.mapping, cls.map)
        cls.truth = Truth(os.path.join(cls.drive, "truth.tum"))
        cls.start = (cls.truth.x[0], cls.truth.y[0], 0.0)

    def tearDown(self):
        kill_running()

    def paths(self, name):
        sock = os.path.join(WORK, name + ".sock")
        pose_file = os.path.join(WORK, name + ".pose.textproto")
        for p in (sock, pose_file):
            if os.path.exists(p):
                os.remove(p)
        return os.path.join(WORK, name + ".textproto"), sock, pose_file

    def test_pcap_replay_serves_poses_within_the_targets(self):
        config, sock, pose_file = self.paths("pcap")
        rate = 1 if QUICK else 4
        write_config(config, 'lidar { pcap { path: "%s" rate: %g } }' % (os.path.join(self.drive, "lidar.pcap"), rate),
                     'can { candump { path: "%s" } }' % os.path.join(self.drive, "can.log"),
                     self.drive, self.map, sock, pose_file, initial=self.start)
        daemon = Daemon(config, sock)
        daemon.wait_ready()
        ready_s = time.monotonic() - daemon.started
        watcher = Watcher(sock)
        duration = (self.truth.t[-1] - self.truth.t[0]) / rate
        time.sleep(duration + 1.0)
        status = daemon.status()
        at = run(FLAT2D, "--socket", sock, "--json", "pose", "--at", str(int(self.truth.t[-1] * 1e9) - 2 * 10**9))
        early = run(FLAT2D, "--socket", sock, "pose", "--at", str(int(self.truth.t[0] * 1e9) - 60 * 10**9))
        self.assertEqual(watcher.stop(), -signal.SIGTERM)
        code, stop_s = daemon.stop()
        self.assertEqual(code, 0)
        self.assertLess(stop_s, 1.0)
        print("pcap x%g: ready after %.2f s, %d poses, stop %.3f s" % (rate, ready_s, len(watcher.poses), stop_s))

        self.assertGreater(int(status["lidar"]["received"]), 1000)
        self.assertGreater(int(status["can"]["received"]), 1000)
        if not QUICK:  # a sanitizer build need not keep up with real time
            self.assertEqual(status["state"], "LOCALIZED")
            self.assertGreater(int(status["revolutions"]), (self.truth.t[-1] - self.truth.t[0]) * 9)
            self.assertEqual(int(status["lidar"]["dropped"]), 0)
        self.assertEqual(at.returncode, 0, at.stderr)
        self.assertTrue(json.loads(at.stdout)["valid"])
        self.assertEqual(early.returncode, 1)
        self.assertIn("OUT_OF_WINDOW", early.stderr)
        self.assertTrue(os.path.exists(pose_file))
        errors = accuracy(watcher.poses, self.truth)
        self.assertGreater(len(errors), 0 if QUICK else 10 * duration)  # 20 Hz, most of it LOCALIZED
        if errors:
            print("pcap x%g: position error p50 %.3f m p95 %.3f m over %d poses" %
                  (rate, percentile(errors, 0.5), percentile(errors, 0.95), len(errors)))
        if not QUICK:
            self.assertLess(percentile(errors, 0.95), 0.10)

    @unittest.skipIf(QUICK, "real-time UDP at twice the recorded rate: the release build")
    def test_live_udp_with_bad_input_reload_and_a_kill(self):
        config, sock, pose_file = self.paths("udp")
        port = free_port(socket.SOCK_DGRAM)
        write_config(config, 'lidar { udp { bind_address: "127.0.0.1" port: %d position_port: %d } }' % (port, port),
                     'can { candump { path: "%s" } }' % os.path.join(self.drive, "can.log"),
                     self.drive, self.map, sock, pose_file, initial=self.start)
        daemon = Daemon(config, sock)
        daemon.wait_ready()
        watcher = Watcher(sock)
        speed = 2
        replay = subprocess.Popen([INSPECT, "replay", "--to", "127.0.0.1:%d" % port, "--speed", str(speed),
                                   os.path.join(self.drive, "lidar.pcap")],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        RUNNING.append(replay)
        self.assertTrue(daemon.wait_state("LOCALIZED", 5), "not LOCALIZED within 5 s of the replay")

        # Bad input: malformed requests on the API, malformed datagrams on the LiDAR port.
        flood(self, daemon, port, sock)

        # SIGHUP: map and options reloaded, the subscriber keeps its connection.
        before = len(watcher.poses)
        daemon.process.send_signal(signal.SIGHUP)
        time.sleep(0.5)
        self.assertTrue(daemon.wait_state("LOCALIZED", 3), "not LOCALIZED after the reload")
        self.assertGreater(len(watcher.poses), before)
        self.assertIsNone(watcher.process.poll())

        # kill -9 mid-drive, then a warm start from the persisted pose.
        time.sleep(1.0)
        self.assertTrue(os.path.exists(pose_file))
        restarted, relocalized_s = kill_and_warm_start(self, daemon, config, sock)
        final = finish_drive(self, replay, restarted, watcher, config, timeout=60)
        errors = accuracy(watcher.poses, self.truth)
        print("udp x%d: warm start LOCALIZED after %.2f s; %d LOCALIZED poses, p50 %.3f m p95 %.3f m; "
              "lidar %s/s received %s dropped %s" % (speed, relocalized_s, len(errors), percentile(errors, 0.5),
                                                   percentile(errors, 0.95), final["lidar"]["rate_hz"],
                                                   final["lidar"]["received"], final["lidar"]["dropped"]))
        self.assertLess(percentile(errors, 0.95), 0.10)

    def test_bad_configuration_stops_start_up(self):
        config, sock, pose_file = self.paths("bad")
        write_config(config, 'lidar { pcap { path: "%s" } }' % os.path.join(self.drive, "lidar.pcap"),
                     'can { candump { path: "%s" } }' % os.path.join(self.drive, "can.log"),
                     self.drive, self.map, sock, pose_file)
        checked = run(FLAT2DD, "--config", config, "--check")
        self.assertEqual(checked.returncode, 0, checked.stderr)
        with open(config, "a") as f:
            f.write("watchdog_stal_s: 3\n")
        unknown = run(FLAT2DD, "--config", config)
        self.assertEqual(unknown.returncode, 1)
        self.assertIn(config + ":10:", unknown.stderr)
        self.assertIn("watchdog_stal_s", unknown.stderr)
        write_config(config, 'lidar { pcap { path: "%s" } }' % os.path.join(self.drive, "lidar.pcap"),
                     'can { candump { path: "%s" } }' % os.path.join(self.drive, "can.log"),
                     self.drive, os.path.join(WORK, "no-such-map.f2m"), sock, pose_file)
        missing = run(FLAT2DD, "--config", config)
        self.assertEqual(missing.returncode, 1)
        self.assertIn("no-such-map.f2m", missing.stderr)
        self.assertEqual(run(FLAT2DD, "--bogus").returncode, 2)
        self.assertEqual(run(FLAT2D, "--socket", sock, "pose", "--timeout").returncode, 2)
        down = run(FLAT2D, "--socket", os.path.join(WORK, "nobody.sock"), "--timeout", "200", "status")
        self.assertEqual(down.returncode, 1)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
