"""Hostile inputs through the Python API (issue 29): the command line's limits and messages, by the
same code: values nested deeper than the one nesting limit (refused at once, not a crash), whole
numbers beyond 64 bits (refused, and kept exact when read back), sweep seeds and duplicate values.
Each case asserts the exception, its fields and the phrases the command line prints for it."""

import os
import time
import unittest

import peensim
from support import SOURCE_DIR, TempDirTest, cli, scene

NESTING = "maps and lists nested deeper than 64 levels; expected at most 64"
BEYOND_64_BITS = "(beyond 64 bits: at most 9223372036854775807 either side of 0)"
SCENES = os.path.join(SOURCE_DIR, "scenes")


def nested(levels, inner=1):
    """A value nested `levels` lists deep."""
    value = inner
    for _ in range(levels):
        value = [value]
    return value


class NestingTest(TempDirTest):
    def assert_refused_at_once(self, call):
        start = time.monotonic()
        with self.assertRaises(peensim.InputError) as caught:
            call()
        self.assertLess(time.monotonic() - start, 5.0)
        self.assertIn(NESTING, str(caught.exception))
        return caught.exception

    def test_from_dict_20000_levels_deep_is_refused_as_the_command_line_refuses_the_file(self):
        d = peensim.Scene(scene("rod.yaml")).to_dict()
        d["name"] = nested(20000)
        e = self.assert_refused_at_once(lambda: peensim.Scene.from_dict(d, base_dir=SCENES, name="deep"))
        self.assertEqual(e.file, os.path.join(SCENES, "deep"))
        self.assertTrue(e.field.startswith("name[0][0]"))
        # The command line reads the same nesting as a file: the same words.
        with open(self.path("deep.yaml"), "w") as f:
            f.write("name: " + "[" * 20000 + "1" + "]" * 20000 + "\n")
        code, printed = cli("check", self.path("deep.yaml"), check=False)
        self.assertEqual(code, 2)
        self.assertIn(NESTING, printed)

    def test_the_limit_itself_is_the_command_lines(self):
        # 64 levels are read (and then refused by the scene's checks: `name` takes text), 65 are not.
        d = peensim.Scene(scene("rod.yaml")).to_dict()
        d["name"] = nested(63)  # the scene's own map is the first level
        with self.assertRaises(peensim.InputError) as caught:
            peensim.Scene.from_dict(d, base_dir=SCENES, name="deep").check()
        self.assertNotIn(NESTING, str(caught.exception))
        self.assertEqual(caught.exception.field, "name")
        d["name"] = nested(64)
        self.assert_refused_at_once(lambda: peensim.Scene.from_dict(d, base_dir=SCENES, name="deep"))
        code, printed = cli("check", scene("rod.yaml"), "--set", "name=" + "[" * 64 + "1" + "]" * 64, check=False)
        self.assertEqual(code, 2)
        self.assertNotIn(NESTING, printed)
        code, printed = cli("check", scene("rod.yaml"), "--set", "name=" + "[" * 65 + "1" + "]" * 65, check=False)
        self.assertEqual(code, 2)
        self.assertIn(NESTING, printed)

    def test_set_20000_levels_deep_is_refused_naming_the_override(self):
        e = self.assert_refused_at_once(lambda: peensim.Scene(scene("rod.yaml")).set("process.gravity", nested(20000)))
        self.assertEqual(e.file, "<--set>")
        self.assertTrue(e.field.startswith("process.gravity[0][0]"))  # the path down to the level too many
        code, printed = cli("check", scene("rod.yaml"), "--set", "process.gravity=" + "[" * 20000 + "1" + "]" * 20000, check=False)
        self.assertEqual(code, 2)
        self.assertIn("<--set>: process.gravity: the value is not valid YAML: " + NESTING, printed)

    def test_a_dict_holding_itself_is_refused(self):
        d = {"process": {}}
        d["process"]["loop"] = d
        self.assert_refused_at_once(lambda: peensim.Scene.from_dict(d))

    def test_yaml_text_20000_levels_deep_is_refused(self):
        text = "name: " + "[" * 20000 + "1" + "]" * 20000 + "\n"
        s = peensim.Scene.from_yaml(text, base_dir=SCENES, name="deep")
        self.assert_refused_at_once(s.check)
        self.assert_refused_at_once(s.to_dict)


