#!/usr/bin/env python3
"""The Debian packages as a vehicle image gets them: CPack builds flat2d and flat2d-dev from
the install rules, dpkg installs both into an empty root (maintainer scripts run against
that root), and everything the units and the default configuration name is there: the
binaries, the configuration and the files it names, the service user and group, the state
and runtime folders. The installed tools then simulate a short drive, build its prior map
into /var/lib/flat2d, and the installed flat2dd accepts the installed configuration
(--check). `systemd-analyze verify` checks the installed units.

usage: deb_package_test.py BUILD_DIR SOURCE_DIR WORK_DIR
Skips (exit 77) when not root and fakeroot is missing, or dpkg is absent.
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import unittest

BUILD, SOURCE, WORK = sys.argv[1:4]
SKIP = 77
UNIT_DIR = "usr/lib/systemd/system"


def run(*args, timeout=600, **kwargs):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=timeout, **kwargs)


def as_root():
    """dpkg installs need root, or fakeroot's pretence of it."""
    if os.geteuid() == 0:
        return []
    return ["fakeroot"] if shutil.which("fakeroot") else None


def unit_settings(path):
    settings = {}
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith(("#", "[")) and "=" in line:
                key, value = line.split("=", 1)
                settings.setdefault(key, []).append(value)
    return settings


def config_paths(path):
    """The file paths a flat2dd textproto names: key: "value" pairs whose value is a path."""
    with open(path) as f:
        text = re.sub(r"#.*", "", f.read())
    return dict(re.findall(r'(\w+)\s*:\s*"([^"]*/[^"]*|[^"]*\.\w+)"', text))


def users(root, table):
    entries = {}
    with open(os.path.join(root, "etc", table)) as f:
        for line in f:
            fields = line.rstrip("\n").split(":")
            entries[fields[0]] = fields
    return entries


def dpkg(root, *args):
    return run(*as_root(), "dpkg", "--root", root, "--log", os.path.join(WORK, "dpkg.log"), *args)


def install(root, debs):
    """dpkg --install into an empty root. It has none of the shared libraries the package
    depends on; the maintainer scripts run on this machine with DPKG_ROOT set, as in an
    image build."""
    for folder in ("var/lib/dpkg/info", "var/lib/dpkg/updates"):
        os.makedirs(os.path.join(root, folder))
    for f in ("var/lib/dpkg/status", "var/lib/dpkg/available"):
        open(os.path.join(root, f), "w").close()
    return dpkg(root, "--force-depends", "--force-script-chrootless", "--install", *sorted(debs))


