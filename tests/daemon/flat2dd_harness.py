"""What the flat2dd end-to-end tests share: the tools, the simulator's truth, the daemon and
a `flat2d watch` subscriber as processes, the daemon's configuration and the accuracy of
the poses received. Every process started is listed in RUNNING, for the tests to kill.
"""
import bisect
import json
import math
import os
import random
import signal
import socket
import subprocess
import threading
import time


class Tools:
    """The binaries under test and the source tree, from the test's command line."""

    def __init__(self, flat2dd, flat2d, sim, map_tool, inspect, source):
        self.flat2dd, self.flat2d, self.sim, self.map, self.inspect = flat2dd, flat2d, sim, map_tool, inspect
        self.packaging = os.path.join(source, "packaging", "config")


TOOLS = None  # set by configure()


def configure(tools):
    global TOOLS
    TOOLS = tools


def run(*args, timeout=600):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=timeout)


def free_port(kind):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Truth:
    """The simulator's truth.tum (t x y z qx qy qz qw), interpolated in time."""

    def __init__(self, path):
        self.t, self.x, self.y, self.yaw = [], [], [], []
        with open(path) as f:
            for line in f:
                v = [float(x) for x in line.split()]
                qx, qy, qz, qw = v[4:8]
                self.t.append(v[0])
                self.x.append(v[1])
                self.y.append(v[2])
                self.yaw.append(math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz)))

    def at(self, time_s):
        """(x, y, yaw) at time_s, or None outside the drive."""
        i = bisect.bisect_left(self.t, time_s)
        if i <= 0 or i >= len(self.t):
            return None
        s = (time_s - self.t[i - 1]) / (self.t[i] - self.t[i - 1])
        dyaw = wrap(self.yaw[i] - self.yaw[i - 1])
        return (self.x[i - 1] + s * (self.x[i] - self.x[i - 1]), self.y[i - 1] + s * (self.y[i] - self.y[i - 1]),
                wrap(self.yaw[i - 1] + s * dyaw))

    def error(self, time_s, x, y):
        truth = self.at(time_s)
        return None if truth is None else math.hypot(x - truth[0], y - truth[1])


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


