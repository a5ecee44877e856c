#!/usr/bin/env python3
"""check_test_folders.py on small made-up repositories: suites in folders that mirror src/ (a
subfolder too), contact/ and tests/support/ pass; a suite at the top of tests/, in a folder that
mirrors nothing, or in a subfolder that src/ lacks fails with the file named."""
import os
import subprocess
import sys
import tempfile
import unittest

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_test_folders.py")
# The source folders of the made-up repository.
SOURCES = ["src/engine/a.cpp", "src/app/sweep/s.cpp", "contact/law.cpp"]


def check(test_files):
    d = tempfile.mkdtemp()
    for path in SOURCES + test_files:
        os.makedirs(os.path.dirname(os.path.join(d, path)), exist_ok=True)
        with open(os.path.join(d, path), "w") as f:
            f.write("// x\n")
    r = subprocess.run([sys.executable, CHECK, d], capture_output=True, text=True)
    return r.returncode, r.stdout


class CheckTestFolders(unittest.TestCase):
    def test_mirroring_folders_pass(self):
        code, out = check(["tests/engine/bounce_test.cpp", "tests/app/sweep/sweep_test.cpp", "tests/app/x_test.cpp",
                           "tests/contact/laws_test.cpp", "tests/support/reference_test.cpp", "tests/support/helper.cpp",
                           "tests/bench/bench_main.cpp"])
        self.assertEqual(code, 0, out)
        self.assertIn("5 test file(s) checked; 0 outside", out)

    def test_a_suite_at_the_top_of_tests_fails(self):
        code, out = check(["tests/engine/bounce_test.cpp", "tests/engine_rest_test.cpp"])
        self.assertEqual(code, 1)
        self.assertIn("tests/engine_rest_test.cpp: lies at the top of tests/", out)
        self.assertNotIn("bounce_test.cpp:", out)

    def test_a_folder_that_mirrors_nothing_fails(self):
        code, out = check(["tests/event/roots_test.cpp", "tests/bench/speed_test.cpp"])
        self.assertEqual(code, 1)
        self.assertIn("tests/event/roots_test.cpp: lies in tests/event/, which mirrors no folder of src/ or contact/", out)
        self.assertIn("tests/bench/speed_test.cpp: lies in tests/bench/", out)
        self.assertIn("2 outside", out)

    def test_a_subfolder_src_lacks_fails(self):
        code, out = check(["tests/app/run/run_test.cpp", "tests/contact/soft/x_test.cpp"])
        self.assertEqual(code, 1)
        self.assertIn("tests/app/run/run_test.cpp: lies in tests/app/run/", out)
        self.assertIn("tests/contact/soft/x_test.cpp: lies in tests/contact/soft/", out)


if __name__ == "__main__":
    unittest.main()