class DebianPackage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        result = run("cpack", "-G", "DEB", "-B", os.path.join(WORK, "cpack"),
                     "--config", os.path.join(BUILD, "CPackConfig.cmake"), timeout=900)
        assert result.returncode == 0, result.stdout + result.stderr
        cls.debs = {}
        for deb in glob.glob(os.path.join(WORK, "cpack", "*.deb")):
            name = run("dpkg-deb", "-f", deb, "Package").stdout.strip()
            cls.debs[name] = deb
        cls.root = os.path.join(WORK, "root")
        result = install(cls.root, cls.debs.values())
        assert result.returncode == 0, result.stdout + result.stderr

    def path(self, absolute):
        return os.path.join(self.root, absolute.lstrip("/"))

    def test_packages_and_their_metadata(self):
        self.assertEqual(set(self.debs), {"flat2d", "flat2d-dev"})
        depends = run("dpkg-deb", "-f", self.debs["flat2d"], "Depends").stdout
        for library in ("libprotobuf", "libzstd", "libsystemd", "libpcap", "libgpiod", "procps"):
            self.assertIn(library, depends)
        status = run("dpkg", "--root", self.root, "-s", "flat2d").stdout
        self.assertIn("Status: install ok installed", status)
        self.assertIn("/etc/flat2d/flat2dd.textproto", status)  # listed as a conffile

    def test_files_land_where_the_units_expect(self):
        service = unit_settings(self.path(UNIT_DIR + "/flat2dd.service"))
        socket_unit = unit_settings(self.path(UNIT_DIR + "/flat2dd.socket"))
        exec_start = service["ExecStart"][0].split()
        self.assertTrue(os.access(self.path(exec_start[0]), os.X_OK), exec_start[0])
        config = exec_start[exec_start.index("--config") + 1]
        self.assertTrue(os.path.isfile(self.path(config)), config)
        self.assertTrue(os.path.isfile(self.path(service["Documentation"][0].replace("file://", ""))))
        for folder in service["ReadWritePaths"]:
            self.assertTrue(os.path.isdir(self.path(folder)), folder)
        # The service user and its group, made by sysusers from the postinst.
        passwd, group = users(self.root, "passwd"), users(self.root, "group")
        self.assertIn(service["User"][0], passwd)
        self.assertIn(service["Group"][0], group)
        self.assertIn(socket_unit["SocketGroup"][0], group)
        # tmpfiles made the socket's folder and the state folder, owned by the service.
        uid = int(passwd["flat2d"][2])
        for folder in (os.path.dirname(socket_unit["ListenStream"][0]), "/var/lib/flat2d"):
            self.assertTrue(os.path.isdir(self.path(folder)), folder)
            self.assertEqual(os.stat(self.path(folder)).st_uid, uid, folder)
        # Every file the default configuration names is installed, but the map, whose
        # folder is; relative paths are taken from the configuration's folder.
        named = config_paths(self.path(config))
        self.assertEqual(named["unix_socket"], socket_unit["ListenStream"][0])
        for key in ("dbc", "odometry_config", "grid_config", "localizer_config"):
            file = os.path.join(os.path.dirname(config), named[key])
            self.assertTrue(os.path.isfile(self.path(file)), "%s: %s" % (key, file))
        self.assertTrue(os.path.isdir(self.path(os.path.dirname(named["map"]))))
        self.assertTrue(os.path.isdir(self.path(os.path.dirname(named["l2g_path"]))))
        for f in ("/usr/share/flat2d/proto/daemon/api/flat2d_api.proto", "/usr/bin/flat2d",
                  "/usr/lib/sysctl.d/60-flat2d.conf", "/usr/include/flat2d/daemon/client/client.hpp",
                  "/usr/lib/cmake/flat2d/flat2dConfig.cmake"):
            self.assertTrue(os.path.exists(self.path(f)), f)

    def test_an_application_builds_against_the_installed_client_library(self):
        build = os.path.join(WORK, "consumer")
        result = run("cmake", "-S", os.path.join(SOURCE, "tests", "packaging", "client_consumer"), "-B", build,
                     "-DCMAKE_PREFIX_PATH=" + self.path("/usr"), "-DCMAKE_BUILD_TYPE=Release")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        result = run("cmake", "--build", build)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        absent = os.path.join(WORK, "no-daemon.sock")
        result = run(os.path.join(build, "pose_printer"), absent)
        self.assertEqual(result.returncode, 1)
        self.assertIn("no-daemon.sock", result.stderr)

    def test_installed_tools_build_a_map_the_installed_daemon_accepts(self):
        bin_dir = self.path("/usr/bin")
        drive = os.path.join(WORK, "drive")
        result = run(os.path.join(bin_dir, "flat2d-sim"), "--world", "occluders", "--drive", "0",
                     "--sensor", "vlp16", "--duration", "20", "--out", drive)
        self.assertEqual(result.returncode, 0, result.stderr)
        # The installed configuration, with its absolute paths moved into the root.
        config = os.path.join(WORK, "flat2dd.textproto")
        with open(self.path("/etc/flat2d/flat2dd.textproto")) as f:
            text = f.read()
        text = re.sub(r'"/(usr|var|run|etc)/', lambda m: '"%s/%s/' % (self.root, m.group(1)), text)
        text = re.sub(r'"(vehicle.dbc|odometry.textproto)"',
                      lambda m: '"%s"' % self.path("/etc/flat2d/" + m.group(1)), text)
        with open(config, "w") as f:
            f.write(text)
        flat2dd = self.path("/usr/sbin/flat2dd")
        missing = run(flat2dd, "--check", "--config", config)
        self.assertNotEqual(missing.returncode, 0)
        self.assertIn("map.f2m", missing.stderr)  # no map yet: the error names it
        result = run(os.path.join(bin_dir, "flat2d-map"), "build", "--pcap", os.path.join(drive, "lidar.pcap"),
                     "--can", os.path.join(drive, "can.log"), "--dbc", self.path("/etc/flat2d/vehicle.dbc"),
                     "--odometry", self.path("/etc/flat2d/odometry.textproto"),
                     "--out", self.path("/var/lib/flat2d/map.f2m"))
        self.assertEqual(result.returncode, 0, result.stderr)
        result = run(flat2dd, "--check", "--config", config)
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_systemd_analyze_verifies_the_installed_units(self):
        if not shutil.which("systemd-analyze"):
            self.skipTest("systemd-analyze is not installed")
        units = [self.path(UNIT_DIR + "/" + u) for u in ("flat2dd.socket", "flat2dd.service")]
        # ExecReload's /bin/kill is procps's (the package depends on it); the empty root gets
        # this machine's, as any Debian base system has it.
        kill = self.path("/bin/kill")
        if not os.path.exists(kill):
            os.makedirs(os.path.dirname(kill), exist_ok=True)
            shutil.copy("/bin/kill", kill)
        result = run("systemd-analyze", "verify", "--root", self.root, "--man=no",
                     "--recursive-errors=no", *units)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual(result.stderr.strip(), "")

    def test_purge_removes_the_package_and_keeps_the_operators_maps(self):
        root = os.path.join(WORK, "purged")
        self.assertEqual(install(root, self.debs.values()).returncode, 0)
        map_file = os.path.join(root, "var/lib/flat2d/map.f2m")
        pose_file = os.path.join(root, "var/lib/flat2d/last_pose.textproto")
        for f in (map_file, pose_file):
            open(f, "w").close()
        result = dpkg(root, "--force-script-chrootless", "--purge", "flat2d-dev", "flat2d")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        for gone in ("usr/sbin/flat2dd", "etc/flat2d/flat2dd.textproto", "usr/lib/systemd/system/flat2dd.service"):
            self.assertFalse(os.path.exists(os.path.join(root, gone)), gone)
        self.assertFalse(os.path.exists(pose_file))
        self.assertTrue(os.path.exists(map_file))


if __name__ == "__main__":
    if as_root() is None or not shutil.which("dpkg"):
        print("SKIP: dpkg --root needs root or fakeroot, and dpkg")
        sys.exit(SKIP)
    sys.argv[1:] = ["-v"]
    unittest.main()
