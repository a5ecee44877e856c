#!/usr/bin/env python3
"""The soft-sphere side by side (side_by_side.sh): LIGGGHTS's statistics of the rod scene (or, with
--case plate, the plate scene) beside peensim's soft scheme's, each with its standard error, and their
differences in standard errors.

    side_by_side.py OUTDIR --duration S --settle S [--case rod|plate]

Reads OUTDIR/liggghts*/liggghts_stats.json (one per LIGGGHTS run) and OUTDIR/peensim/seed-*/
(peensim runs: run/ over the whole duration, settle/ up to the window's start); writes
OUTDIR/side_by_side.json and prints the table.

Standard errors: of the mean over the runs when there are at least three (their spread, the honest
one: the bed's slow swings make a single run's batch means too optimistic); else of one run's
batch means over 10 windows of the measured time. Standard library only.
"""
import argparse
import csv
import glob
import json
import math
import os
import statistics

BATCHES = 10
# (name printed, LIGGGHTS's surface, peensim's component); the part's row (rod or plate) first.
SURFACES = [("rod", "rod", "rod"), ("sonotrode", "sonotrode", "sonotrode"), ("walls + lid", "walls", "chamber")]


def use_case(part):
    """Points SURFACES at the case's part: rod or plate."""
    SURFACES[0] = (part, part, part)


