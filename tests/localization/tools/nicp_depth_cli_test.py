#!/usr/bin/env python3
"""flat2d-map build --mode nicp depth.txt as users call it: TUM fr1/rpy tracked frame to model
and frame to frame, judged by flat2d-eval traj --3d against the motion capture, the files
written, and the exit statuses on bad input.

usage: nicp_depth_cli_test.py FLAT2D_MAP FLAT2D_EVAL DATA_DIR WORK_DIR [quick]
Needs ../shared/data/depth/tum_rgbd_fr1_rpy_first200 (exit 77, skipped, without it). The frames
are taken at 320 x 240 (--image-scale 2) to keep the test short; "quick" (the sanitizer
build) tracks 12 frames and checks the files and statuses, not the accuracy.
"""
import json
import os
import subprocess
import sys
import unittest

MAP, EVAL, DATA, WORK = sys.argv[1:5]
QUICK = len(sys.argv) > 5 and sys.argv[5] == "quick"
TUM = os.path.join(os.environ.get("FLAT2D_DATA", DATA), "depth", "tum_rgbd_fr1_rpy_first200")
FRAMES = 12 if QUICK else 60
# Frames 0-59 at 320 x 240, measured on 2026-12-04: frame to model ATE 0.044 m, frame to
# frame over one radius (0.1 m) 0.105 m; on 2026-12-07 frame to frame over the default
# radii 0.1, 0.03 m 0.033 m. The bounds leave a margin of 1.5x or more; the model must
# also beat the chain of its own one-radius registrations.
MODEL_ATE_M = 0.07
FRAME_RADII_ATE_M = 0.05


def run(tool, *args):
    return subprocess.run([tool, *args], capture_output=True, text=True, timeout=900)


def build(tracking, out, *extra):
    return run(MAP, "build", "--mode", "nicp", os.path.join(TUM, "depth.txt"), "--image-scale", "2",
               "--max-frames", str(FRAMES), "--tracking", tracking, "--out", out, "--json", *extra)