class Watcher:
    """`flat2d watch --json` in the background: every pose it prints, with the wall time."""

    def __init__(self, sock, rate=20):
        self.poses = []
        self.process = subprocess.Popen([TOOLS.flat2d, "--socket", sock, "--json", "watch", "--rate", str(rate)],
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        RUNNING.append(self.process)
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        for line in self.process.stdout:
            try:
                self.poses.append((time.monotonic(), json.loads(line)))
            except json.JSONDecodeError:
                pass

    def stop(self):
        self.process.terminate()
        self.process.wait(timeout=5)
        return self.process.returncode


RUNNING = []  # every process started, killed at the end of each test whatever happened


class Daemon:
    def __init__(self, config, sock):
        self.config, self.sock = config, sock
        self.started = time.monotonic()
        with open(config + ".log", "a") as log:  # the daemon keeps its own descriptor
            self.process = subprocess.Popen([TOOLS.flat2dd, "--config", config], stdout=log, stderr=log)
        RUNNING.append(self.process)

    def wait_ready(self, timeout=30):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise AssertionError("flat2dd exited with %d" % self.process.returncode)
            if os.path.exists(self.sock) and self.status() is not None:
                return
            time.sleep(0.05)
        raise AssertionError("flat2dd did not become ready")

    def status(self):
        result = run(TOOLS.flat2d, "--socket", self.sock, "--json", "--timeout", "1000", "status", timeout=10)
        return json.loads(result.stdout) if result.returncode == 0 else None

    def wait_state(self, state, timeout):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            status = self.status()
            if status and status.get("state") == state:
                return True
            time.sleep(0.05)
        return False

    def stop(self):
        start = time.monotonic()
        self.process.send_signal(signal.SIGTERM)
        code = self.process.wait(timeout=10)
        return code, time.monotonic() - start


def write_config(path, lidar, can, drive, map_path, sock, pose_file, initial=None, odometry=None):
    """A flat2dd configuration; odometry: a calibrated odometry file instead of the shipped one."""
    lines = [lidar, can,
             'dbc: "%s"' % os.path.join(drive, "vehicle.dbc"),
             'odometry_config: "%s"' % (odometry or os.path.join(TOOLS.packaging, "odometry", "flat2d_sim.textproto")),
             'grid_config: "%s"' % os.path.join(TOOLS.packaging, "grid", "structure_grid.textproto"),
             'localizer_config: "%s"' % os.path.join(TOOLS.packaging, "localizer", "localizer.textproto"),
             'map: "%s"' % map_path,
             'api { unix_socket: "%s" }' % sock,
             'persistence { l2g_path: "%s" period_s: 0.5 }' % pose_file]
    if initial:
        lines.append("initial_pose { x: %.6f y: %.6f theta: %.6f sigma_m: 0.2 sigma_rad: 0.02 }" % initial)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def build_map(mapping, map_path, timeout=600, scale_from_gnss=False):
    """flat2d-map build of a simulated mapping drive's folder with its CAN odometry, fitted to
    the truth track, as the map engineer runs it; with scale_from_gnss the map's scale comes
    from the GNSS fixes in the drive's position packets (a drive simulated with --gnss-rtk),
    and MAP.odometry.textproto is the vehicle's odometry with the wheel scale it measured."""
    gnss = ["--scale-from-gnss", "--calibrated-odometry-out", calibrated_odometry(map_path)] if scale_from_gnss else []
    result = run(TOOLS.map, "build", "--pcap", os.path.join(mapping, "lidar.pcap"),
                 "--can", os.path.join(mapping, "can.log"), "--dbc", os.path.join(mapping, "vehicle.dbc"),
                 "--odometry", os.path.join(TOOLS.packaging, "odometry", "flat2d_sim.textproto"),
                 "--anchor", os.path.join(mapping, "truth.tum"), *gnss, "--out", map_path, timeout=timeout)
    assert result.returncode == 0, result.stderr


def calibrated_odometry(map_path):
    """Where build_map(scale_from_gnss=True) writes the calibrated odometry configuration."""
    return os.path.splitext(map_path)[0] + ".odometry.textproto"


def kill_running():
    """Kills every process a test started and still running (tearDown)."""
    for process in RUNNING:
        if process.poll() is None:
            process.kill()
            process.wait()
    RUNNING.clear()


def localized(poses):
    """The valid LOCALIZED poses of a Watcher's list."""
    return [p for _, p in poses if p.get("valid") and p.get("state") == "LOCALIZED"]


def accuracy(poses, truth):
    """Position errors (m) of the LOCALIZED poses against the truth."""
    return [e for e, _ in errors(poses, truth)]


def errors(poses, truth):
    """(position error m, heading error rad) of each LOCALIZED pose against the truth."""
    result = []
    for p in localized(poses):
        g = p["global_T_vehicle"]
        t = truth.at(int(p["time_ns"]) * 1e-9)
        if t is not None:
            result.append((math.hypot(g["x"] - t[0], g["y"] - t[1]), abs(wrap(g.get("theta", 0.0) - t[2]))))
    return result


def flood(test, daemon, port, sock):
    """500 malformed datagrams on the LiDAR port and 100 API connections that each send a frame
    of garbage and then announce 4 GiB (each must be closed): all counted, the state kept."""
    before = daemon.status()
    rng = random.Random(1)
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as bad_udp:
        for _ in range(500):
            size = rng.choice([0, 7, 511, 513, 1205, 1206, 1207])
            bad_udp.sendto(bytes(rng.getrandbits(8) for _ in range(size)), ("127.0.0.1", port))
    for _ in range(100):
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
            s.connect(sock)
            s.sendall(bytes([6]) + bytes(rng.getrandbits(8) for _ in range(6)))  # a frame, garbage inside
            s.sendall(bytes([0x80, 0x80, 0x80, 0x80, 0x10]))                   # then 4 GiB announced
            s.settimeout(2)
            try:
                while s.recv(4096):
                    pass
            except socket.timeout:
                test.fail("the daemon kept a connection that announced 4 GiB")

    def counted(status, key):
        return int(status.get("lidar", {}).get(key, 0)) if key == "malformed" else int(status.get(key, 0))

    deadline = time.monotonic() + 3  # the health figures are published once a revolution
    while True:
        after = daemon.status()
        if counted(after, "malformed") - counted(before, "malformed") >= 500 or time.monotonic() > deadline:
            break
        time.sleep(0.1)
    test.assertEqual(counted(after, "malformed") - counted(before, "malformed"), 500)
    test.assertGreaterEqual(counted(after, "malformed_requests") - counted(before, "malformed_requests"), 200)
    test.assertEqual(after["state"], "LOCALIZED")


def kill_and_warm_start(test, daemon, config, sock):
    """kill -9, then a restart that must be LOCALIZED within 2 s from the persisted pose.
    Returns the restarted Daemon and how long it took."""
    daemon.process.kill()
    daemon.process.wait()
    restarted = Daemon(config, sock)
    restarted.wait_ready()
    test.assertTrue(restarted.wait_state("LOCALIZED", 2.0), "not LOCALIZED within 2 s of the warm start")
    return restarted, time.monotonic() - restarted.started


def finish_drive(test, replay, daemon, watcher, config, timeout):
    """Waits for the replay, checks the subscriber stayed, stops the daemon (exit 0 within 1 s,
    and its log says it warm-started). Returns the last status."""
    replay.wait(timeout=timeout)
    time.sleep(0.5)
    final = daemon.status()
    if watcher.process.poll() is not None:
        test.fail("the subscriber gave up: " + watcher.process.stderr.read())
    watcher.stop()
    code, stop_s = daemon.stop()
    test.assertEqual(code, 0)
    test.assertLess(stop_s, 1.0)
    with open(config + ".log") as f:
        test.assertIn("warm start", f.read())
    return final