def percentile(sorted_values, q):
    if not sorted_values:
        return float("nan")
    k = (len(sorted_values) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return sorted_values[lo] + (sorted_values[hi] - sorted_values[lo]) * (k - lo)


def se_of_runs(values):
    return statistics.stdev(values) / math.sqrt(len(values)) if len(values) >= 2 else float("nan")


def batch_se(values):
    return statistics.stdev(values) / math.sqrt(len(values)) if len(values) >= 2 else float("nan")


def peensim_run(run_dir, settle_dir, settle, duration):
    """One peensim run's figures over [settle, duration]: per surface the impacts, rate per batch,
    and the part's (rod's or plate's) normal speeds; shot-shot impacts from the two summaries."""
    length = duration - settle
    width = length / BATCHES
    per = {c: {"count": 0, "batches": [0] * BATCHES, "speeds": [], "speed_batches": [[] for _ in range(BATCHES)]}
           for _, _, c in SURFACES}
    with open(os.path.join(run_dir, "impacts.csv"), newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["time_s"])
            if t < settle or t >= duration:
                continue
            s = per.get(row["component"])
            if s is None:
                continue
            b = min(BATCHES - 1, int((t - settle) / width))
            s["count"] += 1
            s["batches"][b] += 1
            v = float(row["vn_in_mps"])
            s["speeds"].append(v)
            s["speed_batches"][b].append(v)
    with open(os.path.join(run_dir, "summary.json")) as f:
        whole = json.load(f)
    with open(os.path.join(settle_dir, "summary.json")) as f:
        early = json.load(f)
    count = lambda summary: next(c["impacts"] for c in summary["impacts_per_component"] if c["component"] == "shot-shot")
    pairs = count(whole) - count(early)
    return per, pairs, whole["wall_time_s"], length


def summarise_peensim(outdir, settle, duration):
    runs = sorted(glob.glob(os.path.join(outdir, "peensim", "seed-*")))
    out = {"runs": len(runs), "surfaces": {}, "wall_s": [], "simulated_s": duration}
    rates = {name: [] for name, _, _ in SURFACES}
    pair_rates = []
    rod_means, rod_pooled = [], []
    rod_q = {"p10": [], "p50": [], "p90": []}
    batch_rates = {name: [] for name, _, _ in SURFACES}
    rod_batch_means = []
    other_means = {}
    for r in runs:
        per, pairs, wall, length = peensim_run(os.path.join(r, "run"), os.path.join(r, "settle"), settle, duration)
        out["wall_s"].append(wall)
        pair_rates.append(pairs / length)
        for name, _, comp in SURFACES:
            rates[name].append(per[comp]["count"] / length)
            batch_rates[name] = [n / (length / BATCHES) for n in per[comp]["batches"]]
        part = SURFACES[0][2]
        speeds = sorted(per[part]["speeds"])
        rod_pooled += speeds
        rod_means.append(statistics.mean(speeds))
        for q, key in ((0.1, "p10"), (0.5, "p50"), (0.9, "p90")):
            rod_q[key].append(percentile(speeds, q))
        rod_batch_means = [statistics.mean(b) for b in per[part]["speed_batches"] if b]
        for name, _, comp in SURFACES[1:]:
            other_means.setdefault(name, []).append(statistics.mean(per[comp]["speeds"]) if per[comp]["speeds"] else float("nan"))
    many = len(runs) >= 3
    # the other surfaces' mean normal speeds, per run (a diagnostic: the bed's energy)
    out["other_mean_speed"] = {name: {"mean": statistics.mean(v), "se": se_of_runs(v)} for name, v in other_means.items()}
    for name, _, _ in SURFACES:
        out["surfaces"][name] = {"rate_per_s": statistics.mean(rates[name]),
                                 "rate_se": se_of_runs(rates[name]) if many else batch_se(batch_rates[name])}
    out["surfaces"]["shot-shot"] = {"rate_per_s": statistics.mean(pair_rates), "rate_se": se_of_runs(pair_rates)}
    rod_pooled.sort()
    out[SURFACES[0][0] + "_speed"] = {"mean": statistics.mean(rod_means), "mean_se": se_of_runs(rod_means) if many else batch_se(rod_batch_means)}
    for key, q in (("p10", 0.1), ("p50", 0.5), ("p90", 0.9)):
        out[SURFACES[0][0] + "_speed"][key] = statistics.mean(rod_q[key])
        out[SURFACES[0][0] + "_speed"][key + "_se"] = se_of_runs(rod_q[key])
    out["wall_per_sim_s"] = statistics.mean(out["wall_s"]) / duration
    return out


def summarise_liggghts(outdir):
    runs = sorted(glob.glob(os.path.join(outdir, "liggghts*", "liggghts_stats.json")))
    stats = []
    for path in runs:
        with open(path) as f:
            stats.append(json.load(f))
    out = {"runs": len(stats), "surfaces": {}}
    many = len(stats) >= 3
    for name, key, _ in SURFACES + [("shot-shot", "shot-shot", None)]:
        rates = [s["surfaces"][key]["rate_per_s"] for s in stats]
        out["surfaces"][name] = {"rate_per_s": statistics.mean(rates),
                                 "rate_se": se_of_runs(rates) if many else stats[0]["surfaces"][key]["rate_se_batch_per_s"]}
    sp = [s["surfaces"][SURFACES[0][1]]["normal_speed_corrected_m_s"] for s in stats]
    out[SURFACES[0][0] + "_speed"] = {"mean": statistics.mean(x["mean"] for x in sp),
                        "mean_se": se_of_runs([x["mean"] for x in sp]) if many else sp[0]["sem_batch"]}
    for key in ("p10", "p50", "p90"):
        out[SURFACES[0][0] + "_speed"][key] = statistics.mean(x[key] for x in sp)
        out[SURFACES[0][0] + "_speed"][key + "_se"] = se_of_runs([x[key] for x in sp]) if many else float("nan")
    out["other_mean_speed"] = {}
    for name, key, _ in SURFACES[1:] + [("shot-shot", "shot-shot", None)]:
        v = [s["surfaces"][key]["normal_speed_corrected_m_s"]["mean"] for s in stats]
        out["other_mean_speed"][name] = {"mean": statistics.mean(v), "se": se_of_runs(v)}
    timing = [s["timing"] for s in stats]
    out["wall_per_sim_s_no_output"] = statistics.mean(
        (t["settle_loop_s"] + t["production_loop_s"] - t["production_output_s"]) /
        (t["settle_steps"] + t["production_steps"]) / s["params"]["timestep_s"] for t, s in zip(timing, stats))
    out["wall_per_sim_s_with_contact_output"] = statistics.mean(t["wall_per_sim_s_production"] for t in timing)
    out["contact_duration_median_s"] = {name: stats[0]["surfaces"][key].get("contact_duration_median_s")
                                        for name, key, _ in SURFACES + [("shot-shot", "shot-shot", None)]}
    return out


def row(label, unit, a, a_se, b, b_se):
    se = math.sqrt((a_se if not math.isnan(a_se) else 0.0) ** 2 + (b_se if not math.isnan(b_se) else 0.0) ** 2)
    diff = (b - a) / a * 100.0 if a else float("nan")
    z = (b - a) / se if se > 0 else float("nan")
    verdict = "within noise" if not math.isnan(z) and abs(z) <= 3.0 else ("DIFFERS" if not math.isnan(z) else "")
    fmt = lambda v, e: f"{v:10.4g} +- {e:<8.3g}" if not math.isnan(e) else f"{v:10.4g}" + " " * 12
    print(f"{label:28s} {unit:8s} {fmt(a, a_se)} {fmt(b, b_se)} {diff:+8.2f} % {z:+7.2f} SE  {verdict}")
    return {"liggghts": a, "liggghts_se": a_se, "peensim": b, "peensim_se": b_se, "difference_percent": diff, "z": z,
            "verdict": verdict}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--duration", type=float, required=True)
    ap.add_argument("--settle", type=float, required=True)
    ap.add_argument("--case", choices=("rod", "plate"), default="rod")
    a = ap.parse_args()
    use_case(a.case)
    part = a.case
    lig = summarise_liggghts(a.outdir)
    pee = summarise_peensim(a.outdir, a.settle, a.duration)
    with open(sorted(glob.glob(os.path.join(a.outdir, "liggghts*", "liggghts_stats.json")))[0]) as f:
        P = json.load(f)["params"]
    print(f"\n{part} scene, Hertz-Mindlin (E {P['young_pa'] / 1e9:g} GPa, nu {P['poisson']:g}, e {P['restitution']:g}, "
          f"f {P['friction']:g}, {P['shots']} shot), window {a.settle}-{a.duration} s; "
          f"LIGGGHTS {lig['runs']} run(s), peensim soft {pee['runs']} run(s) (seeds); 3 SE = 3 combined standard errors")
    print(f"{'':28s} {'':8s} {'LIGGGHTS 3.8':>22s} {'peensim soft':>22s} {'diff':>10s} {'':>10s}")
    out = {"window_s": [a.settle, a.duration], "liggghts": lig, "peensim": pee, "rows": {}}
    for name in (part, "sonotrode", "walls + lid", "shot-shot"):
        L, P = lig["surfaces"][name], pee["surfaces"][name]
        out["rows"][name + " rate"] = row(name + " impacts", "1/s", L["rate_per_s"], L["rate_se"], P["rate_per_s"], P["rate_se"])
    L, P = lig[part + "_speed"], pee[part + "_speed"]
    out["rows"][part + " mean vn"] = row(part + " normal speed mean", "m/s", L["mean"], L["mean_se"], P["mean"], P["mean_se"])
    for key in ("p10", "p50", "p90"):
        # A single LIGGGHTS run gives no spread of its percentiles: peensim's stands for both.
        lse = L[key + "_se"] if not math.isnan(L[key + "_se"]) else P[key + "_se"] * math.sqrt(max(1, pee["runs"]))
        out["rows"][part + " " + key] = row(part + " normal speed " + key, "m/s", L[key], lse, P[key], P[key + "_se"])
    if part != "rod":
        # The bed's energy seen on the other surfaces (peensim does not log shot-shot speeds).
        print("mean normal impact speed on the other surfaces (the bed's energy):")
        for name in ("sonotrode", "walls + lid"):
            L, P = lig["other_mean_speed"][name], pee["other_mean_speed"][name]
            out["rows"][name + " mean vn"] = row(name + " normal speed mean", "m/s", L["mean"], L["se"], P["mean"], P["se"])
    ratio_quiet = lig["wall_per_sim_s_no_output"] / pee["wall_per_sim_s"]
    ratio_dump = lig["wall_per_sim_s_with_contact_output"] / pee["wall_per_sim_s"]
    print(f"\nwall time per simulated second: LIGGGHTS {lig['wall_per_sim_s_no_output']:.1f} s (its loop, contact output left out; "
          f"{lig['wall_per_sim_s_with_contact_output']:.1f} s writing the contacts), peensim {pee['wall_per_sim_s']:.3f} s (its run loop, writing impacts.csv)")
    print(f"peensim is {ratio_dump:.0f}x faster than the LIGGGHTS run that wrote the contacts these statistics come from, "
          f"{ratio_quiet:.0f}x faster than LIGGGHTS's loop alone")
    out["speed_ratio"] = ratio_quiet
    out["speed_ratio_with_contact_output"] = ratio_dump
    with open(os.path.join(a.outdir, "side_by_side.json"), "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
