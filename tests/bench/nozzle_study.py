#!/usr/bin/env python3
"""The reference's conventional-peening study (section 4) run with scenes/nozzle-study.yaml: 0.58 mm
shot, a nozzle 20 mm from a flat steel target, e = 0.4. Prints, beside the study's figures:

  1. the share of impacts arriving with >= 90 % of v0 at eps = 0.667 (5.5 kg/min, 100 m/s) and
     eps = 3.154 (13 kg/min, 50 m/s), and when the stream is steady;
  2. the angle-of-attack sweep: the share of impacts keeping >= 90 % of the jet's normal speed;
  3. constant (0.4) against impact-history restitution: shot-shot and shot-target counts, mean
     normal impact speed, the mean restitution the history law gave;
  4. cost: wall time per 10,000 target impacts, without and with air drag.

    tests/bench/nozzle_study.py [--peensim build/peensim] [--seeds 2]

Each case is `peensim run` then `peensim analyze` (its report's jet table). Standard library only.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "scenes", "nozzle-study.yaml")
HISTORY = "contacts.shot-steel={law: impact-history, restitution_by_hits: [0.4, 0.5, 0.56, 0.6, 0.63], mu: 0.3, f: 0.3}"


def run_case(peensim, sets, seed, workdir):
    out = os.path.join(workdir, "run")
    args = [peensim, "run", SCENE, "-o", out, "--no-analyze", "--set", f"process.seed={seed}"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    subprocess.run([peensim, "analyze", out], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "analysis", "target_jet.csv")) as f:
        windows = list(csv.DictReader(f))
    counts = {c["component"]: c["impacts"] for c in summary["impacts_per_component"]}
    n = sum(int(w["impacts"]) for w in windows)
    fast = sum(float(w["share_at_least_0_9_v0"]) * int(w["impacts"]) for w in windows) / n
    kept_key = "share_keeping_0_9_jet_normal_speed"
    kept = sum(float(w[kept_key]) * int(w["impacts"]) for w in windows) / n
    # Restitution actually given on the target: mean vn_out / vn_in over the impacts.
    # And the share of impacts with a high normal speed, v_n >= 0.7 v0.
    v0 = float(next(s for s in sets if s.startswith("sources[nozzle].speed=")).split("=")[1].split()[0]) if any(
        s.startswith("sources[nozzle].speed=") for s in sets) else 100.0
    ratio, rows, high, target_rows = 0.0, 0, 0, 0
    with open(os.path.join(out, "impacts.csv")) as f:
        for r in csv.DictReader(f):
            if r["component"] != "target":
                continue
            vn = float(r["vn_in_mps"])
            target_rows += 1
            high += vn >= 0.7 * v0
            if vn > 1.0:
                ratio += float(r["vn_out_mps"]) / vn
                rows += 1
    with open(os.path.join(out, "analysis", "report.md")) as f:
        jet = f.read().split("## The jet", 1)[1]
        steady = next(line.split("|")[5].strip() for line in jet.splitlines() if line.startswith("| target |"))
    return {
        "target": counts["target"], "shot-shot": counts["shot-shot"], "fast": fast, "kept": kept, "steady": steady,
        "vn": summary["normal_speed"][0]["mean_normal_speed_mps"], "high": high / max(target_rows, 1), "wall": summary["wall_time_s"], "e": ratio / max(rows, 1),
    }


def cases(peensim, sets, seeds):
    results = []
    for seed in range(1, seeds + 1):
        with tempfile.TemporaryDirectory() as d:
            results.append(run_case(peensim, sets, seed, d))
    return results


def mean_se(values):
    m = statistics.mean(values)
    se = statistics.stdev(values) / len(values) ** 0.5 if len(values) > 1 else float("nan")
    return m, se


def pct(results, key):
    m, se = mean_se([r[key] for r in results])
    return f"{100 * m:.1f} +- {100 * se:.1f} %"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--peensim", default=os.path.join(ROOT, "build", "peensim"))
    p.add_argument("--seeds", type=int, default=2)
    a = p.parse_args()

    print("## Flow rate (eps) against the share of impacts at >= 90 % of v0\n")
    print("| case | eps | target impacts | shot-shot | at >= 0.9 v0 | study | steady after (impacts) |")
    print("|---|---|---|---|---|---|---|")
    flows = [("5.5 kg/min, 100 m/s", 0.667, [], "56 %"),
             ("13 kg/min, 50 m/s", 3.154, ["sources[nozzle].mass_flow=13 kg/min", "sources[nozzle].speed=50 m/s",
                                           "process.duration=40 ms"], "3.9 %")]
    for name, eps, sets, study in flows:
        r = cases(a.peensim, sets, a.seeds)
        print(f"| {name} | {eps} | {statistics.mean(x['target'] for x in r):.0f} | {statistics.mean(x['shot-shot'] for x in r):.0f} "
              f"| {pct(r, 'fast')} | {study} | {', '.join(x['steady'] for x in r)} |", flush=True)

    print("\n## Angle of attack (5.5 kg/min, 100 m/s): how much of the jet's normal speed arrives\n")
    print("| angle of attack (deg) | target impacts | shot-shot | keeping >= 0.9 v0 sin(a) | at >= 0.9 v0 | v_n >= 0.7 v0 | mean v_n (m/s) |")
    print("|---|---|---|---|---|---|---|")
    for angle in (90, 75, 62.5, 52.5, 45, 30):
        r = cases(a.peensim, [f"sources[nozzle].angle_of_attack={angle} deg"], a.seeds)
        print(f"| {angle} | {statistics.mean(x['target'] for x in r):.0f} | {statistics.mean(x['shot-shot'] for x in r):.0f} "
              f"| {pct(r, 'kept')} | {pct(r, 'fast')} | {pct(r, 'high')} | {statistics.mean(x['vn'] for x in r):.2f} |", flush=True)

    print("\n## Constant against impact-history restitution (5.5 kg/min, 100 m/s)\n")
    print("| restitution | mean e given on the target | target impacts | shot-shot | mean v_n (m/s) | at >= 0.9 v0 |")
    print("|---|---|---|---|---|---|")
    for name, sets in (("constant 0.4 (hertz-mindlin)", []), ("impact history 0.4 -> 0.63", [HISTORY])):
        r = cases(a.peensim, sets, a.seeds)
        print(f"| {name} | {statistics.mean(x['e'] for x in r):.3f} | {statistics.mean(x['target'] for x in r):.0f} "
              f"| {statistics.mean(x['shot-shot'] for x in r):.0f} | {statistics.mean(x['vn'] for x in r):.2f} | {pct(r, 'fast')} |",
              flush=True)

    print("\n## Cost (one core)\n")
    print("| case | scheme | target impacts | wall s | wall s per 10,000 target impacts |")
    print("|---|---|---|---|---|")
    for name, sets in (("5.5 kg/min, 100 m/s", []), ("5.5 kg/min, 100 m/s, air drag", ["air.drag=sphere", "accuracy.scheme=step"]),
                       ("13 kg/min, 50 m/s", flows[1][2])):
        r = cases(a.peensim, sets, 1)[0]
        scheme = "step" if "air.drag=sphere" in sets else "event"
        print(f"| {name} | {scheme} | {r['target']} | {r['wall']:.2f} | {1e4 * r['wall'] / r['target']:.3f} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
