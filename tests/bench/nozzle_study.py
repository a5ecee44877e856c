#!/usr/bin/env python3
"""The reference's conventional-peening (DEM-FEM) study, run at the study's own conditions
(reference section 6) with scenes/nozzle-study.yaml: 0.58 mm shot (7800 kg/m3), a nozzle 20 mm from
a flat steel target, Hertz-Mindlin e = 0.4. Prints the tables of docs/user-guide.md, "Conventional peening":

  1. paper against peensim, case by case: the reference case (9.25 kg/min, 75 m/s, 67.5 deg), the
     flow-rate matrix (62.5 deg), the angle study (9.25 kg/min, 100 m/s), the shot-size study
     (9.25 kg/min, 75 m/s, 62.5 deg) and constant against impact-history restitution;
  2. what the study leaves unstated, varied: the nozzle's diameter and divergence at four anchor cases;
  4. cost: wall time per 10,000 target impacts, without and with air drag.

    tests/bench/nozzle_study.py [--peensim build/peensim] [--seeds 2] [--only 1,2,3,4]

Each case is `peensim run` (the reference case also `peensim analyze`, for its steady state). An
impact "arrives at v0" when its speed is >= 0.9 v0 (the nozzle's speeds spread +-5 %, so every shot
leaves at >= 0.95 v0). Standard library only.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "scenes", "nozzle-study.yaml")
RHO_SHOT = 7800.0  # kg/m3, the study's (590,000 shot/s of 0.4 mm at 9.25 kg/min)


def table(restitution):
    return ("contacts.shot-steel={law: impact-history, restitution_by_hits: [" + ", ".join(str(c) for c in restitution) +
            "], influence_distance: 0.58 mm, f: 0.3}")


# Constant against history: the same law (impulse rebound, tangential 5/7 kept: hertz-mindlin's rigid
# limit for a gripping sphere), only the normal restitution changes; marks reach one shot diameter.
CONSTANT = table([0.4])
HISTORY = table([0.4, 0.5, 0.56, 0.6, 0.63])


def nozzle(flow_kg_min, speed_mps, angle_deg, duration_ms):
    return [f"sources[nozzle].mass_flow={flow_kg_min} kg/min", f"sources[nozzle].speed={speed_mps} m/s",
            f"sources[nozzle].angle_of_attack={angle_deg} deg", f"process.duration={duration_ms} ms"]


def run_case(peensim, sets, seed, v0, analyze=False):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "run")
        args = [peensim, "run", SCENE, "-o", out, "--no-analyze", "--set", f"process.seed={seed}"]
        for s in sets:
            args += ["--set", s]
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        steady = ""
        if analyze:
            subprocess.run([peensim, "analyze", out], check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(out, "analysis", "report.md")) as f:
                jet = f.read().split("## The jet", 1)[1]
            steady = next(line.split("|")[5].strip() for line in jet.splitlines() if line.startswith("| target |"))
        n = fast = first50 = high = e_rows = 0
        vn_sum = e_sum = 0.0
        with open(os.path.join(out, "impacts.csv")) as f:
            for r in csv.DictReader(f):
                if r["component"] != "target":
                    continue
                vn = float(r["vn_in_mps"])
                at_v0 = math.hypot(vn, float(r["vt_in_mps"])) >= 0.9 * v0
                n += 1
                fast += at_v0
                first50 += at_v0 and n <= 50
                high += vn >= 0.7 * v0
                vn_sum += vn
                if vn > 1.0:
                    e_sum += float(r["vn_out_mps"]) / vn
                    e_rows += 1
    counts = {c["component"]: c["impacts"] for c in summary["impacts_per_component"]}
    return {"target": n, "shot-shot": counts["shot-shot"], "fast": fast / n, "fast_count": fast, "first50": first50 / min(n, 50),
            "high": high / n, "vn": vn_sum / n, "e": e_sum / max(e_rows, 1), "steady": steady, "wall": summary["wall_time_s"],
            "emitted": sum(s["emitted"] for s in summary["emitted_per_source"])}


def cases(peensim, sets, seeds, v0, analyze=False):
    return [run_case(peensim, sets, seed, v0, analyze) for seed in range(1, seeds + 1)]


def mean_se(results, key):
    values = [r[key] for r in results]
    m = statistics.mean(values)
    return m, (statistics.stdev(values) / len(values) ** 0.5 if len(values) > 1 else float("nan"))


def pct(results, key):
    m, se = mean_se(results, key)
    return f"{100 * m:.1f} +- {100 * se:.1f} %"


def mean(results, key, fmt="{:.0f}"):
    return fmt.format(statistics.mean(r[key] for r in results))


def verdict(results, key, paper, within_pts):
    """'agrees' when |peensim - paper| <= max(3 SE, within_pts percentage points)."""
    m, se = mean_se(results, key)
    gap = abs(m - paper)
    return "agrees" if gap <= max(3 * (se if se == se else 0), within_pts / 100) else f"differs ({100 * (m - paper):+.1f} pts)"


def validation(a):
    print("## 1. The study's figures at its own conditions\n")
    print("| study | conditions | figure | paper | peensim | verdict |")
    print("|---|---|---|---|---|---|")
    row = lambda *c: print("| " + " | ".join(c) + " |", flush=True)

    ref = cases(a.peensim, nozzle(9.25, 75, 67.5, 60), a.seeds, 75, analyze=True)
    cond = "9.25 kg/min, 75 m/s, 67.5 deg, 60 ms"
    row("reference case", cond, "first 50 impacts at v0", "64 %", pct(ref, "first50"), verdict(ref, "first50", 0.64, 5))
    row("reference case", cond, "steady share at v0", "33.65 %", pct(ref, "fast"), verdict(ref, "fast", 0.3365, 2))
    steady = [int(r["steady"]) for r in ref if r["steady"].isdigit()]
    row("reference case", cond, "steady after (impacts, per seed)", "~4000", ", ".join(r["steady"] for r in ref),
        f"differs (x{statistics.mean(steady) / 4000:.2f} of the paper's)" if len(steady) == len(ref) else "differs (not steady)")

    for eps, flow, speed, paper, dur in ((0.667, 5.5, 100, 0.56, 120), (3.154, 13, 50, 0.0389, 40)):
        r = cases(a.peensim, nozzle(flow, speed, 62.5, dur), a.seeds, speed)
        row("flow rate (its Fig. 8)", f"eps {eps}: {flow} kg/min, {speed} m/s, 62.5 deg", "share at v0", f"{100 * paper:.3g} %",
            pct(r, "fast"), verdict(r, "fast", paper, 2))

    angles = {}
    for angle in (35, 45, 62.5, 67.5, 75, 90):
        angles[angle] = cases(a.peensim, nozzle(9.25, 100, angle, 60), a.seeds, 100)
    for angle, paper in ((35, 0.74), (90, 0.50)):
        row("angle of attack", f"9.25 kg/min, 100 m/s, {angle} deg", "share at v0", f"~{100 * paper:.0f} %", pct(angles[angle], "fast"),
            verdict(angles[angle], "fast", paper, 3))
    best = max(angles, key=lambda x: statistics.mean(r["high"] for r in angles[x]))
    row("angle of attack", "9.25 kg/min, 100 m/s, 35-90 deg", "angle with the largest share of v_n >= 0.7 v0", "62.5 deg (62.83 %)",
        f"{best} deg ({pct(angles[best], 'high')})", "agrees" if best == 62.5 else "differs")
    below = statistics.mean(r["high"] for r in angles[35])
    row("angle of attack", "9.25 kg/min, 100 m/s, 35 deg", "share of v_n >= 0.7 v0", "none", f"{100 * below:.1f} %",
        "agrees" if below < 0.005 else "differs")
    print("\nAngle study, every angle (9.25 kg/min, 100 m/s):\n")
    print("| angle (deg) | target impacts | shot-shot | at v0 | v_n >= 0.7 v0 | mean v_n (m/s) |")
    print("|---|---|---|---|---|---|")
    for angle, r in angles.items():
        print(f"| {angle} | {mean(r, 'target')} | {mean(r, 'shot-shot')} | {pct(r, 'fast')} | {pct(r, 'high')} | {mean(r, 'vn', '{:.2f}')} |",
              flush=True)

    print("\nShot size (9.25 kg/min, 75 m/s, 62.5 deg; the study: 590,000 shot/s at 0.4 mm, 11,200 at 1.5 mm; shot-shot "
          "collisions 18,057 at 0.4 mm falling almost linearly to 2,174 at 1.5 mm):\n")
    print("| shot (mm) | shot/s (from the mass flow) | simulated (ms) | target impacts | shot-shot | shot-shot per 10,000 target impacts |")
    print("|---|---|---|---|---|---|")
    sizes = {}
    for d_mm, dur in ((0.4, 25), (0.58, 60), (1.0, 250), (1.5, 900)):
        r = cases(a.peensim, nozzle(9.25, 75, 62.5, dur) + [f"shot.diameter={d_mm} mm"], a.seeds, 75)
        rate = 9.25 / 60 / (RHO_SHOT * math.pi / 6 * (d_mm * 1e-3) ** 3)
        sizes[d_mm] = statistics.mean(1e4 * x["shot-shot"] / x["target"] for x in r)
        print(f"| {d_mm} | {rate:,.0f} | {dur} | {mean(r, 'target')} | {mean(r, 'shot-shot')} | {sizes[d_mm]:,.0f} |", flush=True)
    print(f"\nRatio 0.4 mm / 1.5 mm of shot-shot per 10,000 target impacts: {sizes[0.4] / sizes[1.5]:.1f} (study: 18,057 / 2,174 = 8.3)\n")

    print("Constant against impact-history restitution (reference case; the same law, only the normal restitution differs):\n")
    print("| restitution | mean e given | target impacts | of them at v0 | shot-shot | mean v_n (m/s) | share at v0 |")
    print("|---|---|---|---|---|---|---|")
    res = {}
    for name, law in (("constant 0.4", CONSTANT), ("by hits 0.4, 0.5, 0.56, 0.6, 0.63", HISTORY)):
        res[name] = r = cases(a.peensim, nozzle(9.25, 75, 67.5, 60) + [law], a.seeds, 75)
        print(f"| {name} | {mean(r, 'e', '{:.3f}')} | {mean(r, 'target')} | {mean(r, 'fast_count')} | {mean(r, 'shot-shot')} "
              f"| {mean(r, 'vn', '{:.2f}')} | {pct(r, 'fast')} |", flush=True)
    c, h = res.values()
    change = lambda k: 100 * (statistics.mean(x[k] for x in h) / statistics.mean(x[k] for x in c) - 1)
    print(f"\nHistory against constant: target impacts {change('target'):+.1f} % (study: up), of them at v0 {change('fast_count'):+.1f} %, "
          f"shot-shot {change('shot-shot'):+.1f} % (study: down), mean v_n {change('vn'):+.1f} % (study: up)\n")


def unstated(a):
    print("## 2. What the study does not state, varied\n")
    anchors = (("62.5 deg, eps 0.667", nozzle(5.5, 100, 62.5, 120), 100, "56 %"),
               ("90 deg, 9.25 kg/min, 100 m/s", nozzle(9.25, 100, 90, 60), 100, "~50 %"),
               ("35 deg, 9.25 kg/min, 100 m/s", nozzle(9.25, 100, 35, 60), 100, "~74 %"),
               ("62.5 deg, eps 3.154", nozzle(13, 50, 62.5, 40), 50, "3.89 %"))
    variants = (("6 mm, 2 deg (shipped)", []), ("10 mm, 2 deg", ["sources[nozzle].diameter=10 mm"]),
                ("16 mm, 2 deg", ["sources[nozzle].diameter=16 mm"]), ("6 mm, 6 deg", ["sources[nozzle].spread=6 deg"]))
    print("| nozzle | " + " | ".join(f"{name} (paper {paper})" for name, _, _, paper in anchors) + " |")
    print("|---|" + "---|" * len(anchors))
    for vname, vsets in variants:
        cells = [pct(cases(a.peensim, sets + vsets, a.seeds, v0), "fast") for _, sets, v0, _ in anchors]
        print(f"| {vname} | " + " | ".join(cells) + " |", flush=True)
    print()


def cost(a):
    print("## 4. Cost (one core)\n")
    print("| case | scheme | target impacts | wall s | wall s per 10,000 target impacts |")
    print("|---|---|---|---|---|")
    for name, sets in (("5.5 kg/min, 100 m/s, 62.5 deg", nozzle(5.5, 100, 62.5, 120)),
                       ("same, air drag", nozzle(5.5, 100, 62.5, 120) + ["air.drag=sphere", "accuracy.scheme=step"]),
                       ("13 kg/min, 50 m/s, 62.5 deg", nozzle(13, 50, 62.5, 40))):
        r = run_case(a.peensim, sets, 1, 100)
        scheme = "step" if "air.drag=sphere" in sets else "event"
        print(f"| {name} | {scheme} | {r['target']} | {r['wall']:.2f} | {1e4 * r['wall'] / r['target']:.3f} |", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--peensim", default=os.path.join(ROOT, "build", "peensim"))
    p.add_argument("--seeds", type=int, default=2)
    p.add_argument("--only", default="1,2,4", help="sections to run (1 validation, 2 unstated parameters, 4 cost)")
    a = p.parse_args()
    only = a.only.split(",")
    if "1" in only:
        validation(a)
    if "2" in only:
        unstated(a)
    if "4" in only:
        cost(a)


if __name__ == "__main__":
    sys.exit(main())
