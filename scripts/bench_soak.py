#!/usr/bin/env python3
"""flat2dd soak run (called by scripts/bench-soak): the daemon on a long drive through its
pcap source, faster than real time, sampled every 5 s: RSS, each thread's CPU, the health
figures. Writes OUT/samples.csv and OUT/report.json and prints the summary: CPU per
revolution by thread, and whether RSS stayed flat (the first sample after the warm-up
against the largest and the last).

usage: bench_soak.py --bin BUILD_DIR --drive DRIVE_DIR --map MAP.f2m --rate X --out OUT_DIR
"""
import argparse
import json
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(ROOT, "tests", "daemon"))
from flat2dd_harness import RUNNING, Daemon, Tools, Truth, configure, write_config  # noqa: E402
from proc_stats import memory_kb, thread_cpu_s  # noqa: E402

SAMPLE_S = 5.0
WARM_UP_S = 60.0  # wall seconds: the map window's tiles, the graph's window and the rings fill


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--bin", "--drive", "--map", "--out"):
        parser.add_argument(flag, required=True)
    parser.add_argument("--rate", type=float, default=4.0)
    args = parser.parse_args()
    b, out, drive = args.bin, os.path.abspath(args.out), os.path.abspath(args.drive)
    configure(Tools(os.path.join(b, "daemon", "flat2dd"), os.path.join(b, "daemon", "flat2d"), "", "", "", ROOT))
    truth = Truth(os.path.join(drive, "truth.tum"))
    drive_s = truth.t[-1] - truth.t[0]
    config, sock, pose_file = (os.path.join(out, "flat2dd" + ext) for ext in (".textproto", ".sock", ".pose.textproto"))
    for p in (sock, pose_file, config + ".log"):
        if os.path.exists(p):
            os.remove(p)
    write_config(config, 'lidar { pcap { path: "%s" rate: %g } }' % (os.path.join(drive, "lidar.pcap"), args.rate),
                 'can { candump { path: "%s" } }' % os.path.join(drive, "can.log"),
                 drive, os.path.abspath(args.map), sock, pose_file, initial=truth.at(truth.t[1]))
    samples = []
    try:
        daemon = Daemon(config, sock)
        daemon.wait_ready()
        pid = daemon.process.pid
        started = time.monotonic()
        deadline = started + drive_s / args.rate + 2.0
        while time.monotonic() < deadline:
            status = daemon.status() or {}
            samples.append({"wall_s": time.monotonic() - started, "rss_kb": memory_kb(pid)[0], "cpu": thread_cpu_s(pid),
                            "revolutions": int(status.get("revolutions", 0)), "state": status.get("state", "?"),
                            "lidar_dropped": int(status.get("lidar", {}).get("dropped", 0)),
                            "match_ms_p99": status.get("match_ms_p99", 0.0)})
            time.sleep(SAMPLE_S)
        final = daemon.status()
        code, _ = daemon.stop()
    finally:
        for process in RUNNING:
            if process.poll() is None:
                process.kill()
    report = summarize(samples, final, drive_s, args.rate, code)
    with open(os.path.join(out, "samples.csv"), "w") as f:
        f.write("wall_s,rss_kb,revolutions,state,lidar_dropped,match_ms_p99\n")
        for s in samples:
            f.write("%.1f,%d,%d,%s,%d,%.2f\n" % (s["wall_s"], s["rss_kb"], s["revolutions"], s["state"],
                                                  s["lidar_dropped"], s["match_ms_p99"]))
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    print(json.dumps(report, indent=2))


def summarize(samples, final, drive_s, rate, code):
    warm = [s for s in samples if s["wall_s"] >= WARM_UP_S] or samples
    first, last = warm[0], samples[-1]
    revolutions = last["revolutions"] - first["revolutions"]
    # A thread's CPU time only grows; the pcap source's thread ends with the file, so take
    # each thread's newest sample.
    newest = {}
    for s in warm:
        newest.update(s["cpu"])
    cpu_ms = {name: round(1e3 * (cpu - first["cpu"].get(name, 0.0)) / max(1, revolutions), 3)
              for name, cpu in newest.items()}
    states = {}
    for s in samples:
        states[s["state"]] = states.get(s["state"], 0) + 1
    return {
        "drive_s": round(drive_s, 1), "rate": rate, "samples": len(samples), "exit_code": code,
        "revolutions": int(final.get("revolutions", 0)), "lidar_dropped": int(final["lidar"].get("dropped", 0)),
        "states_sampled": states,
        "cpu_ms_per_revolution": {"total": round(sum(cpu_ms.values()), 3), "by_thread": cpu_ms},
        "rss_mib": {"after_warm_up": round(first["rss_kb"] / 1024, 1),
                    "max_after_warm_up": round(max(s["rss_kb"] for s in warm) / 1024, 1),
                    "last": round(last["rss_kb"] / 1024, 1)},
        "rss_growth_after_warm_up_mib": round((max(s["rss_kb"] for s in warm) - first["rss_kb"]) / 1024, 2),
    }


if __name__ == "__main__":
    main()
