#!/usr/bin/env python3
"""The FEM deck's convergence study (docs/user-guide.md, "FEM hand-off"): the quarter single-impact deck of
`peensim export-fem` (default: a 0.58 mm steel shot at 50 m/s onto steel, 500 MPa, perfectly
plastic) for each block element (C3D8, C3D8I, C3D8R) and mesh (--elements-per-dent), run in
CalculiX one at a time (one thread, nice, a time cap); prints, per case, the mesh, the ccx wall
time and peak memory, the residual dent (after the relaxation step), the rebound (CoR) and the
residual in-plane stress sigma_xx under the centre (surface layer, the most compressive and its
depth, where it turns tensile), as the table of docs/user-guide.md. Cases already run in OUT (a .dat and a
time.txt there) are read, not rerun.

  tests/bench/fem_convergence.py [--peensim build/peensim] [--out out/fem-convergence]
                                 [--cases C3D8I:4,C3D8I:6,...] [--dynamics explicit|implicit]
                                 [--single ...] [--shot-diameter ...] [--yield-stress ...]
                                 [--shot-divisions 8] [--cap 900] [--profile]
"""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fem_read  # noqa: E402

DEFAULT_CASES = "C3D8I:4,C3D8I:6,C3D8I:8,C3D8I:10"  # the explicit table of docs/user-guide.md


def run_case(args, element, per_dent, directory):
    os.makedirs(directory, exist_ok=True)
    done = os.path.exists(os.path.join(directory, "patch.dat")) and os.path.exists(os.path.join(directory, "time.txt"))
    if not done:
        cmd = [args.peensim, "export-fem", "-o", directory, "--single", args.single, "--shot-diameter", args.shot_diameter,
               "--quarter", "--element", element, "--elements-per-dent", str(per_dent), "--dynamics", args.dynamics,
               "--shot-divisions", str(args.shot_divisions)]
        if args.yield_stress:
            cmd += ["--yield-stress", args.yield_stress]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        env = dict(os.environ, OMP_NUM_THREADS="1")
        with open(os.path.join(directory, "ccx.log"), "w") as log:
            subprocess.run(["/usr/bin/time", "-v", "-o", "time.txt", "timeout", str(args.cap), "nice", "ccx", "-i", "patch"],
                           cwd=directory, env=env, stdout=log, stderr=subprocess.STDOUT)


def measured(directory):
    """(wall s, peak MB) from /usr/bin/time -v."""
    wall, rss = float("nan"), float("nan")
    with open(os.path.join(directory, "time.txt")) as f:
        for line in f:
            if "Elapsed (wall clock)" in line:
                parts = [float(p) for p in line.rsplit(" ", 1)[1].split(":")]
                wall = sum(p * 60 ** (len(parts) - 1 - i) for i, p in enumerate(parts))
            if "Maximum resident" in line:
                rss = float(line.split(":")[1]) / 1024.0
    return wall, rss


def deck_size(inp):
    """(block elements, nodes of the whole deck, h m)."""
    nodes, elements, _ = fem_read.read_inp(inp)
    all_nodes = 0
    with open(inp) as f:
        mode = False
        for line in f:
            if line.startswith("*"):
                mode = line.upper().startswith("*NODE, NSET=")
                continue
            if mode and line.strip():
                all_nodes += 1
    xs = sorted(set(round(p[0], 12) for p in nodes.values()))
    return len(elements), all_nodes, xs[1] - xs[0]


def why_unfinished(directory):
    """ccx's error and how far its first step got, from its log."""
    error, reached, increments = "no error message", "", 0
    with open(os.path.join(directory, "ccx.log")) as f:
        for line in f:
            if "*ERROR" in line:
                error = line.strip().lstrip("*")
            if "actual step time=" in line:
                reached = line.split("=")[1].strip()
            if line.startswith(" increment ") and "attempt 1" in line:
                increments += 1
    with open(os.path.join(directory, "time.txt")) as f:
        if any(line.strip() == "Exit status: 124" for line in f):
            error = "stopped at the time cap (timeout)"
    return "%s, at step time %s s after %d increments" % (error, reached, increments)


def at(profile, depth):
    """sigma at `depth` (m), linear between the element centroids (nan outside them)."""
    for (d0, v0), (d1, v1) in zip(profile, profile[1:]):
        if d0 <= depth <= d1:
            return v0 + (v1 - v0) * (depth - d0) / (d1 - d0)
    return float("nan")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peensim", default="build/peensim")
    p.add_argument("--out", default="out/fem-convergence")
    p.add_argument("--cases", default=DEFAULT_CASES, help="ELEMENT:ELEMENTS_PER_DENT, comma-separated")
    p.add_argument("--single", default="0,0,0,0,0,-50 m/s")
    p.add_argument("--shot-diameter", default="0.58 mm")
    p.add_argument("--yield-stress", default="")
    p.add_argument("--dynamics", default="explicit", help="export-fem --dynamics")
    p.add_argument("--shot-divisions", type=int, default=8, help="export-fem --shot-divisions")
    p.add_argument("--speed", type=float, default=50.0, help="impact speed (m/s), for the CoR")
    p.add_argument("--yield-pa", type=float, default=500e6, help="yield stress (Pa), to state stresses in yields")
    p.add_argument("--cap", type=int, default=900, help="seconds a ccx run may take")
    p.add_argument("--depths", default="25,50,100,150,200,300", help="depths (um) the table states sigma_xx at")
    p.add_argument("--profile", action="store_true", help="also print each case's sigma_xx against depth")
    args = p.parse_args()

    depths = [float(d) for d in args.depths.split(",")]
    print("| element | per dent | h um | block elements | deck nodes | ccx s | MB | depth um | zero diameter um | crest um | CoR | "
          + " | ".join("sxx %g um MPa" % d for d in depths) + " | most compressive MPa (yields) at um |")
    print("|---" * (12 + len(depths)) + "|")
    for case in args.cases.split(","):
        element, per_dent = case.split(":")
        directory = os.path.join(args.out, "%s-%s" % (element, per_dent))
        run_case(args, element, per_dent, directory)
        inp, dat = os.path.join(directory, "patch.inp"), os.path.join(directory, "patch.dat")
        n_el, n_nodes, h = deck_size(inp)
        wall, rss = measured(directory)
        try:
            s = fem_read.summarise(inp, dat, args.speed)
        except (TypeError, KeyError, ValueError, IndexError):  # ccx did not finish: say where and why
            print("| %s | %s | %.0f | %d | %d | %.0f | %.0f | did not finish: %s |" % (element, per_dent, h * 1e6, n_el, n_nodes, wall, rss,
                                                                                   why_unfinished(directory)))
            continue
        prof = s["sxx"]
        low = min(prof, key=lambda q: q[1])
        print("| %s | %s | %.0f | %d | %d | %.0f | %.0f | %.1f | %.0f | %.1f | %.2f | %s | %.0f (%.2f) at %.0f |" % (
            element, per_dent, h * 1e6, n_el, n_nodes, wall, rss, s["depth"] * 1e6, s["zero_diameter"] * 1e6,
            s["crest_height"] * 1e6, s["cor"], " | ".join("%.0f" % (at(prof, d * 1e-6) / 1e6) for d in depths),
            low[1] / 1e6, low[1] / args.yield_pa, low[0] * 1e6))
        if args.profile:
            print("|   | sxx vs depth: " + ", ".join("%.0f um %.0f" % (d * 1e6, v / 1e6) for d, v in prof if d < 4 * s["zero_diameter"]) + " MPa |")


if __name__ == "__main__":
    main()
