"""The user guide's worked example (docs/user-guide.md, section "Python API"; it was the README's) runs
as written: a fresh directory with the shipped scenes and assets, the example's code exactly, its
plot checked."""

import os
import re
import subprocess
import sys
import unittest

from support import SOURCE_DIR, TempDirTest


GUIDE = os.path.join("docs", "user-guide.md")


def readme_example():
    with open(os.path.join(SOURCE_DIR, GUIDE), encoding="utf-8") as f:
        guide = f.read()
    found = re.search(r"<!-- python-example:begin -->\s*```python\n(.*?)```\s*<!-- python-example:end -->", guide, re.S)
    if not found:
        raise AssertionError(GUIDE + " lacks the python-example markers around a ```python block")
    return found.group(1)


class ReadmeExampleTest(TempDirTest):
    def test_the_worked_example_runs_and_draws_its_plot(self):
        code = readme_example()
        for folder in ("scenes", "assets"):
            os.symlink(os.path.join(SOURCE_DIR, folder), self.path(folder))
        done = subprocess.run([sys.executable, "-c", code], cwd=self.tmp, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=600)
        self.assertEqual(done.returncode, 0, done.stdout)
        self.assertIn("impacts, mean normal speed", done.stdout)
        plots = re.findall(r'plt\.savefig\("([^"]+)"', code)
        self.assertEqual(len(plots), 1)
        with open(self.path(plots[0]), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