def trajectory_errors(out):
    result = run(EVAL, "traj", "--3d", "--truth", os.path.join(TUM, "groundtruth.txt"),
                 "--est", os.path.join(out, "trajectory.tum"), "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def ate(out):
    return trajectory_errors(out)["ate_rmse_m"]


def ply_vertices(path):
    with open(path, "rb") as f:
        header = f.read(512).split(b"end_header")[0].decode()
    for line in header.splitlines():
        if line.startswith("element vertex"):
            return int(line.split()[2])
    return -1


class NicpDepthList(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        cls.model_out = os.path.join(WORK, "fr1_model")
        cls.frame_out = os.path.join(WORK, "fr1_frame")
        cls.model = build("model", cls.model_out)
        cls.frame = build("frame", cls.frame_out)
        # Only the accuracy tests read the one-radius chain, and they skip in the quick run.
        cls.frame_one_radius_out = os.path.join(WORK, "fr1_frame_one_radius")
        cls.frame_one_radius = None if QUICK else build("frame", cls.frame_one_radius_out, "--radius", "0.1")
        cls.model_fine_out = os.path.join(WORK, "fr1_model_fine")
        cls.model_fine = None if QUICK else build("model", cls.model_fine_out, "--model-fine-radius")

    def test_frame_to_model_writes_its_summary_trajectory_and_model(self):
        self.assertEqual(self.model.returncode, 0, self.model.stderr)
        s = json.loads(self.model.stdout)
        for key in ("frames", "failures", "frame_ms_p50", "frame_ms_p95", "registration_ms_p50", "merge_ms_p50",
                    "load_ms_p50", "model_points", "method", "tracking"):
            self.assertIn(key, s)
        self.assertEqual((s["frames"], s["failures"], s["method"], s["tracking"]), (FRAMES, 0, "nicp", "model"))
        with open(os.path.join(self.model_out, "trajectory.tum")) as f:
            self.assertEqual(len([l for l in f if not l.startswith("#")]), FRAMES)
        # The merged model: more than one frame's points (320 x 240), fewer than every frame's.
        vertices = ply_vertices(os.path.join(self.model_out, "model.ply"))
        self.assertEqual(vertices, s["model_points"])
        self.assertGreater(vertices, 320 * 240)
        self.assertLess(vertices, FRAMES * 320 * 240 // 2)

    def test_frame_to_model_drifts_less_than_the_chain_of_frames(self):
        if QUICK:
            self.skipTest("accuracy is judged in the release build")
        self.assertEqual(self.frame_one_radius.returncode, 0, self.frame_one_radius.stderr)
        model_ate, frame_ate = ate(self.model_out), ate(self.frame_one_radius_out)
        print("ATE over %d frames: frame to model %.3f m, frame to frame (R 0.1 m) %.3f m" % (FRAMES, model_ate, frame_ate))
        self.assertLess(model_ate, MODEL_ATE_M)
        self.assertLess(model_ate, 0.8 * frame_ate)

    def test_coarse_to_fine_radii_shorten_the_chain_drift(self):
        """Frame to frame over radii 0.1 then 0.03 m (the default) against 0.1 m alone."""
        if QUICK:
            self.skipTest("accuracy is judged in the release build")
        self.assertEqual(self.frame.returncode, 0, self.frame.stderr)
        radii_ate, one_ate = ate(self.frame_out), ate(self.frame_one_radius_out)
        print("ATE over %d frames, frame to frame: R 0.1, 0.03 m %.3f m, R 0.1 m %.3f m" % (FRAMES, radii_ate, one_ate))
        self.assertLess(radii_ate, FRAME_RADII_ATE_M)
        self.assertLess(radii_ate, 0.6 * one_ate)

    def test_model_fine_radius_steadies_each_frame(self):
        """--model-fine-radius: the model tracker's last 5 iterations on normals over 0.03 m.
        Measured on frames 0-59 at 320 x 240: RPE per frame 9.6 mm against 17.8 mm. Its ATE
        is no better over these frames (0.059 against 0.045 m; over all 200, 0.040 against
        0.077 m), so the test holds the per-frame error, where the gain is steady."""
        if QUICK:
            self.skipTest("accuracy is judged in the release build")
        self.assertEqual(self.model_fine.returncode, 0, self.model_fine.stderr)
        fine = trajectory_errors(self.model_fine_out)["rpe_frame_trans_rmse_m"]
        one = trajectory_errors(self.model_out)["rpe_frame_trans_rmse_m"]
        print("RPE per frame over %d frames, frame to model: fine radius %.4f m, one radius %.4f m" % (FRAMES, fine, one))
        self.assertLess(fine, 0.7 * one)

    def test_snicp_at_160x120_tracks_with_merging(self):
        """The real-time configuration: SNICP's pyramid 80x60, 160x120 of every 4th pixel,
        each frame merged. Frames 0-59, measured on 2026-12-07: ATE 0.111 m, no failure,
        3.1 ms a frame (p50, not asserted: timing belongs to the benchmarks)."""
        out = os.path.join(WORK, "fr1_snicp_160")
        r = run(MAP, "build", "--mode", "nicp", os.path.join(TUM, "depth.txt"), "--method", "snicp",
                "--image-scale", "4", "--snicp-scales", "2,1", "--max-frames", str(FRAMES), "--out", out, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        s = json.loads(r.stdout)
        self.assertEqual((s["frames"], s["failures"], s["method"]), (FRAMES, 0, "snicp"))
        # Every frame adds at most its 160 x 120 points.
        self.assertLess(s["model_points"], FRAMES * 160 * 120)
        if not QUICK:
            self.assertLess(ate(out), 0.17)

    def test_bad_input_is_refused_with_a_status(self):
        self.assertEqual(build("sideways", os.path.join(WORK, "bad")).returncode, 1)
        for flag, value in (("--snicp-scales", "1,2"), ("--snicp-scales", "0"), ("--flat-curvature", "1.5"),
                            ("--image-scale", "0"), ("--radius", "0.03,0.1"), ("--radius", "-1")):
            bad = build("model", os.path.join(WORK, "bad"), flag, value)
            self.assertEqual(bad.returncode, 1, flag + " " + value)
            self.assertIn(flag, bad.stderr + bad.stdout, value)
        # The model tracker's fine radius needs the model tracker, NICP's normals and a radius to refine to.
        for tracking, extra in (("frame", ()), ("model", ("--method", "snicp")), ("model", ("--radius", "0.1"))):
            bad = build(tracking, os.path.join(WORK, "bad"), "--model-fine-radius", *extra)
            self.assertEqual(bad.returncode, 1, " ".join((tracking,) + extra))
            self.assertIn("--model-fine-radius", bad.stderr)
        missing = run(MAP, "build", "--mode", "nicp", os.path.join(WORK, "no_such_list.txt"), "--out",
                      os.path.join(WORK, "bad"))
        self.assertEqual(missing.returncode, 2)
        self.assertIn("no_such_list.txt", missing.stderr)


if __name__ == "__main__":
    if not os.path.isdir(TUM):
        print("nicp_depth_cli_test: skipped, no %s (set FLAT2D_DATA)" % TUM)
        sys.exit(77)
    unittest.main(argv=sys.argv[:1], verbosity=2)
