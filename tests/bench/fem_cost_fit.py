#!/usr/bin/env python3
"""Fits the CalculiX cost model of src/fem/ccx_cost.cpp to measured ccx runs of export-fem decks
and checks it on runs left out of the fit (docs/user-guide.md, "FEM hand-off").

  tests/bench/fem_cost_fit.py --fit DIR[,DIR...] [--check DIR[,DIR...]]

Each DIR holds a deck (patch.inp), ccx's log and /usr/bin/time -v's time.txt (as
tests/bench/fem_convergence.py leaves them). The model, per deck: nodes N (block and shot), planned
increments I (sum over the *DYNAMIC steps of duration / largest increment, rounded up) and the
block's element type and dynamics (the "type"):  wall = a[type] * I * (N / 1e4)^b[type]  and
peak memory = m[type] * (N / 1e4)^c[type], each by least squares in logs (a type with one run takes
the exponents of a type of the same dynamics)."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fem_convergence import measured  # noqa: E402

REFERENCE_NODES = 1e4


EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def deck_facts(directory):
    """Nodes, block element type, dynamics and planned increments of a deck, as src/fem/ccx_cost.cpp
    counts them (explicit: duration over the shortest edge / the dilatational wave speed)."""
    inp = os.path.join(directory, "patch.inp")
    with open(inp) as f:
        lines = f.read().split("\n")
    coords, shortest, material, props = {}, {"block": 1e9, "shot": 1e9}, None, {}
    element, kind, steps, mode, explicit = "C3D8", None, [], None, False
    for i, line in enumerate(lines):
        if line.startswith("**") or not line.strip():
            continue
        if line.startswith("*"):
            u = line.upper()
            mode = ("node" if u.startswith("*NODE, NSET=") else "element" if u.startswith("*ELEMENT") else
                    "elastic" if u.startswith("*ELASTIC") else "density" if u.startswith("*DENSITY") else None)
            if u.startswith("*ELEMENT"):
                kind = "block" if "ELSET=EBLOCK" in u else "shot"
                if kind == "block":
                    element = u.split("TYPE=")[1].split(",")[0].strip()
            if u.startswith("*MATERIAL"):
                material = u.split("NAME=")[1].strip()
                props[material] = {}
            if u.startswith("*DYNAMIC"):
                explicit = "EXPLICIT" in u
                steps.append([float(x) for x in lines[i + 1].split(",")])
            continue
        f = [x for x in line.split(",") if x.strip()]
        if mode == "node":
            coords[int(f[0])] = [float(x) for x in f[1:4]]
        elif mode == "element":
            ids = [int(x) for x in f[1:9]]
            for a, b in EDGES:
                shortest[kind] = min(shortest[kind], math.dist(coords[ids[a]], coords[ids[b]]))
        elif mode == "elastic":
            props[material]["E"], props[material]["nu"] = float(f[0]), float(f[1])
        elif mode == "density":
            props[material]["rho"] = float(f[0])

    def speed(m):
        E, nu, rho = props[m]["E"], props[m]["nu"], props[m]["rho"]
        return math.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))

    if explicit:
        dt = min(shortest["block"] / speed("TARGET"), shortest["shot"] / speed("SHOT"))
        increments = sum(math.ceil(s[1] / dt) for s in steps)
    else:
        increments = sum(math.ceil(s[1] / s[3] - 1e-9) for s in steps)
    wall, mb = measured(directory)
    return {"dir": directory, "nodes": len(coords), "element": element + (" explicit" if explicit else " implicit"),
            "increments": increments, "wall": wall, "mb": mb}


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
    # Per type: log(wall / I) = log a + b log(N / 1e4) and log(MB) = log m + c log(N / 1e4); a type
    # with one run takes b and c of a type of the same dynamics (implicit or explicit) that has more.
    types = sorted(set(r["element"] for r in fit))
    law = {}
    for ty in types:
        rs = [r for r in fit if r["element"] == ty]
        if len(rs) > 1:
            xs = [math.log(r["nodes"] / REFERENCE_NODES) for r in rs]
            b, la = lstsq(xs, [math.log(r["wall"] / r["increments"]) for r in rs])
            c, lm = lstsq(xs, [math.log(r["mb"]) for r in rs])
            law[ty] = (la, b, lm, c)
    for ty in types:
        if ty not in law:
            r = [r for r in fit if r["element"] == ty][0]
            _, b, _, c = next(v for k, v in law.items() if k.endswith("implicit") == ty.endswith("implicit"))
            x = math.log(r["nodes"] / REFERENCE_NODES)
            law[ty] = (math.log(r["wall"] / r["increments"]) - b * x, b, math.log(r["mb"]) - c * x, c)
    for ty in types:
        la, b, lm, c = law[ty]
        print("%s: %.4g s per planned increment x (N / %g)^%.3f; %.4g MB x (N / %g)^%.3f" % (
            ty, math.exp(la), REFERENCE_NODES, b, math.exp(lm), REFERENCE_NODES, c))
    print("| run | in fit | element | nodes | planned increments | ccx s | model s | error | MB | model MB | error |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r, used in [(r, "yes") for r in fit] + [(r, "no") for r in check]:
        la, b, lm, c = law[r["element"]]
        x = r["nodes"] / REFERENCE_NODES
        t = math.exp(la) * r["increments"] * x ** b
        m = math.exp(lm) * x ** c
        print("| %s | %s | %s | %d | %d | %.0f | %.0f | %+.0f %% | %.0f | %.0f | %+.0f %% |" % (
            os.path.basename(r["dir"].rstrip("/")), used, r["element"], r["nodes"], r["increments"], r["wall"], t,
            100 * (t / r["wall"] - 1), r["mb"], m, 100 * (m / r["mb"] - 1)))


if __name__ == "__main__":
    main()
