#!/usr/bin/env python3
"""The tests mirror the source folders (docs/contributing.md, "Layout"): every GoogleTest file (*_test.cpp) under
tests/ lies in the folder that mirrors a folder of src/ or contact/ (tests/engine/ for src/engine/,
tests/app/sweep/ for src/app/sweep/, tests/contact/ for contact/), or in tests/support/ beside the
support code it tests. Prints each file that lies elsewhere (at the top of tests/ too) and exits 1
on any, so that a newcomer finds the tests of a folder in one place. Standard library only.

    tests/architecture/check_test_folders.py [REPO]
"""
import os
import sys

# Folders of tests/ that mirror no source folder but may hold suites: the support code's own tests.
NON_SOURCE_FOLDERS = ("support",)


def mirrored(repo, folder):
    """Whether tests/<folder> has a counterpart: src/<folder>, contact/ (and below), or a non-source folder."""
    if not folder:
        return False
    top = folder.split("/")[0]
    if top in NON_SOURCE_FOLDERS:
        return True
    if top == "contact":
        return os.path.isdir(os.path.join(repo, folder))
    return os.path.isdir(os.path.join(repo, "src", folder))


def test_files(repo):
    """(path relative to the repository, folder relative to tests/) of every *_test.cpp under tests/."""
    tests = os.path.join(repo, "tests")
    for dirpath, dirnames, files in os.walk(tests):
        dirnames.sort()
        for name in sorted(files):
            if name.endswith("_test.cpp"):
                path = os.path.join(dirpath, name)
                folder = os.path.relpath(dirpath, tests)
                yield os.path.relpath(path, repo), ("" if folder == "." else folder.replace(os.sep, "/"))


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    problems, count = [], 0
    for rel, folder in test_files(repo):
        count += 1
        if mirrored(repo, folder):
            continue
        where = "at the top of tests/" if not folder else f"in tests/{folder}/, which mirrors no folder of src/ or contact/"
        problems.append(f"{rel}: lies {where}: move it to the tests/ folder that mirrors the code it tests "
                        f"(tests/engine/ for src/engine/, tests/contact/ for contact/; support code's tests: tests/support/)")
    for p in problems:
        print(p)
    print(f"{count} test file(s) checked; {len(problems)} outside a folder that mirrors src/ or contact/")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