class WholeNumberTest(TempDirTest):
    def test_a_seed_or_count_of_10_to_the_30_is_refused_as_on_the_command_line(self):
        for path in ("process.seed", "shot.count"):
            with self.assertRaises(peensim.InputError) as caught:
                peensim.Scene(scene("rod.yaml")).set(path, 10**30).check()
            e = caught.exception
            self.assertEqual((e.file, e.field), ("<--set>", path))
            self.assertIn("expected a whole number", e.problem)
            code, printed = cli("check", scene("rod.yaml"), "--set", f"{path}={10**30}", check=False)
            self.assertEqual(code, 2)
            self.assertIn(str(e), printed)
        with self.assertRaises(peensim.InputError) as caught:
            peensim.Scene(scene("rod.yaml")).set("process.seed", 10**30).check()
        self.assertIn(BEYOND_64_BITS, caught.exception.problem)

    def test_a_dict_keeps_a_big_whole_number_exact(self):
        d = peensim.Scene(scene("rod.yaml")).to_dict()
        d["process"]["seed"] = 10**30
        s = peensim.Scene.from_dict(d, base_dir=SCENES, name="big-seed")
        self.assertEqual(s.to_dict()["process"]["seed"], 10**30)  # an int, not 1e+30
        self.assertIsInstance(s.to_dict()["process"]["seed"], int)
        with self.assertRaises(peensim.InputError) as caught:
            s.check()
        self.assertIn("got '1000000000000000000000000000000' " + BEYOND_64_BITS, caught.exception.problem)


class SweepRulesTest(TempDirTest):
    def test_seeds_0_is_refused_with_the_command_lines_message(self):
        code, printed = cli("sweep", scene("rod.yaml"), "-o", self.path("cli"), "--seeds", "0", check=False)
        self.assertEqual(code, 2)
        for seeds in (0, -1, 1001, 10**30, 2.0):
            with self.assertRaises(peensim.InputError) as caught:
                peensim.sweep(scene("rod.yaml"), self.path("py"), seeds=seeds)
            self.assertEqual(caught.exception.file, "--seeds")
            self.assertIn("expected 1 to 1000 replicates per variant, got ", str(caught.exception))
            if seeds == 0:
                self.assertIn(str(caught.exception), printed)
        self.assertFalse(os.path.exists(self.path("py", "base")))

    def test_a_value_twice_is_refused(self):
        for values, said in (([1, 1], "the value '1' is given twice"), (["1 mm", "0.001 m"], "'0.001 m' is the value '1 mm' again")):
            path = "process.seed" if values[0] == 1 else "shot.diameter"
            with self.assertRaises(peensim.InputError) as caught:
                peensim.sweep(scene("rod.yaml"), self.path("py"), vary={path: values})
            self.assertEqual((caught.exception.file, caught.exception.field), ("--vary", path))
            self.assertIn(said, caught.exception.problem)
            code, printed = cli("sweep", scene("rod.yaml"), "-o", self.path("cli"), "--vary", f"{path}=" + ",".join(map(str, values)),
                                check=False)
            self.assertEqual(code, 2)
            self.assertIn(str(caught.exception), printed)

    def test_too_many_values_are_refused_at_once(self):
        start = time.monotonic()
        with self.assertRaises(peensim.InputError) as caught:
            peensim.sweep(scene("rod.yaml"), self.path("py"), vary={"process.seed": list(range(1, 20001))})
        self.assertLess(time.monotonic() - start, 5.0)
        self.assertIn("20000 values; expected at most 1000 values per --vary", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
