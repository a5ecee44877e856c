#!/usr/bin/env python3
"""The documents' links resolve (README.md and docs/*.md, see docs/contributing.md, "Layout"): every
relative link and picture ([text](path), ![alt](path), with or without #anchor) names a file or
folder that exists, and every #anchor a heading of the document it points to (anchors as GitHub
makes them: lower case, punctuation dropped, spaces to hyphens, -1, -2 ... for repeats). Links in
code blocks and code spans are not links; http(s) and mailto links are not checked. Prints each
broken link with its file and line and exits 1 on any. Standard library only.

    tests/architecture/check_doc_links.py [REPO]
"""
import os
import re
import sys

LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\(([^()\s]*)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def documents(repo):
    """The Markdown files checked: README.md and every .md under docs/ (relative paths)."""
    found = ["README.md"] if os.path.isfile(os.path.join(repo, "README.md")) else []
    for dirpath, _, files in os.walk(os.path.join(repo, "docs")):
        for name in sorted(files):
            if name.endswith(".md"):
                found.append(os.path.relpath(os.path.join(dirpath, name), repo))
    return sorted(found)


def outside_fences(text):
    """(line number, line) of the lines outside fenced code blocks (``` or ~~~)."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.lstrip()
        if fence is None and (stripped.startswith("```") or stripped.startswith("~~~")):
            fence = stripped[:3]
            continue
        if fence is not None:
            if stripped.startswith(fence):
                fence = None
            continue
        yield number, line


def prose_lines(text):
    """(line number, line) outside code blocks, code spans blanked (same length). A fenced block is
    code; so is a line indented 4 spaces or more after a blank line or another such line (an
    indented block, also inside a list item)."""
    indented, previous_blank = False, True
    for number, line in outside_fences(text):
        stripped = line.lstrip()
        blank = not stripped
        indented = not blank and len(line) - len(stripped) >= 4 and (previous_blank or indented)
        previous_blank = blank if not indented else previous_blank
        if indented:
            continue
        yield number, re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), line)


def slug(heading):
    """GitHub's anchor of a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link keeps its text
    text = text.replace("`", "").lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(text):
    """Every anchor the document's headings give."""
    seen, out = {}, set()
    for _, line in outside_fences(text):
        m = HEADING.match(line)
        if not m:
            continue
        base = slug(m.group(2))
        n = seen.get(base, 0)
        seen[base] = n + 1
        out.add(base if n == 0 else f"{base}-{n}")
    return out


def links(text):
    """(line number, target) of every link and picture in the prose (a link may span lines)."""
    lines = list(prose_lines(text))
    joined = "\n".join(line for _, line in lines)
    numbers = [number for number, _ in lines]
    for m in LINK.finditer(joined):
        yield numbers[joined.count("\n", 0, m.start())], m.group(2)


def check(repo):
    problems, count = [], 0
    cache = {}

    def text_of(path):
        if path not in cache:
            with open(path, encoding="utf-8") as f:
                cache[path] = f.read()
        return cache[path]

    for doc in documents(repo):
        doc_path = os.path.join(repo, doc)
        for number, target in links(text_of(doc_path)):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or not target:
                continue  # http:, https:, mailto:
            count += 1
            path, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(doc_path), path)) if path else doc_path
            if not os.path.exists(resolved):
                problems.append(f"{doc}:{number}: '{target}': no file {os.path.relpath(resolved, repo)}")
                continue
            if anchor:
                if not resolved.endswith(".md") or os.path.isdir(resolved):
                    problems.append(f"{doc}:{number}: '{target}': an anchor into a file that is not Markdown")
                elif anchor not in anchors(text_of(resolved)):
                    problems.append(f"{doc}:{number}: '{target}': no heading of {os.path.relpath(resolved, repo)} has the anchor '#{anchor}'")
    return problems, count


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    problems, count = check(repo)
    for p in problems:
        print(p)
    print(f"{count} relative links checked in {len(documents(repo))} documents; {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
