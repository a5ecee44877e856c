#!/usr/bin/env python3
"""check_hand_stepping.py on small made-up repositories: tests that drive the engine through the run
loop pass; a test that calls sim.step( or sim->step( outside the allow-list fails with the file
and line named; a call in a comment is not one; an allowed file that no longer steps by hand fails."""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "check_hand_stepping.py")
sys.path.insert(0, HERE)
import check_hand_stepping  # noqa: E402  (for its allow-list)

LOOP = "    run_through_loop(sim, {.after_step = [&](const Simulation&, const std::vector<ImpactRecord>& impacts) {}});\n"
BY_HAND = "    while (!sim.finished()) sim.step(impacts);\n"


def check(files):
    """Exit code and output of the check on a repository with `files` ({path: text}) and every
    allowed file stepping by hand (as the real ones do), unless `files` says otherwise."""
    d = tempfile.mkdtemp()
    contents = {path: BY_HAND for path in check_hand_stepping.ALLOWED}
    contents.update(files)
    for path, text in contents.items():
        os.makedirs(os.path.dirname(os.path.join(d, path)), exist_ok=True)
        with open(os.path.join(d, path), "w") as f:
            f.write(text)
    r = subprocess.run([sys.executable, CHECK, d], capture_output=True, text=True)
    return r.returncode, r.stdout


class CheckHandStepping(unittest.TestCase):
    def test_tests_through_the_run_loop_pass(self):
        code, out = check({"tests/engine/bounce_test.cpp": LOOP, "tests/support/run_through_loop.h": "    return loop.run();\n"})
        self.assertEqual(code, 0, out)
        self.assertIn(f"{len(check_hand_stepping.ALLOWED)} test file(s) step by hand", out)
        self.assertIn("0 finding(s)", out)

    def test_a_hand_loop_outside_the_list_fails_with_file_and_line(self):
        code, out = check({"tests/engine/bounce_test.cpp": "// drop\n" + LOOP + BY_HAND,
                           "tests/kernels/jet_test.cpp": "    g.sim->step(impacts);\n"})
        self.assertEqual(code, 1)
        self.assertIn("tests/engine/bounce_test.cpp:3: steps a Simulation by hand (line(s) 3)", out)
        self.assertIn("tests/kernels/jet_test.cpp:1: steps a Simulation by hand", out)
        self.assertIn("run_through_loop", out)
        self.assertIn("2 finding(s)", out)

    def test_a_step_in_a_comment_is_not_a_call(self):
        code, out = check({"tests/engine/a_test.cpp": "// sim.step(impacts) by hand would drift\n/* sim.step(x);\n sim.step(y); */\n" + LOOP})
        self.assertEqual(code, 0, out)

    def test_an_allowed_file_that_no_longer_steps_by_hand_fails(self):
        stale = sorted(check_hand_stepping.ALLOWED)[0]
        code, out = check({stale: LOOP})
        self.assertEqual(code, 1)
        self.assertIn(f"{stale}: listed in ALLOWED but steps nothing by hand", out)


if __name__ == "__main__":
    unittest.main()
