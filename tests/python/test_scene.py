"""peensim.Scene: files and dicts, overrides as --set, checks, bad input as InputError with file,
line and field, the resolved scene."""

import contextlib
import io
import os
import unittest

import numpy as np

import peensim
from support import SOURCE_DIR, TempDirTest, cli, read_bytes, scene


class SceneTest(TempDirTest):
    def test_a_file_scene_checks_as_the_command_does(self):
        report = peensim.Scene(scene("gear.yaml")).check()
        self.assertEqual(report.warnings, 0)
        _, printed = cli("check", scene("gear.yaml"))
        self.assertEqual(report.text, printed)

    def test_overrides_are_set_strings_in_order(self):
        s = peensim.Scene(scene("gear.yaml")).set("process.duration", "0.2 s").set({"shot.count": 100, "process.gravity": [0, 0, -9.8]})
        s.set("shot.diameter=1.5 mm")
        self.assertEqual(s.overrides, ["process.duration=0.2 s", "shot.count=100", "process.gravity=[0, 0, -9.8]", "shot.diameter=1.5 mm"])
        resolved = s.resolved()
        self.assertEqual(resolved["process"]["duration"], 0.2)
        self.assertEqual(resolved["shot"]["count"], 100)
        self.assertEqual(resolved["shot"]["diameter"], 0.0015)
        self.assertEqual(resolved["process"]["gravity"], [0, 0, -9.8])
        # NumPy values are numbers too; a copy keeps its own overrides.
        t = s.copy().set("shot.count", np.int64(7)).set("process.duration", np.float64(0.25))
        self.assertEqual(t.overrides[-2:], ["shot.count=7", "process.duration=0.25"])
        self.assertEqual(len(s.overrides), 4)

    def test_to_dict_keeps_the_units_and_the_file_is_unchanged(self):
        d = peensim.Scene(scene("gear.yaml")).to_dict()
        self.assertEqual(d["shot"], {"count": 140, "diameter": "2 mm", "material": "steel"})
        self.assertEqual(d["process"]["gravity"], [0, 0, -9.81])
        self.assertEqual(d["components"][0]["vibration"], {"amplitude": "25 um", "frequency": "20 kHz"})

    def test_a_dict_scene_resolves_as_its_file(self):
        from_file = peensim.Scene(scene("rotating-gear.yaml"))
        from_dict = peensim.Scene.from_dict(from_file.to_dict(), base_dir=os.path.join(SOURCE_DIR, "scenes"), name="rotating-gear")
        self.assertEqual(from_dict.resolved_yaml(), from_file.resolved_yaml())
        self.assertTrue(from_dict.in_memory)
        self.assertIn("components:", from_dict.yaml_text)

    def test_bad_input_is_an_input_error_with_file_line_and_field(self):
        bad = os.path.join(SOURCE_DIR, "tests", "scenes_bad", "negative_diameter.yaml")
        with self.assertRaises(peensim.InputError) as caught:
            peensim.Scene(bad).check()
        e = caught.exception
        self.assertIsInstance(e, ValueError)
        self.assertEqual((e.file, e.line, e.column, e.field), (bad, 3, 29, "shot.diameter"))
        self.assertIn("expected a length", e.problem)
        self.assertEqual(str(e), f"{bad}:3:29: shot.diameter: {e.problem}")

    def test_a_bad_override_names_the_field(self):
        with self.assertRaises(peensim.InputError) as caught:
            peensim.Scene(scene("gear.yaml")).set("shot.count", -3).check()
        e = caught.exception
        self.assertEqual((e.file, e.line, e.field), ("<--set>", None, "shot.count"))
        self.assertIn("expected a whole number", e.problem)
        with self.assertRaises(peensim.InputError) as caught:
            peensim.Scene(scene("gear.yaml")).set("shot.colour", "red").check()
        self.assertIn("shot.colour", str(caught.exception))

    def test_a_bad_dict_value_points_at_its_line_in_the_yaml(self):
        d = peensim.Scene(scene("gear.yaml")).to_dict()
        d["shot"]["diameter"] = "-2 mm"
        s = peensim.Scene.from_dict(d, base_dir=os.path.join(SOURCE_DIR, "scenes"), name="bad-gear")
        with self.assertRaises(peensim.InputError) as caught:
            s.check()
        e = caught.exception
        self.assertEqual(e.file, os.path.join(SOURCE_DIR, "scenes", "bad-gear"))
        self.assertEqual(e.field, "shot.diameter")
        self.assertIn("-2 mm", s.yaml_text.splitlines()[e.line - 1])

    def test_values_without_a_yaml_form_are_refused(self):
        with self.assertRaises(TypeError) as caught:
            peensim.Scene.from_dict({"process": {"duration": object()}})
        self.assertIn("process.duration", str(caught.exception))
        with self.assertRaises(TypeError):
            peensim.Scene.from_dict({"process": {"duration": float("nan")}})
        with self.assertRaises(ValueError):
            peensim.Scene(scene("gear.yaml")).set("shot.count")

    def test_setup_warnings_reach_sys_stderr_and_strict_makes_them_errors(self):
        s = peensim.Scene(scene("gear.yaml")).set("components[sonotrode].vibration.amplitude", 25)  # 25 m: meant 25 um
        printed = io.StringIO()
        with contextlib.redirect_stderr(printed):
            report = s.check()
        self.assertEqual(report.warnings, 2)
        self.assertIn("did you mean 25 um?", printed.getvalue())
        self.assertEqual(printed.getvalue().count("warning: "), 2)
        with self.assertRaises(peensim.InputError) as caught, contextlib.redirect_stderr(io.StringIO()):
            s.check(strict=True)
        self.assertEqual(caught.exception.field, "components[0].vibration.amplitude")

    def test_the_check_draws_the_assembly(self):
        png = self.path("gear.png")
        peensim.Scene(scene("gear.yaml")).check(picture=png)
        self.assertEqual(read_bytes(png)[:8], b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
