#!/usr/bin/env python3
"""What the tessellation of a STEP part does to a run's results (docs/step-iges.md).

The rod scene (scenes/rod.yaml) with its rod a STEP solid of the same size (written by
build/peensim_write_step_rod: radius 5 mm, 30 mm along y centred on y = 0, axis 20 mm above the floor), run at
several chordal tolerances (the angular one at its loosest, 45 deg, so that the chordal one binds;
and once at the defaults, 0.01 mm and 5 deg) and seeds, beside the shipped STL rod (96 sides).
Per case: the rod's triangles (from `peensim check`), its volume deficit against the exact
cylinder (from the triangles' area, `figures.json`'s `area_m2`), and the means over the seeds of
the impacts on the rod, their mean normal speed, the coverage at the end and the forecast time to
98 % (`figures.json`), each with its difference to the finest tessellation. Prints a markdown table.

    tests/validation/step_tessellation.py [--build build] [--seeds "1 2 3"] [--chordal "0.1 0.03 0.01 0.003"]
                                          [--duration "1 s"] [--out DIR] [--writer EXE]

Not a timed test: each run is a full `peensim run` of the rod scene and its analysis (about a
minute each on 2 cores).
Standard library only.
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "scenes", "rod.yaml")
RADIUS_M, LENGTH_M = 5e-3, 30e-3


def scene_text(rod_mesh, tessellation):
    """scenes/rod.yaml with the rod's mesh replaced (and the assets' paths made absolute)."""
    text = open(SCENE, encoding="utf-8").read().replace("../assets/", os.path.join(ROOT, "assets") + "/")
    rod = re.compile(r"(  - name: rod\n    role: part\n    mesh: )[^\n]*\n    mesh_unit: mm\n")
    assert rod.search(text), "scenes/rod.yaml: the rod's entry moved; update this study"
    entry = r"\g<1>" + rod_mesh + "\n"
    if tessellation:
        entry += "    tessellation: {chordal: %s mm, angular: %s deg}\n" % tessellation
    else:
        entry += "    mesh_unit: mm\n"
    return rod.sub(entry, text)


def rod_triangles(peensim, scene):
    out = subprocess.run([peensim, "check", scene], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        m = re.search(r"\brod\b.*?(\d+) triangles", line)
        if m:
            return int(m.group(1))
    raise RuntimeError("no triangle count of the rod in `peensim check`:\n" + out)


def run(peensim, scene, out_dir, seed, duration):
    figures = os.path.join(out_dir, "analysis", "figures.json")
    if not os.path.exists(figures):  # a finished run is reused
        subprocess.run([peensim, "run", scene, "-o", out_dir, "--quiet", "--set", "process.seed=%d" % seed,
                        "--set", "process.duration=%s" % duration], check=True, stdout=subprocess.DEVNULL)
    data = json.load(open(figures, encoding="utf-8"))
    return next(c for c in data["components"] if c["component"] == "rod")


def mean(values):
    """Of the values that exist (a time to 98 % may be null)."""
    values = [v for v in values if v is not None]
    return statistics.fmean(values) if values else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--seeds", default="1 2 3")
    ap.add_argument("--chordal", default="0.1 0.03 0.01 0.003", help="chordal tolerances, mm (the last: the reference)")
    ap.add_argument("--duration", default="1 s")
    ap.add_argument("--out", default=None)
    ap.add_argument("--writer", default=None, help="the STEP rod writer (default: BUILD/peensim_write_step_rod)")
    a = ap.parse_args()
    peensim = os.path.join(a.build, "peensim")
    out = a.out or os.path.join(a.build, "validation", "step-tessellation")
    os.makedirs(out, exist_ok=True)
    step = os.path.join(out, "rod.step")
    subprocess.run([a.writer or os.path.join(a.build, "peensim_write_step_rod"), step], check=True)
    seeds = [int(s) for s in a.seeds.split()]

    cases = [("STEP, chordal %s mm" % c, step, (c, "45")) for c in a.chordal.split()]
    cases.append(("STEP, defaults (0.01 mm, 5 deg)", step, ("0.01", "5")))
    cases.append(("STL rod.stl (96 sides)", os.path.join(ROOT, "assets", "rod.stl"), None))
    rows = []
    for label, mesh, tessellation in cases:
        name = re.sub(r"[^A-Za-z0-9.]+", "-", label).strip("-")
        scene = os.path.join(out, name + ".yaml")
        with open(scene, "w", encoding="utf-8") as f:
            f.write(scene_text(mesh, tessellation))
        triangles = rod_triangles(peensim, scene)
        figs = [run(peensim, scene, os.path.join(out, "%s-seed%d" % (name, s)), s, a.duration) for s in seeds]
        rows.append({
            "label": label, "triangles": triangles,
            # Area deficit against the exact cylinder (caps and side): the tessellation's own error.
            "area_deficit": 1.0 - figs[0]["area_m2"] / (2 * math.pi * RADIUS_M ** 2 + 2 * math.pi * RADIUS_M * LENGTH_M),
            "impacts": [f["impacts"] for f in figs],
            "vn": [f["mean_vn_mps"] for f in figs],
            "coverage": [f["coverage"] for f in figs],
            "t98": [f["time_to_target"]["time_s"] for f in figs],
        })
        print("done: %s" % label, file=sys.stderr)

    ref = rows[len(a.chordal.split()) - 1]  # the finest chordal tolerance

    def cell(row, key, digits):
        """mean (sd over the seeds) and the mean's difference to the finest tessellation's."""
        m, r = mean(row[key]), mean(ref[key])
        if m is None:
            return "- | -"
        values = [v for v in row[key] if v is not None]
        sd = statistics.stdev(values) if len(values) > 1 else float("nan")
        return "%.*f (%.*f) | %+.1f %%" % (digits, m, digits, sd, 100.0 * (m / r - 1.0))

    print("| rod mesh | triangles | area deficit | impacts on the rod | vs finest | mean v_n (m/s) | vs finest "
          "| coverage at %s | vs finest | time to 98 %% (s) | vs finest |" % a.duration)
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %s | %d | %.2g %% | %s | %s | %s | %s |" % (r["label"], r["triangles"], 100.0 * r["area_deficit"], cell(r, "impacts", 0),
                                                         cell(r, "vn", 3), cell(r, "coverage", 4), cell(r, "t98", 1)))
    print("\nMeans over %d seeds (%s) of %s of the rod scene each, the seeds' standard deviation in brackets; "
          "\"vs finest\": the mean's difference to the finest chordal tolerance's." % (len(seeds), a.seeds, a.duration))


if __name__ == "__main__":
    main()
