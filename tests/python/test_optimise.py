"""peensim.optimise and peensim.Optimisation: a study as a dict around a Scene, the winner and the
evaluations as data, its runs as Runs, a resumed call that runs nothing, bad input before
anything runs; a study file as the command line reads it."""

import contextlib
import io
import os
import unittest

import peensim
from support import TempDirTest, scene

ROD_SHORT = {"process.duration": "20 ms"}


class OptimiseTest(TempDirTest):
    def optimise(self, *args, **kwargs):
        with contextlib.redirect_stdout(io.StringIO()) as printed:
            result = peensim.optimise(*args, **kwargs)
        return result, printed.getvalue()

    def study(self, **extra):
        d = {"scene": peensim.Scene(scene("rod.yaml")).set(ROD_SHORT),
             "variables": {"count": {"path": "shot.count", "min": 32, "max": 160, "integer": True, "start": 64}},
             "objective": {"figure": "impact_rate_per_s", "goal": "maximise"},
             "runs": 6, "initial": 3, "confirm": 2}
        d.update(extra)
        return d

    def test_a_dict_study_finds_its_winner_and_a_rerun_runs_nothing(self):
        result, printed = self.optimise(self.study(), self.path("opt"), jobs=2)
        self.assertIn("optimise: round 0, 4 settings = 5 runs, 2 at once", printed)
        winner = result.winner
        self.assertEqual(winner["goal"], "maximise")
        self.assertEqual(list(winner["values"]), ["count"])
        self.assertTrue(winner["set"][0].startswith("shot.count="))
        self.assertIsNotNone(winner["confirmed"]["mean"])
        table = result.evaluations
        self.assertEqual(table["setting"][0], "start")
        self.assertEqual(int(table["runs"].sum()), 6)
        self.assertIn(table["count"].dtype.kind, "if")  # whole numbers: int64
        best = winner["setting"]
        self.assertIn(best, table["setting"].tolist())
        self.assertTrue(all(r.finished for r in result.runs(best)))
        self.assertEqual(len(result.runs("confirm-start")), 2)
        self.assertIn("## The winner: `" + best + "`", result.report)
        self.assertTrue(os.path.isfile(result.report_html))
        # The study the command read, kept beside the results; the Scene's overrides joined its set.
        with open(self.path("opt", "optimise", "study.yaml"), encoding="utf-8") as f:
            self.assertIn("process.duration=20 ms", f.read())
        again, printed = self.optimise(self.study(), self.path("opt"), jobs=2)
        self.assertNotIn("sweep: ", printed)  # no run's progress: none ran
        self.assertEqual(again.winner, winner)

    def test_bad_studies_raise_input_errors_before_anything_runs(self):
        bad = self.study(variables={"count": {"path": "shot.count", "min": 160, "max": 32}})
        with self.assertRaises(peensim.InputError) as caught:
            self.optimise(bad, self.path("bad"))
        self.assertEqual(caught.exception.field, "variables.count.max")
        self.assertIsNotNone(caught.exception.line)
        self.assertFalse(os.path.exists(self.path("bad", "start")))
        with self.assertRaises(peensim.InputError):
            self.optimise(self.study(objective="fastest"), self.path("bad2"))

    def test_a_study_file_is_read_as_the_command_line_reads_it(self):
        with open(self.path("study.yaml"), "w", encoding="utf-8") as f:
            f.write(f"scene: {scene('rod.yaml')}\nset: [\"process.duration=20 ms\"]\n"
                    "variables:\n  count: {path: shot.count, min: 32, max: 160, integer: true, start: 64}\n"
                    "objective: {figure: impact_rate_per_s, goal: maximise}\nruns: 4\ninitial: 2\nconfirm: 0\n")
        result, _ = self.optimise(self.path("study.yaml"), self.path("file"), runs=5, jobs=2)
        self.assertEqual(int(result.evaluations["runs"].sum()), 5)
        self.assertNotIn("confirmed", result.winner)


if __name__ == "__main__":
    unittest.main()
