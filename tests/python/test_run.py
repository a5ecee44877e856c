"""peensim.run and peensim.Run: a run from Python is the command line's run byte for byte; its
progress callback, stopping and resuming, Ctrl-C; the impact log and the analysis as NumPy arrays."""

import contextlib
import csv
import io
import os
import signal
import subprocess
import sys
import textwrap
import unittest

import numpy as np

import peensim
from support import SOURCE_DIR, TempDirTest, cli, read_bytes, scene


class RunTest(TempDirTest):
    def test_a_run_is_the_command_line_s_run(self):
        run = peensim.run(peensim.Scene(scene("rod.yaml")).set("process.duration", "0.3 s"), self.path("py"))
        cli("run", scene("rod.yaml"), "-o", self.path("cli"), "--set", "process.duration=0.3 s", "--quiet")
        self.assertTrue(run.finished)
        self.assertEqual(read_bytes(self.path("py", "impacts.csv")), read_bytes(self.path("cli", "impacts.csv")))
        self.assertEqual(read_bytes(self.path("py", "analysis", "rod_triangles.csv")), read_bytes(self.path("cli", "analysis", "rod_triangles.csv")))
        self.assertEqual(set(run.summary), set(peensim.Run(self.path("cli")).summary))
        self.assertEqual(run.summary["simulated_time_s"], 0.3)

    def test_replicas_are_the_command_line_s_replicas(self):
        # The rod, 4 s, as two replicas from Python and from the command line: the same bytes;
        # replicas below 1 are a ValueError.
        rod = peensim.Scene(scene("rod.yaml")).set("process.duration", "4 s")
        run = peensim.run(rod, self.path("py"), analyze=False, replicas=2)
        cli("run", scene("rod.yaml"), "-o", self.path("cli"), "--set", "process.duration=4 s", "--quiet", "--no-analyze", "--replicas", "2")
        self.assertEqual(len(run.summary["replicas"]["windows"]), 2)
        self.assertEqual(read_bytes(self.path("py", "impacts.csv")), read_bytes(self.path("cli", "impacts.csv")))
        with self.assertRaises(ValueError):
            peensim.run(rod, self.path("bad"), analyze=False, replicas=0)

    def test_a_dict_scene_runs_as_its_file(self):
        file_scene = peensim.Scene(scene("gear.yaml")).set("process.duration", "0.4 s")
        dict_scene = peensim.Scene.from_dict(file_scene.to_dict(), base_dir=os.path.join(SOURCE_DIR, "scenes"), name="gear-dict")
        dict_scene.set("process.duration", "0.4 s")
        a = peensim.run(file_scene, self.path("file"), analyze=False)
        b = peensim.run(dict_scene, self.path("dict"), analyze=False)
        self.assertEqual(read_bytes(os.path.join(a.dir, "impacts.csv")), read_bytes(os.path.join(b.dir, "impacts.csv")))

    def test_impacts_are_the_log_s_columns_exactly(self):
        run = peensim.run(peensim.Scene(scene("gear.yaml")).set("process.duration", "0.5 s"), self.path("gear"), analyze=False)
        impacts = run.impacts()
        with open(self.path("gear", "impacts.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        self.assertGreater(len(rows), 100)
        self.assertEqual(list(impacts), list(rows[0]))  # the file's names, in its order
        self.assertEqual(run.components, ["gear"])
        for name, values in impacts.items():
            self.assertEqual(values.shape, (len(rows),), name)
            if name == "component":
                self.assertEqual(values.dtype, np.int16)
                self.assertTrue(all(run.components[c] == r["component"] for c, r in zip(values, rows)))
            elif name in ("shot", "triangle"):
                self.assertEqual(values.dtype, np.int32)
                self.assertEqual(values.tolist(), [int(r[name]) for r in rows])
            else:
                self.assertEqual(values.dtype, np.float64)
                self.assertEqual(values.tolist(), [float(r[name]) for r in rows], name)  # shortest round trip: exact
        # The parser's buffer is the array's: owned through a capsule, not copied into NumPy.
        self.assertFalse(impacts["time_s"].flags["OWNDATA"])
        self.assertNotIsInstance(impacts["time_s"].base, np.ndarray)
        # A window of time and one component.
        window = run.impacts(component="gear", t_min=0.1, t_max=0.2)
        t = impacts["time_s"]
        self.assertEqual(window["time_s"].tolist(), t[(t >= 0.1) & (t <= 0.2)].tolist())
        with self.assertRaises(ValueError):
            run.impacts(component="chamber")

    def test_a_shot_mix_has_the_diameter_column(self):
        run = peensim.run(peensim.Scene(scene("nozzle-mix.yaml")).set("process.duration", "5 ms"), self.path("mix"), analyze=False)
        impacts = run.impacts()
        self.assertIn("shot_diameter_m", impacts)
        with open(self.path("mix", "impacts.csv"), newline="") as f:
            self.assertEqual(impacts["shot_diameter_m"].tolist(), [float(r["shot_diameter_m"]) for r in csv.DictReader(f)])

    def test_the_analysis_as_arrays(self):
        run = peensim.run(peensim.Scene(scene("gear.yaml")).set("process.duration", "0.5 s"), self.path("gear"))
        impacts = run.impacts()
        triangles = run.triangles()
        self.assertEqual(triangles["impacts"].dtype, np.int64)
        self.assertEqual(int(triangles["impacts"].sum()), len(impacts["time_s"]))
        self.assertEqual(len(triangles["triangle"]), 4960)
        self.assertTrue(np.isnan(triangles["mean_vn_mps"][triangles["impacts"] == 0]).all())
        regions = run.regions("gear")
        self.assertEqual(regions["region"].tolist(), [f"tooth-{k}" for k in range(20)] + ["bore"])
        self.assertEqual(regions["excluded"].tolist(), ["false"] * 20 + ["true"])
        self.assertEqual(int(regions["impacts"][:20].sum()), len(impacts["time_s"]))  # the teeth tile the gear; impacts by their points
        coverage = run.coverage()
        self.assertEqual(coverage["time_s"][-1], 0.5)
        figures = run.figures
        self.assertEqual(figures["components"][0]["impacts"], len(impacts["time_s"]))
        self.assertAlmostEqual(figures["components"][0]["coverage"], coverage["coverage"][-1], places=5)
        self.assertIn("# peensim analysis", run.report)
        with open(run.report_html, encoding="utf-8") as f:
            page = f.read()
        if os.path.isfile("/usr/share/javascript/three/three.min.js"):  # libjs-three: the main job's packages
            self.assertIn('<div class="pv" data-part="gear">', page)
        histograms = run.histograms()
        self.assertEqual(set(histograms["quantity"].tolist()), {"normal_speed", "impact_angle", "dent_diameter"})

    def test_analysis_on_demand(self):
        run = peensim.run(peensim.Scene(scene("rod.yaml")).set("process.duration", "0.2 s"), self.path("rod"), analyze=False)
        with self.assertRaises(FileNotFoundError) as caught:
            run.triangles()
        self.assertIn("run.analyze()", str(caught.exception))
        self.assertEqual(int(run.analyze().triangles()["impacts"].sum()), len(run.impacts()["time_s"]))
        self.assertEqual(peensim.analyze(run.dir).figures["components"][0]["impacts"], len(run.impacts()["time_s"]))
        # The maps' radius as --smoothing-radius takes it: metres or text with a unit; a bad one is an InputError.
        self.assertEqual(set(run.analyze(smoothing_radius=0.002).triangles()["smoothing_radius_mm"].tolist()), {2.0})
        self.assertEqual(set(run.analyze(smoothing_radius="1.5 mm").triangles()["smoothing_radius_mm"].tolist()), {1.5})
        with self.assertRaises(peensim.InputError) as bad:
            run.analyze(smoothing_radius="2 kg")
        self.assertIn("--smoothing-radius", str(bad.exception))
        with self.assertRaises(FileNotFoundError):
            peensim.Run(self.path("nothing"))

    def test_runs_share_the_geometry_cache_as_on_the_command_line(self):
        # Two runs of the rod with one geometry_cache: the first keeps the rod's coverage geometry,
        # the second reads it back and writes the analysis of the first; run.analyze takes it too.
        rod = peensim.Scene(scene("rod.yaml")).set("process.duration", "0.1 s")
        cache = self.path("cache")
        first = peensim.run(rod, self.path("a"), geometry_cache=cache)
        entries = [f for f in os.listdir(cache) if f.endswith(".bin")]
        self.assertEqual(len(entries), 1)
        kept = read_bytes(os.path.join(cache, entries[0]))
        second = peensim.run(rod, self.path("b"), geometry_cache=cache)
        self.assertEqual(read_bytes(os.path.join(first.dir, "analysis", "rod_triangles.csv")),
                         read_bytes(os.path.join(second.dir, "analysis", "rod_triangles.csv")))
        second.analyze(geometry_cache=cache)
        self.assertEqual(read_bytes(os.path.join(cache, entries[0])), kept)  # read, never rewritten
        self.assertEqual([f for f in os.listdir(cache) if f.endswith(".bin")], entries)

    def test_verbose_prints_the_summary(self):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            peensim.run(scene("rod.yaml"), self.path("rod"), verbose=True, analyze=False, scheme="step")
        self.assertIn("impacts", printed.getvalue())
        self.assertEqual(peensim.Run(self.path("rod")).summary["scheme"], "step")

    def test_progress_reaches_the_end(self):
        seen = []
        run = peensim.run(peensim.Scene(scene("gear.yaml")).set("process.duration", "2 s"), self.path("gear"), progress=seen.append,
                          analyze=False)
        self.assertGreaterEqual(len(seen), 2)  # at the start and at the end at least
        times = [p.time_s for p in seen]
        self.assertEqual(times, sorted(times))
        last = seen[-1]
        self.assertEqual((last.time_s, last.duration_s, last.fraction), (2.0, 2.0, 1.0))
        self.assertEqual(last.impacts, len(run.impacts()["time_s"]))
        self.assertGreater(last.wall_s, 0.0)

    def test_a_callback_returning_false_stops_and_resume_ends_with_the_same_bytes(self):
        s = peensim.Scene(scene("rod.yaml")).set("process.duration", "0.5 s")
        stopped = peensim.run(s, self.path("py"), progress=lambda p: False, analyze=False)
        self.assertFalse(stopped.finished)
        self.assertTrue(os.path.isfile(self.path("py", "checkpoint.bin")))
        self.assertLess(stopped.summary["simulated_time_s"], 0.5)
        done = peensim.run(s, self.path("py"), resume=True, analyze=False)
        self.assertTrue(done.finished)
        cli("run", scene("rod.yaml"), "-o", self.path("cli"), "--set", "process.duration=0.5 s", "--quiet", "--no-analyze")
        self.assertEqual(read_bytes(self.path("py", "impacts.csv")), read_bytes(self.path("cli", "impacts.csv")))

    def test_an_exception_in_the_callback_is_raised_once_the_run_has_checkpointed(self):
        s = peensim.Scene(scene("rod.yaml")).set("process.duration", "0.5 s")

        def fails(p):
            raise ZeroDivisionError("the callback's own error")

        with self.assertRaises(ZeroDivisionError), contextlib.redirect_stderr(io.StringIO()):
            peensim.run(s, self.path("py"), progress=fails, analyze=False)
        self.assertTrue(os.path.isfile(self.path("py", "checkpoint.bin")))
        self.assertTrue(peensim.run(s, self.path("py"), resume=True, analyze=False).finished)

    def test_ctrl_c_stops_the_run_at_a_checkpoint_and_raises_keyboard_interrupt(self):
        duration = "8 s"  # about a second of wall time: the interrupt comes long before the end
        child = textwrap.dedent(f"""
            import sys, peensim
            def started(p):
                if p.time_s == 0.0 or not getattr(started, "said", False):
                    started.said = True
                    print("running", flush=True)
            try:
                peensim.run(peensim.Scene({scene("gear.yaml")!r}).set("process.duration", {duration!r}), {self.path("py")!r},
                            progress=started, analyze=False)
                print("finished", flush=True)
            except KeyboardInterrupt:
                print("KeyboardInterrupt", flush=True)
        """)
        p = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=dict(os.environ))
        self.assertEqual(p.stdout.readline().strip(), "running")
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
        self.assertEqual(out.strip(), "KeyboardInterrupt", err)
        self.assertIn("interrupted at t = ", err)
        self.assertTrue(os.path.isfile(self.path("py", "checkpoint.bin")))
        s = peensim.Scene(scene("gear.yaml")).set("process.duration", duration)
        peensim.run(s, self.path("py"), resume=True, analyze=False)
        cli("run", scene("gear.yaml"), "-o", self.path("cli"), "--set", f"process.duration={duration}", "--quiet", "--no-analyze")
        self.assertEqual(read_bytes(self.path("py", "impacts.csv")), read_bytes(self.path("cli", "impacts.csv")))


if __name__ == "__main__":
    unittest.main()
