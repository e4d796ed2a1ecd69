"""A process's CPU time and memory from /proc, for scripts/demo and scripts/bench-soak."""
import os

TICKS = os.sysconf("SC_CLK_TCK")


def _cpu_s(stat_path):
    with open(stat_path) as f:
        fields = f.read().rsplit(")", 1)[1].split()  # past the command name, which may hold spaces
    return (int(fields[11]) + int(fields[12])) / TICKS  # utime + stime


def process_cpu_s(pid):
    """User + system CPU seconds of the process, all its threads (ended ones included)."""
    return _cpu_s("/proc/%d/stat" % pid)


def thread_cpu_s(pid):
    """{thread name: user + system CPU seconds} of the threads still running."""
    result = {}
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/comm" % (pid, tid)) as f:
                name = f.read().strip()
            result[name] = result.get(name, 0.0) + _cpu_s("/proc/%d/task/%s/stat" % (pid, tid))
        except OSError:  # the thread ended meanwhile
            continue
    return result


def memory_kb(pid):
    """(VmRSS, VmHWM) in KiB."""
    values = {}
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            key, _, rest = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                values[key] = int(rest.split()[0])
    return values.get("VmRSS", 0), values.get("VmHWM", 0)
