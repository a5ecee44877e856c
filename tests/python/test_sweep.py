"""peensim.sweep and peensim.Sweep: each run is the run alone, byte for byte; the comparison as
arrays; a dict scene; resuming; bad input before anything runs."""

import contextlib
import io
import os
import unittest

import numpy as np

import peensim
from support import SOURCE_DIR, TempDirTest, cli, read_bytes, scene

ROD_SHORT = {"process.duration": "20 ms", "shot.count": 64}


class SweepTest(TempDirTest):
    def sweep(self, *args, **kwargs):
        with contextlib.redirect_stdout(io.StringIO()) as printed:
            result = peensim.sweep(*args, **kwargs)
        return result, printed.getvalue()

    def test_each_run_is_the_run_alone_and_the_comparison_is_arrays(self):
        rod = peensim.Scene(scene("rod.yaml")).set(ROD_SHORT)
        study, printed = self.sweep(rod, self.path("study"), vary={"process.gravity": [[0, 0, -9.81], [0, 0, -4.9]]}, seeds=2, jobs=2)
        self.assertIn("sweep: 2 variants x 2 seeds = 4 runs, 2 at once", printed)
        runs = study.runs
        self.assertEqual(list(runs), ["gravity-00-9.81", "gravity-00-4.9"])
        self.assertEqual([len(r) for r in runs.values()], [2, 2])
        self.assertTrue(all(r.finished for rs in runs.values() for r in rs))
        # Variant 2, seed replicate 1, run alone by the command line.
        cli("run", scene("rod.yaml"), "-o", self.path("alone"), "--quiet", "--no-analyze", "--set", "process.duration=20 ms",
            "--set", "shot.count=64", "--set", "process.gravity=[0, 0, -4.9]", "--set", "process.seed=2")
        self.assertEqual(read_bytes(os.path.join(runs["gravity-00-4.9"][1].dir, "impacts.csv")), read_bytes(self.path("alone", "impacts.csv")))
        table = study.comparison
        self.assertEqual(table["variant"].tolist(), ["gravity-00-9.81", "gravity-00-4.9"])
        self.assertEqual(table["process.gravity"].tolist(), ["[0, 0, -9.81]", "[0, 0, -4.9]"])  # quoted values stay text
        self.assertEqual(table["runs_finished"].tolist(), [2, 2])
        rates = [np.mean([r.figures["components"][0]["impact_rate_per_s"] for r in rs]) for rs in runs.values()]
        np.testing.assert_allclose(table["impact_rate_per_s"], rates, rtol=1e-5)
        self.assertEqual(table["impact_rate_per_s"].dtype, np.float64)  # whole numbers here, a float column still
        self.assertTrue((table["impact_rate_per_s_ci95"] >= 0).all())
        self.assertIn("baseline `gravity-00-9.81`", study.report)
        with open(study.report_html, encoding="utf-8") as f:
            self.assertIn("<h2>The variants in 3D</h2>", f.read())

    def test_a_dict_scene_is_swept_from_its_resolved_file_and_a_rerun_skips_finished_runs(self):
        d = peensim.Scene(scene("rod.yaml")).to_dict()
        d["process"]["duration"] = "20 ms"
        d["shot"]["count"] = 64
        rod = peensim.Scene.from_dict(d, base_dir=os.path.join(SOURCE_DIR, "scenes"), name="rod-dict")
        study, _ = self.sweep(rod, self.path("study"), vary={"shot.count": [32, 64]}, jobs=2)
        self.assertEqual(list(study.runs), ["count-32", "count-64"])
        with open(self.path("study", "sweep", "scene.yaml")) as f:
            self.assertEqual(f.read(), rod.resolved_yaml())
        cli("run", scene("rod.yaml"), "-o", self.path("alone"), "--quiet", "--no-analyze", "--set", "process.duration=20 ms",
            "--set", "shot.count=32")
        self.assertEqual(read_bytes(self.path("study", "count-32", "s0", "impacts.csv")), read_bytes(self.path("alone", "impacts.csv")))
        written = os.path.getmtime(self.path("study", "count-32", "s0", "impacts.csv"))
        _, printed = self.sweep(rod, self.path("study"), vary={"shot.count": [32, 64]}, jobs=2)
        self.assertIn("2 finished before", printed)
        self.assertEqual(os.path.getmtime(self.path("study", "count-32", "s0", "impacts.csv")), written)

    def test_bad_input_is_raised_before_anything_runs(self):
        rod = peensim.Scene(scene("rod.yaml")).set(ROD_SHORT)
        with self.assertRaises(peensim.InputError) as caught:
            self.sweep(rod, self.path("bad"), vary={"shot.count": [64, -1]})
        self.assertEqual(caught.exception.field, "shot.count")
        self.assertFalse(os.path.exists(self.path("bad", "count-64")))
        with self.assertRaises(ValueError):
            self.sweep(rod, self.path("bad"), vary={"shot.count": "64"})
        with self.assertRaises(peensim.InputError):
            self.sweep(rod, self.path("bad"), vary={"shot.count": [64]}, baseline="nobody")
        with self.assertRaises(FileNotFoundError):
            peensim.Sweep(self.path("nothing"))


if __name__ == "__main__":
    unittest.main()
