#!/usr/bin/env python3
"""The tests drive the engine through the run loop (docs/contributing.md, "Tests"; engine/run_loop.h): a test that
steps a Simulation by hand (`sim.step(...)`, `sim->step(...)`) runs a second run loop that can drift
from the one `run` and `bench` use (the pauses listeners ask for, the end at a restart point, the
hooks). tests/support/run_through_loop.h gives a test its hooks instead. Grep-level: every call of a
method named step in a C++ file under tests/ (comments left out) is flagged, unless the file is in
ALLOWED below with the reason it steps by hand; an allowed file that no longer steps by hand is
flagged too, so the list stays true. Prints each finding and exits 1 on any. Standard library only.

    tests/architecture/check_hand_stepping.py [REPO]
"""
import os
import re
import sys

# Files that step a Simulation by hand, each with its reason (paths relative to the repository).
ALLOWED = {
    "tests/engine/run_loop_test.cpp": "steps by hand as the reference the run loop is compared with",
    "tests/engine/edit_state_test.cpp": "tests a step from a state edited mid-run; RunLoop ends only at restart points",
    "tests/engine/contact_state_test.cpp": "edits the state mid-run (lifts the shot at 0.35 s); RunLoop ends only at restart points",
    "tests/scene/scenes_test.cpp": "runs exactly 200 units of work of each shipped scene's scheme; RunLoop stops only at restart points",
}

# A call of a method named step: `x.step(` or `x->step(` (Simulation::step; a kernel's own step
# function would be listed in ALLOWED with its reason).
CALL = re.compile(r"(\.|->)\s*step\s*\(")


def code_lines(path):
    """(line number, text without its // comment) of a C++ file; block comments are left out too."""
    in_block = False
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            text = ""
            rest = line
            while rest:
                if in_block:
                    end = rest.find("*/")
                    if end < 0:
                        rest = ""
                    else:
                        in_block, rest = False, rest[end + 2:]
                    continue
                start_line, start_block = rest.find("//"), rest.find("/*")
                if start_line >= 0 and (start_block < 0 or start_line < start_block):
                    text += rest[:start_line]
                    rest = ""
                elif start_block >= 0:
                    text += rest[:start_block]
                    in_block, rest = True, rest[start_block + 2:]
                else:
                    text += rest
                    rest = ""
            yield number, text


def hand_steps(repo):
    """{path relative to the repository: [line numbers]} of every C++ file under tests/ that calls step."""
    found = {}
    tests = os.path.join(repo, "tests")
    for dirpath, dirnames, files in os.walk(tests):
        dirnames.sort()
        for name in sorted(files):
            if not name.endswith((".cpp", ".h")):
                continue
            path = os.path.join(dirpath, name)
            lines = [n for n, text in code_lines(path) if CALL.search(text)]
            if lines:
                found[os.path.relpath(path, repo).replace(os.sep, "/")] = lines
    return found


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    found = hand_steps(repo)
    problems = []
    for rel, lines in sorted(found.items()):
        if rel not in ALLOWED:
            where = ", ".join(str(n) for n in lines)
            problems.append(f"{rel}:{lines[0]}: steps a Simulation by hand (line(s) {where}): drive it through the run loop "
                            f"(tests/support/run_through_loop.h: run_through_loop with LoopHooks), or add the file to ALLOWED in "
                            f"tests/architecture/check_hand_stepping.py with the reason it must step by hand")
    for rel in sorted(ALLOWED):
        if rel not in found:
            problems.append(f"{rel}: listed in ALLOWED but steps nothing by hand (any more): remove it from the list")
    for p in problems:
        print(p)
    print(f"{len(found)} test file(s) step by hand, {len(ALLOWED)} allowed; {len(problems)} finding(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
