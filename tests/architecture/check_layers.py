#!/usr/bin/env python3
"""The folders are the architecture (docs/contributing.md, "Layout"): each folder of src/ and contact/
may include only the folders its row of that document's dependency table lists (common/ always), and
no folders may include each other in a cycle. Reads the table from docs/contributing.md and the
`#include "..."` lines of every source file; prints each offending include with its file and line,
and exits 1 on any.

    tests/architecture/check_layers.py [REPO]

A subfolder (engine/event/) belongs to its top folder's row; cycles are checked between subfolders
too, and none is allowed (the last one, engine <-> engine/event <-> engine/soft, went when the soft
scheme left the event scheme). Standard library only.
"""
import os
import re
import sys


INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')

# The document that holds the dependency table, relative to the repository.
TABLE_DOCUMENT = "docs/contributing.md"


def read_table(document):
    """{folder: set of folders it may include} from the contributor guide's dependency block."""
    text = open(document, encoding="utf-8").read()
    start = text.index("    folder       depends on (besides common/)\n")
    rows, order = {}, []
    for line in text[start:].splitlines()[1:]:
        if not line.startswith("    ") or not line.strip():
            break
        names_part, deps_part = re.split(r"\s{2,}", line.strip(), maxsplit=1)
        deps_part = re.sub(r"\(.*?\)", "", deps_part).strip()
        names = [n.strip() for n in names_part.split(",")]
        if deps_part == "-":
            deps = set()
        elif deps_part.endswith("and below"):
            top = deps_part[: -len("and below")].strip()
            deps = set(order[: order.index(top) + 1])
        else:
            deps = {d.strip() for d in deps_part.split(",")}
        for n in names:
            rows[n] = deps
            order.append(n)
    return rows


def folder_of(repo_path):
    parts = repo_path.split("/")
    return "contact" if parts[0] == "contact" else "/".join(parts[1:-1])


def target_folder(include):
    return "contact" if include.startswith("contact/") else os.path.dirname(include)


def includes(repo):
    """(from folder, to folder, file, line number) of every include between folders."""
    for root in ("src", "contact"):
        for dirpath, _, files in os.walk(os.path.join(repo, root)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, repo)
                here = folder_of(rel)
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m:
                            there = target_folder(m.group(1))
                            if there and there != here:
                                yield here, there, rel, number


def cycles(edges):
    """The strongly connected components with more than one folder (Tarjan), each sorted."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []
    nodes = sorted(set(edges) | {b for bs in edges.values() for b in bs})

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(tuple(sorted(component)))

    for v in nodes:
        if v not in index:
            visit(v)
    return sorted(out)


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    table = read_table(os.path.join(repo, TABLE_DOCUMENT))
    problems, edges = [], {}
    for here, there, rel, number in includes(repo):
        edges.setdefault(here, set()).add(there)
        top_here, top_there = here.split("/")[0], there.split("/")[0]
        if top_there in ("common", top_here):
            continue
        if top_here not in table:
            problems.append(f"{rel}:{number}: folder '{top_here}' has no row in {TABLE_DOCUMENT}'s dependency table")
        elif top_there not in table[top_here]:
            problems.append(f"{rel}:{number}: '{top_here}' includes '{there}', which its row in {TABLE_DOCUMENT}'s table does not list "
                            f"(it lists: {', '.join(sorted(table[top_here])) or 'nothing'})")
    for c in cycles(edges):
        problems.append("a cycle of folders including each other: " + " <-> ".join(c))
    for p in problems:
        print(p)
    print(f"{sum(len(v) for v in edges.values())} folder edges checked against {len(table)} table rows; "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
