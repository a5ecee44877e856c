#!/usr/bin/env python3
"""The table of tests/validation/time_to_coverage.sh: forecasts of the time to 98 % against the
time the long runs reached it (python3's standard library only).

    python3 time_to_coverage_table.py DIR [--md FILE]

DIR holds <case>-s<seed>/ run directories with truth.json (the whole run's analysis) and
forecast-<T>.json (the analysis of its first T s). Per case and run length T: of the seeds whose
forecast gives a number, how many 95 % intervals hold the truth, for the whole part, "everywhere"
and every region (the worst region's count too); how many said "too short"; and the forecasts'
relative errors (mean and largest) against the truth.
"""
import glob
import json
import os
import re
import sys
from collections import defaultdict

TIMED = ("reached", "forecast")


def areas(figures):
    """{area name: time_to_target object} of the first component: whole, everywhere, regions."""
    c = figures["components"][0]
    out = {"whole": c.get("time_to_target"), "everywhere": c.get("time_to_target_everywhere")}
    for r in c.get("regions", []):
        if not r.get("excluded") and r.get("time_to_target", {}).get("status") not in (None, "none"):
            out["region:" + r["region"]] = r["time_to_target"]
    return out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    md = sys.argv[sys.argv.index("--md") + 1] if "--md" in sys.argv else None
    runs = defaultdict(list)  # case -> [(seed, dir)]
    for d in sorted(glob.glob(os.path.join(root, "*-s*"))):
        m = re.match(r"(.+)-s(\d+)$", os.path.basename(d))
        if m and os.path.isfile(os.path.join(d, "truth.json")):
            runs[m.group(1)].append((int(m.group(2)), d))
    lines = [
        "| case | seeds | run | whole part: truth in the 95 % interval | everywhere | regions (worst region) | too short (whole / everywhere / regions) "
        "| error, whole part: mean (largest) | everywhere | regions |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    truths = []
    for case, seeds in sorted(runs.items()):
        truth = {s: areas(json.load(open(os.path.join(d, "truth.json")))) for s, d in seeds}
        whole_truth = [truth[s]["whole"]["time_s"] for s, _ in seeds if truth[s]["whole"]["status"] == "reached"]
        every_truth = [truth[s]["everywhere"]["time_s"] for s, _ in seeds if truth[s]["everywhere"]["status"] == "reached"]
        truths.append((case, len(seeds), whole_truth, every_truth))
        lengths = sorted({int(re.search(r"forecast-(\d+)", f).group(1)) for _, d in seeds for f in glob.glob(os.path.join(d, "forecast-*.json"))})
        for T in lengths:
            held = defaultdict(lambda: [0, 0])  # kind -> [held, with a number]
            short = defaultdict(int)
            errors = defaultdict(list)
            per_region = defaultdict(lambda: [0, 0])
            for s, d in seeds:
                path = os.path.join(d, f"forecast-{T}.json")
                if not os.path.isfile(path):
                    continue
                forecast = areas(json.load(open(path)))
                for name, f in forecast.items():
                    t = truth[s].get(name)
                    if f is None or t is None or t.get("status") != "reached":
                        continue
                    kind = "region" if name.startswith("region:") else name
                    if f["status"] == "too_short":
                        short[kind] += 1
                        continue
                    if f["status"] not in TIMED:
                        continue
                    true = t["time_s"]
                    high = f["high_s"] if f["high_s"] is not None else float("inf")
                    inside = f["low_s"] <= true <= high
                    held[kind][0] += inside
                    held[kind][1] += 1
                    errors[kind].append((f["time_s"] - true) / true)
                    if kind == "region":
                        per_region[name][0] += inside
                        per_region[name][1] += 1

            def frac(kind):
                h, n = held[kind]
                return f"{h}/{n}" if n else "-"

            def err(kind):
                e = errors[kind]
                if not e:
                    return "-"
                worst = max(e, key=abs)
                return f"{100 * sum(e) / len(e):+.1f} % ({100 * worst:+.1f} %)"

            worst = min(per_region.items(), key=lambda kv: kv[1][0] / kv[1][1] if kv[1][1] else 1.0, default=None)
            regions = frac("region") + (f" ({worst[0][7:]}: {worst[1][0]}/{worst[1][1]})" if worst else "")
            lines.append(
                f"| {case} | {len(seeds)} | {T} s | {frac('whole')} | {frac('everywhere')} | {regions} | "
                f"{short['whole']} / {short['everywhere']} / {short['region']} | {err('whole')} | {err('everywhere')} | {err('region')} |"
            )
    lines.append("")
    lines.append("| case | seeds | truth: whole part reaches 98 % (s), min-max | everywhere (s), min-max |")
    lines.append("|---|---|---|---|")
    for case, n, w, e in truths:
        rng = lambda v: f"{min(v):.0f}-{max(v):.0f} ({len(v)} reached)" if v else "not reached"
        lines.append(f"| {case} | {n} | {rng(w)} | {rng(e)} |")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if md:
        with open(md, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
