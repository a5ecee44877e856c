#!/usr/bin/env python3
"""check_doc_links.py on small made-up repositories: links and pictures that resolve pass (anchors as
GitHub makes them, a repeated heading's -1, a link that spans two lines, links in code left alone);
a missing file, a missing anchor and a picture path that lost its ../ each fail with the document,
line and target named."""
import os
import subprocess
import sys
import tempfile
import unittest

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_doc_links.py")

GUIDE = """# Guide

## Using `peensim run`: the basics

### Soft-sphere contacts (`accuracy.scheme: soft`)

## Notes

## Notes

See [the README](../README.md), [soft](#soft-sphere-contacts-accuracyscheme-soft), [again](#notes-1) and
"[Using peensim
run](#using-peensim-run-the-basics)". ![a picture](../assets/images/p.png)

    [not a link](nowhere.md) in a code block, and `[nor](this.md)` in a code span

```
[nor this](missing.md)
```
"""


def check(readme, guide=GUIDE):
    d = tempfile.mkdtemp()
    os.makedirs(os.path.join(d, "docs"))
    os.makedirs(os.path.join(d, "assets", "images"))
    with open(os.path.join(d, "assets", "images", "p.png"), "wb") as f:
        f.write(b"\x89PNG")
    with open(os.path.join(d, "README.md"), "w") as f:
        f.write(readme)
    with open(os.path.join(d, "docs", "guide.md"), "w") as f:
        f.write(guide)
    r = subprocess.run([sys.executable, CHECK, d], capture_output=True, text=True)
    return r.returncode, r.stdout


class CheckDocLinks(unittest.TestCase):
    def test_links_that_resolve_pass(self):
        code, out = check("# x\n\n[guide](docs/guide.md#using-peensim-run-the-basics), [web](https://example.org/a.md),\n"
                          "![p](assets/images/p.png)\n")
        self.assertEqual(code, 0, out)
        self.assertIn("7 relative links checked in 2 documents; 0 problem(s)", out)

    def test_a_missing_file_fails(self):
        code, out = check("# x\n\nSee [it](docs/gone.md).\n")
        self.assertEqual(code, 1)
        self.assertIn("README.md:3: 'docs/gone.md': no file docs/gone.md", out)

    def test_a_missing_anchor_fails(self):
        code, out = check("# x\n\n[guide](docs/guide.md#usage)\n")
        self.assertEqual(code, 1)
        self.assertIn("README.md:3: 'docs/guide.md#usage': no heading of docs/guide.md has the anchor '#usage'", out)

    def test_a_picture_moved_without_its_path_fails(self):
        code, out = check("# x\n", GUIDE.replace("../assets/images/p.png", "assets/images/p.png"))
        self.assertEqual(code, 1)
        self.assertIn("docs/guide.md:13: 'assets/images/p.png': no file docs/assets/images/p.png", out)


if __name__ == "__main__":
    unittest.main()
