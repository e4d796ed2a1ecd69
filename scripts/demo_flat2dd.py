#!/usr/bin/env python3
"""The demo's service run (called by scripts/demo): flat2dd on out/demo/drive over a UDP
LiDAR on loopback and the drive's candump log, a `flat2d watch` subscriber, and a report
of accuracy against the truth, rates, CPU and memory; the map with the true and estimated
trajectories in OUT/campus_trajectory.png (flat2d-eval traj --plot).

usage: demo_flat2dd.py --bin BUILD_DIR --out OUT_DIR [--speed X]
"""
import argparse
import json
import math
import os
import socket
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(ROOT, "tests", "daemon"))
from flat2dd_harness import RUNNING, Daemon, Tools, Truth, Watcher, configure, free_port, write_config  # noqa: E402
from proc_stats import memory_kb, process_cpu_s  # noqa: E402

def write_tum(poses, path):
    """The subscriber's valid poses as a TUM trajectory (t x y z qx qy qz qw), one per time."""
    last = None
    with open(path, "w") as f:
        for _, p in poses:
            if not p.get("valid"):
                continue
            t = int(p["time_ns"])
            if t == last:
                continue
            last = t
            g = p["global_T_vehicle"]
            theta = g.get("theta", 0.0)
            f.write("%.9f %.4f %.4f 0 0 0 %.9f %.9f\n" % (t * 1e-9, g.get("x", 0.0), g.get("y", 0.0),
                                                          math.sin(theta / 2), math.cos(theta / 2)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bin", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--speed", type=float, default=2.0)
    args = parser.parse_args()
    b, out = args.bin, os.path.abspath(args.out)
    configure(Tools(os.path.join(b, "daemon", "flat2dd"), os.path.join(b, "daemon", "flat2d"),
                    os.path.join(b, "maps", "tools", "flat2d-sim"), os.path.join(b, "localization", "tools", "flat2d-map"),
                    os.path.join(b, "maps", "tools", "flat2d-inspect"), ROOT))
    drive = os.path.join(out, "drive")
    truth = Truth(os.path.join(drive, "truth.tum"))
    config, sock, pose_file = (os.path.join(out, "flat2dd" + ext) for ext in (".textproto", ".sock", ".pose.textproto"))
    for p in (sock, pose_file, config + ".log"):
        if os.path.exists(p):
            os.remove(p)
    port = free_port(socket.SOCK_DGRAM)
    write_config(config, 'lidar { udp { bind_address: "127.0.0.1" port: %d position_port: %d } }' % (port, port),
                 'can { candump { path: "%s" } }' % os.path.join(drive, "can.log"),
                 drive, os.path.join(out, "campus.f2m"), sock, pose_file, initial=truth.at(truth.t[1]),
                 odometry=os.path.join(out, "campus.odometry.textproto"))  # the mapping drive's wheel calibration
    try:
        daemon = Daemon(config, sock)
        daemon.wait_ready()
        ready_s = time.monotonic() - daemon.started
        watcher = Watcher(sock)
        cpu_before = process_cpu_s(daemon.process.pid)
        started = time.monotonic()
        replay = subprocess.run([os.path.join(b, "maps", "tools", "flat2d-inspect"), "replay", "--to",
                                 "127.0.0.1:%d" % port, "--speed", str(args.speed), os.path.join(drive, "lidar.pcap")],
                                capture_output=True, text=True)
        wall_s = time.monotonic() - started
        time.sleep(0.5)
        status = daemon.status()
        cpu_s = process_cpu_s(daemon.process.pid) - cpu_before
        rss_kb, hwm_kb = memory_kb(daemon.process.pid)
        watcher.stop()
        code, stop_s = daemon.stop()
    finally:
        for process in RUNNING:
            if process.poll() is None:
                process.kill()
    if replay.returncode != 0:
        sys.exit("demo: the replay failed: " + replay.stderr)

    estimate = os.path.join(out, "campus_estimate.tum")
    write_tum(watcher.poses, estimate)
    evaluation = subprocess.run([os.path.join(b, "localization", "tools", "flat2d-eval"), "traj", "--truth",
                                 os.path.join(drive, "truth.tum"), "--est", estimate, "--json", "--plot",
                                 os.path.join(out, "campus"), "--map", os.path.join(out, "campus_map.yaml")],
                                capture_output=True, text=True)
    if evaluation.returncode != 0:
        sys.exit("demo: flat2d-eval failed: " + evaluation.stderr)
    traj = json.loads(evaluation.stdout)
    states = {}
    for _, p in watcher.poses:
        states[p.get("state", "?")] = states.get(p.get("state", "?"), 0) + 1
    revolutions = int(status.get("revolutions", 0))
    drive_s = truth.t[-1] - truth.t[0]
    report = {
        "drive_s": round(drive_s, 1), "replay_speed": args.speed, "replay_wall_s": round(wall_s, 1),
        "ready_s": round(ready_s, 3), "stop_s": round(stop_s, 3), "exit_code": code,
        "poses_received": len(watcher.poses), "states": states, "accuracy": traj,
        "lidar": status.get("lidar", {}), "can": status.get("can", {}), "revolutions": revolutions,
        "matches_accepted": int(status.get("matches_accepted", 0)),
        "match_ms_p50": status.get("match_ms_p50", 0), "match_ms_p99": status.get("match_ms_p99", 0),
        "cpu_s": round(cpu_s, 2), "cpu_ms_per_revolution": round(1e3 * cpu_s / max(1, revolutions), 2),
        "cpu_share_of_a_core": round(cpu_s / wall_s, 3), "rss_mib": round(rss_kb / 1024, 1),
        "peak_rss_mib": round(hwm_kb / 1024, 1),
    }
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    print_report(report, traj, out)


def print_report(r, traj, out):
    lidar, can = r["lidar"], r["can"]
    print("flat2d demo: campus drive 1, %.0f s, replayed over UDP at %gx in %.0f s" %
          (r["drive_s"], r["replay_speed"], r["replay_wall_s"]))
    print("  service    READY after %.2f s, stopped in %.3f s (exit %d)" % (r["ready_s"], r["stop_s"], r["exit_code"]))
    print("  poses      %d received; states %s" % (r["poses_received"],
                                                 ", ".join("%s %d" % kv for kv in sorted(r["states"].items()))))
    print("  accuracy   position p50 %.3f m, p95 %.3f m, lateral p99 %.3f m, ATE %.3f m; "
          "heading within 0.02 rad %.1f %%, worst %.4f rad (%d poses at the truth's times)" %
          (traj["position_p50_m"], traj["position_p95_m"], traj["lateral_p99_m"], traj["ate_rmse_m"],
           100 * traj["heading_within_0_02"], traj["heading_worst_rad"], traj["poses"]))
    print("  rates      LiDAR %.0f datagrams/s (%s received, %s dropped, %s malformed), CAN %.0f frames/s" %
          (lidar.get("rate_hz", 0), lidar.get("received", 0), lidar.get("dropped", 0), lidar.get("malformed", 0),
           can.get("rate_hz", 0)))
    print("  matching   %d revolutions, %d matches accepted, match p50 %.1f ms p99 %.1f ms" %
          (r["revolutions"], r["matches_accepted"], r["match_ms_p50"], r["match_ms_p99"]))
    print("  CPU        %.1f s: %.2f ms per revolution, %.0f %% of one core" %
          (r["cpu_s"], r["cpu_ms_per_revolution"], 100 * r["cpu_share_of_a_core"]))
    print("  memory     RSS %.1f MiB at the end, peak %.1f MiB" % (r["rss_mib"], r["peak_rss_mib"]))
    print("  files      %s/report.json, %s/campus_trajectory.png (truth green, estimate blue)" % (out, out))


if __name__ == "__main__":
    main()
