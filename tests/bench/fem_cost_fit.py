#!/usr/bin/env python3
"""Fits the CalculiX cost model of src/fem/ccx_cost.cpp to measured ccx runs of export-fem decks
and checks it on runs left out of the fit (README, "FEM hand-off").

  tests/bench/fem_cost_fit.py --fit DIR[,DIR...] [--check DIR[,DIR...]]

Each DIR holds a deck (patch.inp), ccx's log and /usr/bin/time -v's time.txt (as
tests/bench/fem_convergence.py leaves them). The model, per deck: nodes N (block and shot), planned
increments I (sum over the *DYNAMIC steps of duration / largest increment, rounded up) and the
block's element type:  wall = a[type] * I * (N / 1e4)^b  and  memory = m0 + m1 * (N / 1e4)^c.
b, log a[type] by least squares on log(wall / I); m0 fixed at the smallest run's memory share, c
and m1 by least squares on log(memory - m0)."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fem_convergence import measured  # noqa: E402

REFERENCE_NODES = 1e4
BASE_MB = 40.0  # ccx's footprint with a tiny model (MB)


def deck_facts(directory):
    inp = os.path.join(directory, "patch.inp")
    nodes, element, increments = 0, "C3D8", 0
    with open(inp) as f:
        lines = f.read().split("\n")
    mode = False
    for i, line in enumerate(lines):
        if line.startswith("*"):
            u = line.upper()
            mode = u.startswith("*NODE, NSET=")
            if u.startswith("*ELEMENT") and "ELSET=EBLOCK" in u:
                element = u.split("TYPE=")[1].split(",")[0].strip()
            if u.startswith("*DYNAMIC"):
                f = [float(x) for x in lines[i + 1].split(",")]
                increments += math.ceil(f[1] / f[3] - 1e-9)
            continue
        if mode and line.strip():
            nodes += 1
    wall, mb = measured(directory)
    return {"dir": directory, "nodes": nodes, "element": element, "increments": increments, "wall": wall, "mb": mb}


def lstsq(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    return slope, my - slope * mx


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fit", required=True)
    p.add_argument("--check", default="")
    a = p.parse_args()
    fit = [deck_facts(d) for d in a.fit.split(",")]
    check = [deck_facts(d) for d in a.check.split(",") if d]
    # Time: a common exponent b, a factor per element type: regress log(wall / I) - log a[type] on log N.
    types = sorted(set(r["element"] for r in fit))
    b = 1.5
    for _ in range(50):  # alternate: factors given b, then b given the factors
        la = {t: sum(math.log(r["wall"] / r["increments"]) - b * math.log(r["nodes"] / REFERENCE_NODES) for r in fit if r["element"] == t) /
              sum(1 for r in fit if r["element"] == t) for t in types}
        xs = [math.log(r["nodes"] / REFERENCE_NODES) for r in fit]
        ys = [math.log(r["wall"] / r["increments"]) - la[r["element"]] for r in fit]
        b = sum(x * y for x, y in zip(xs, ys)) / sum(x * x for x in xs)
    c, lm = lstsq([math.log(r["nodes"] / REFERENCE_NODES) for r in fit], [math.log(max(r["mb"] - BASE_MB, 1.0)) for r in fit])
    print("time exponent b = %.3f; seconds per planned increment at %g nodes: %s" % (
        b, REFERENCE_NODES, ", ".join("%s %.3g" % (t, math.exp(la[t])) for t in types)))
    print("memory: %.0f MB + %.4g MB x (N / %g)^%.3f" % (BASE_MB, math.exp(lm), REFERENCE_NODES, c))
    print("| run | in fit | element | nodes | planned increments | ccx s | model s | error | MB | model MB | error |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r, used in [(r, "yes") for r in fit] + [(r, "no") for r in check]:
        t = math.exp(la.get(r["element"], la[types[0]])) * r["increments"] * (r["nodes"] / REFERENCE_NODES) ** b
        m = BASE_MB + math.exp(lm) * (r["nodes"] / REFERENCE_NODES) ** c
        print("| %s | %s | %s | %d | %d | %.0f | %.0f | %+.0f %% | %.0f | %.0f | %+.0f %% |" % (
            os.path.basename(r["dir"].rstrip("/")), used, r["element"], r["nodes"], r["increments"], r["wall"], t,
            100 * (t / r["wall"] - 1), r["mb"], m, 100 * (m / r["mb"] - 1)))


if __name__ == "__main__":
    main()
