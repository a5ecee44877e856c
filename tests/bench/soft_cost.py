#!/usr/bin/env python3
"""What the soft scheme costs, and how it grows: wall time per simulated second of the shipped soft
scenes (rod-soft, gear-soft) with the soft and the rigid event scheme side by side (`peensim bench`),
the contacts per simulated second (impacts on every component plus shot-shot), and the soft scheme's
cost per contact, against the shot count, the stiffness (every material's E scaled) and the
integration resolution (steps per contact).

    tests/bench/soft_cost.py [--peensim build/peensim] [--quick]

Runs on one core; run it on a quiet machine (the figures of docs/design.md, "Benchmark"). Standard
library only.
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

MATERIALS = {
    "rod-soft": {"steel": 200e9, "titanium": 200e9, "copper": 200e9},
    "gear-soft": {"steel": 200e9, "TA6V": 114e9, "aluminium-2000": 73e9, "HDPE": 1e9},
}


def bench(peensim, scene, duration, sets):
    """One `peensim bench --schemes soft,event` run; per scheme: wall s per simulated s and contacts per simulated s."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "bench.csv")
        cmd = [peensim, "bench", os.path.join(ROOT, "scenes", scene + ".yaml"), "--duration", str(duration), "--schemes", "soft,event",
               "--csv", out]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        rows = list(csv.DictReader(open(out)))
    figures = {}
    for scheme in ("soft", "event"):
        mine = [r for r in rows if r["scheme"] == scheme and r["component"] != "all logged"]
        wall = float(mine[0]["wall_s_per_simulated_s"])
        contacts = sum(float(r["impact_rate_per_s"]) for r in mine) + float(mine[0]["shot_shot_impacts_per_s"])
        figures[scheme] = (wall, contacts)
    return figures


def row(label, f):
    soft_wall, contacts = f["soft"]
    event_wall, _ = f["event"]
    print(f"{label:44s} {soft_wall:9.3f} {event_wall:9.3f} {soft_wall / event_wall:7.2f} {contacts:12.0f} {1e6 * soft_wall / contacts:9.2f}")
    sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--peensim", default=os.path.join(ROOT, "build", "peensim"))
    ap.add_argument("--quick", action="store_true", help="shorter runs (figures noisier)")
    a = ap.parse_args()
    rod_t, gear_t = (0.2, 1.0) if a.quick else (0.5, 2.0)
    print(f"{'case':44s} {'soft s/s':>9s} {'event s/s':>9s} {'ratio':>7s} {'contacts/s':>12s} {'us/contact':>9s}")
    print("(wall seconds per simulated second, the stepping loop; contacts: impacts on every component and shot-shot)")
    for n in (128, 256, 512, 1024):
        row(f"rod-soft, {n} shot ({rod_t} s)", bench(a.peensim, "rod-soft", rod_t, [f"shot.count={n}"]))
    for steps in (10, 20, 40, 80):
        row(f"rod-soft, {steps} steps per contact", bench(a.peensim, "rod-soft", rod_t, [f"accuracy.soft_steps_per_contact={steps}"]))
    for factor in (1.0, 0.1, 0.01):
        sets = [f"materials.{m}.youngs_modulus={e * factor:g} Pa" for m, e in MATERIALS["rod-soft"].items()]
        row(f"rod-soft, E x {factor:g}", bench(a.peensim, "rod-soft", rod_t, sets))
    for n in (70, 140, 280):
        row(f"gear-soft, {n} shot ({gear_t} s)", bench(a.peensim, "gear-soft", gear_t, [f"shot.count={n}"]))
    for factor in (1.0, 0.1):
        sets = [f"materials.{m}.youngs_modulus={e * factor:g} Pa" for m, e in MATERIALS["gear-soft"].items()]
        row(f"gear-soft, E x {factor:g}", bench(a.peensim, "gear-soft", gear_t, sets))


if __name__ == "__main__":
    main()
