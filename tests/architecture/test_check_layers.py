#!/usr/bin/env python3
"""check_layers.py on small made-up repositories: an include the table lists passes; an unlisted
one, a folder without a row and a cycle (also between subfolders) each fail with the file, line
and folders named."""
import os
import subprocess
import sys
import tempfile
import unittest

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_layers.py")
TABLE = """# x

    folder       depends on (besides common/)
    kernels      -
    geometry     -
    engine       kernels, geometry   (engine/soft/ beside engine/event/)
    app          engine, kernels
    cli          app and below

"""


def repo(files):
    d = tempfile.mkdtemp()
    os.makedirs(os.path.join(d, "docs"))
    with open(os.path.join(d, "docs", "contributing.md"), "w") as f:
        f.write(TABLE)
    for path, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(d, path)), exist_ok=True)
        with open(os.path.join(d, path), "w") as f:
            f.write(text)
    return d


# Schemes above the engine's base, as in the real tree (engine/stepper.h declares the factory that
# engine/schemes/ defines): no cycle.
KNOWN = {"src/engine/a.h": '#include "kernels/k.h"\n', "src/engine/event/b.h": '#include "engine/a.h"\n',
         "src/engine/soft/c.h": '#include "engine/event/b.h"\n',
         "src/engine/schemes/f.cpp": '#include "engine/soft/c.h"\n#include "engine/event/b.h"\n#include "engine/a.h"\n'}


def check(files):
    r = subprocess.run([sys.executable, CHECK, repo(files)], capture_output=True, text=True)
    return r.returncode, r.stdout


class CheckLayers(unittest.TestCase):
    def test_listed_includes_pass(self):
        code, out = check({**KNOWN, "src/app/x.cpp": '#include "engine/a.h"\n#include "common/v.h"\n',
                           "src/cli/m.cpp": '#include "app/x.h"\n#include "geometry/g.h"\n'})
        self.assertEqual(code, 0, out)
        self.assertIn("0 problem(s)", out)

    def test_an_unlisted_include_fails_naming_file_line_and_folders(self):
        code, out = check({**KNOWN, "src/geometry/g.cpp": '// g\n#include "kernels/k.h"\n'})
        self.assertEqual(code, 1)
        self.assertIn("src/geometry/g.cpp:2: 'geometry' includes 'kernels', which its row in docs/contributing.md's table does not list", out)

    def test_a_folder_without_a_row_fails(self):
        code, out = check({**KNOWN, "src/extra/e.cpp": '#include "kernels/k.h"\n'})
        self.assertEqual(code, 1)
        self.assertIn("folder 'extra' has no row", out)

    def test_a_new_cycle_fails(self):
        code, out = check({**KNOWN, "src/app/x.h": '#include "cli/m.h"\n', "src/cli/m.h": '#include "app/x.h"\n'})
        self.assertEqual(code, 1)
        self.assertIn("a cycle of folders including each other: app <-> cli", out)

    def test_a_cycle_between_subfolders_fails(self):
        # The cycle the soft scheme once made inside the event scheme.
        code, out = check({**KNOWN, "src/engine/a.h": '#include "engine/event/b.h"\n'})
        self.assertEqual(code, 1)
        self.assertIn("a cycle of folders including each other: engine <-> engine/event", out)

if __name__ == "__main__":
    unittest.main()
