#!/usr/bin/env python3
"""Bookkeeping of the extremes matrix (tests/extremes/run.sh): standard library only.

  extremes.py row --case NAME --what TEXT --duration S --step DIR --event DIR [--cylinder SEGMENTS] [--closed-part]
      reads each scheme's run (summary.json, impacts.csv of the logged part), prints one text row
      and appends the row as one JSON line to --out FILE.
  extremes.py report ROWS.jsonl [--tube LOG] [--md FILE] [--mode TEXT] [--wall S]
      prints the table and the PASS/FAIL line, writes the Markdown table; exit 1 on any failure.
  extremes.py header
      prints the header of the text rows.

Impact statistics on the logged part follow `peensim bench` (src/app/bench/bench_job.cpp): standard
errors by batch means over 10 equal time batches, the mean normal speed's by the ratio estimator,
and a difference within noise when it is at most k combined standard errors (k sqrt(SE_step^2 +
SE_event^2)). The standard errors are estimated from 10 batches each, so the difference in SE
follows Student's t with Welch-Satterthwaite degrees of freedom (~18), not the normal law: k is
its quantile with the chance a 3 SE comparison has under the normal law (0.27 %), ~3.6 for 18
degrees of freedom (`peensim bench` still prints 3 SE). A mean speed without impacts in one run is
not compared (n/a).
Batch means estimate the noise only when the impacts spread over the run: when either run has
impacts in fewer than MIN_BATCHES of the 10 batches (a lone shot that hits the part a few times),
the schemes are not compared ("too few impacts"; the counts are in the row).
"""
import argparse
import json
import math
import os
import re
import sys

BATCHES = 10        # time batches for the batch-means standard errors (kBenchBatches)
NORMAL_SE = 3.0     # -, the normal-law bound whose chance (0.27 %) the t bound keeps
MIN_BATCHES = 5     # batches with impacts each run needs before its noise is estimated


class Batched:
    """Impact count and normal speeds of one component over a run, by time batch."""

    def __init__(self, duration_s):
        self.duration = duration_s
        self.count = 0
        self.speed_sum = 0.0
        self.n = [0] * BATCHES
        self.s = [0.0] * BATCHES

    def add(self, t, vn):
        k = min(max(int(math.floor(t / self.duration * BATCHES)), 0), BATCHES - 1)
        self.count += 1
        self.speed_sum += vn
        self.n[k] += 1
        self.s[k] += vn

    def rate(self):
        return self.count / self.duration

    def batches_with_impacts(self):
        return sum(1 for n in self.n if n > 0)

    def rate_se(self):
        b = self.duration / BATCHES
        m = self.rate()
        sq = sum((n / b - m) ** 2 for n in self.n)
        return math.sqrt(sq / (BATCHES * (BATCHES - 1.0)))

    def mean(self):
        return self.speed_sum / self.count if self.count else math.nan

    def mean_se(self):
        if not self.count:
            return math.nan
        m = self.mean()
        sq = sum((s - m * n) ** 2 for n, s in zip(self.n, self.s))
        return math.sqrt(BATCHES / (BATCHES - 1.0) * sq) / self.count


def incomplete_beta(x, a, b):
    """Regularized incomplete beta I_x(a, b) by its continued fraction (modified Lentz)."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    if x > (a + 1.0) / (a + b + 2.0):
        return 1.0 - incomplete_beta(1.0 - x, b, a)
    log_front = a * math.log(x) + b * math.log1p(-x) - (math.lgamma(a) + math.lgamma(b) - math.lgamma(a + b))
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    f = d
    for m in range(1, 1001):
        for coefficient in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                            -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + coefficient * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + coefficient / c
            c = c if abs(c) > tiny else tiny
            f *= c * d
        if abs(c * d - 1.0) < 1e-15:
            break
    return math.exp(log_front) * f / a


def t_quantile(p, dof):
    """The t with P(|T| > t) = p for Student's T with dof degrees of freedom."""
    if not dof < 1e7:
        tail = lambda t: math.erfc(t / math.sqrt(2.0))
    else:
        tail = lambda t: incomplete_beta(dof / (dof + t * t), 0.5 * dof, 0.5)
    lo, hi = 0.0, 1e3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if tail(mid) > p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def noise_bound(se_a, se_b):
    """k: the bound in combined standard errors of two batch-means estimates (see the docstring)."""
    va, vb = se_a * se_a, se_b * se_b
    denominator = (va * va + vb * vb) / (BATCHES - 1.0)
    dof = (va + vb) ** 2 / denominator if denominator > 0.0 else math.inf
    return t_quantile(math.erfc(NORMAL_SE / math.sqrt(2.0)), dof)


def difference(a, se_a, b, se_b):
    """(percent, bound percent, within noise) of b against a; None when there is nothing to compare."""
    if not all(math.isfinite(x) for x in (a, se_a, b, se_b)):
        return None
    bound = noise_bound(se_a, se_b) * math.hypot(se_a, se_b)
    within = abs(b - a) <= bound
    if a != 0.0:
        return 100.0 * (b - a) / abs(a), 100.0 * bound / abs(a), within
    return (0.0 if b == a else math.nan), math.nan, within


def read_scheme(directory, duration_s, cylinder_segments):
    """Figures of one `peensim run` output directory."""
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    health = summary["health_counters"]
    stages = summary.get("step_stage_time_s", {})
    # The stepping loop's wall time, without writing impacts.csv (record_impacts), as `peensim bench` times it.
    wall = summary["wall_time_s"] - stages.get("record_impacts", 0.0)
    logged = [c["component"] for c in summary.get("normal_speed", [])]
    stats = Batched(duration_s)
    inside = 0
    inside_worst = 0.0  # -, largest outward radial part / speed among impacts from inside
    caps = 0
    if cylinder_segments:
        # The rod and the generated cylinder: radius 5 mm, axis along y through x = 0, z = 20 mm in
        # their own (mesh) frame, 30 mm long (its end caps at |y| = 15 mm, flush with the chamber).
        limit = math.sin(math.pi / cylinder_segments)
        axis_z, half_length = 0.020, 0.015
    path = os.path.join(directory, "impacts.csv")
    with open(path) as f:
        header = f.readline().rstrip("\n").split(",")
        col = {name: i for i, name in enumerate(header)}
        it, ic, ivn = col["time_s"], col["component"], col["vn_in_mps"]
        ix, iy, iz = col["x_m"], col["y_m"], col["z_m"]
        ivx, ivy, ivz = col["vx_in_mps"], col["vy_in_mps"], col["vz_in_mps"]
        for line in f:
            r = line.split(",")
            stats.add(float(r[it]), float(r[ivn]))
            if not cylinder_segments:
                continue
            y = float(r[iy])
            if abs(y) >= half_length - 1e-9:
                caps += 1  # on an end cap (or its rim): the radial test does not apply
                continue
            x, z = float(r[ix]), float(r[iz]) - axis_z
            vx, vy, vz = float(r[ivx]), float(r[ivy]), float(r[ivz])
            rho = math.hypot(x, z)
            speed = math.sqrt(vx * vx + vy * vy + vz * vz)
            if rho == 0.0 or speed == 0.0:
                continue
            outward = (vx * x + vz * z) / rho  # m/s, radial part of the approach velocity, outward positive
            # Approaching a facet from outside, the velocity points into it; the facet's normal is
            # within pi/segments of the radial direction, so the outward radial part is at most
            # sin(pi/segments) of the speed. More is an impact from inside the part.
            if outward > limit * speed * (1.0 + 1e-9):
                inside += 1
                inside_worst = max(inside_worst, outward / speed)
    return {
        "finished": bool(summary.get("finished", False)),
        "simulated_s": summary["simulated_time_s"],
        "wall_s": wall,
        "wall_per_sim_s": wall / summary["simulated_time_s"] if summary["simulated_time_s"] > 0 else math.nan,
        "logged": logged,
        "impacts": stats.count, "batches_with_impacts": stats.batches_with_impacts(),
        "rate": stats.rate(), "rate_se": stats.rate_se(),
        "mean_vn": stats.mean(), "mean_vn_se": stats.mean_se(),
        "lost": health["shot_lost"], "non_finite": health["non_finite"],
        "deep": health["deep_penetrations"], "unresolved": health["unresolved_contacts"],
        "engine_errors": health.get("engine_errors", 0),  # serious; in builds that count it
        "fallbacks": health.get("search_fallbacks", 0),  # the net under "time advances" (not a failure: counted)
        "inside": inside if cylinder_segments else None, "inside_worst": inside_worst, "cap_impacts": caps,
    }


TIMED_OUT = 124  # `timeout`'s exit status: the run exceeded its wall-time bound (run.sh)


def fmt(v, digits):
    return "-" if v is None or not math.isfinite(v) else f"{v:.{digits}f}"


def pair(a, b):
    return f"{a} / {b}"


def row_failures(row):
    """The failed assertions of one case, as 'scheme counter value' texts."""
    out = []
    for scheme in ("step", "event"):
        s = row.get(scheme)
        if s is None:
            code = row.get(scheme + "_exit")
            if code == TIMED_OUT:
                out.append(f"{scheme} exceeded the wall-time bound ({row.get('wall_bound_s')} s for {row['duration_s']:g} simulated s)")
            else:
                out.append(f"{scheme} run failed (exit {code})")
            continue
        if not s["finished"]:
            out.append(f"{scheme} did not finish")
        for key in ("lost", "non_finite", "engine_errors", "deep", "unresolved"):
            if s.get(key):
                out.append(f"{scheme} {key} {s[key]}")
        if s["inside"]:
            out.append(f"{scheme} inside {s['inside']} (worst outward radial part {s['inside_worst']:.3f} of the speed)")
    if row.get("verdict") == "DIFFERS":
        out.append("schemes differ: " + row["difference"])
    return out


def judge(row):
    """The schemes' comparison, verdict and failed assertions of a row, from its runs' figures
    (the report judges again, so rows written by an older rule are judged by this one)."""
    s, e = row.get("step"), row.get("event")
    if s and e:
        row["speedup"] = s["wall_s"] / e["wall_s"] if e["wall_s"] > 0 else math.nan
        rate = difference(s["rate"], s["rate_se"], e["rate"], e["rate_se"])
        speed = difference(s["mean_vn"], s["mean_vn_se"], e["mean_vn"], e["mean_vn_se"])
        within = all(d is None or d[2] for d in (rate, speed))
        parts = []
        for name, d in (("rate", rate), ("mean vn", speed)):
            parts.append(f"{name} n/a" if d is None else f"{name} {d[0]:+.1f} % (bound {d[1]:.1f} %)")
        row["difference"] = ", ".join(parts)
        row["verdict"] = "within noise" if within else "DIFFERS"
        if s["impacts"] == 0 and e["impacts"] == 0:
            row["verdict"] = "no impacts"
        elif min(s["batches_with_impacts"], e["batches_with_impacts"]) < MIN_BATCHES:
            row["verdict"] = "too few impacts"
            row["difference"] = (f"not compared: {s['impacts']} / {e['impacts']} impacts in "
                                 f"{s['batches_with_impacts']} / {e['batches_with_impacts']} of {BATCHES} batches")
    else:
        row["speedup"] = math.nan
        row["difference"] = "-"
        row["verdict"] = "-"
    row["failures"] = row_failures(row)


def make_row(a):
    row = {"case": a.case, "what": a.what, "duration_s": a.duration, "closed_part": a.closed_part,
           "cylinder_segments": a.cylinder, "wall_bound_s": a.wall_bound}
    runs = {}
    for scheme, directory, code in (("step", a.step, a.step_exit), ("event", a.event, a.event_exit)):
        row[scheme + "_exit"] = code
        try:
            runs[scheme] = read_scheme(directory, a.duration, a.cylinder) if code == 0 else None
        except (OSError, KeyError, ValueError) as e:
            print(f"extremes.py: {a.case} {scheme}: cannot read {directory}: {e}", file=sys.stderr)
            runs[scheme] = None
        row[scheme] = runs[scheme]
    judge(row)
    return row


def cells(row):
    s, e = row.get("step"), row.get("event")

    def both(key, digits):
        return pair(fmt(s[key], digits) if s else "-", fmt(e[key], digits) if e else "-")

    def counts(key):
        return pair(str(s[key]) if s else "-", str(e[key]) if e else "-")

    if row["cylinder_segments"]:
        inside = counts("inside")
    else:
        inside = "(deep)" if row["closed_part"] else "-"
    return [row["case"], f"{row['duration_s']:g}", both("wall_per_sim_s", 3), fmt(row["speedup"], 2) + "x",
            both("rate", 0), both("mean_vn", 3), counts("lost"), counts("deep"), counts("unresolved"), inside,
            str(e.get("fallbacks", 0)) if e else "-", row["verdict"]]


HEADER = ["case", "sim s", "wall s/sim s step / event", "event speed-up", "part impacts/s step / event",
          "part mean vn m/s step / event", "lost", "deep", "unresolved", "inside", "search fallbacks (event)", "schemes"]


def text_line(values, widths):
    return "  ".join(v.ljust(w) for v, w in zip(values, widths)).rstrip()


WIDTHS = [26, 5, 17, 8, 17, 15, 5, 5, 10, 8, 9, 12]


def cmd_row(a):
    row = make_row(a)
    with open(a.out, "a") as f:
        f.write(json.dumps(row) + "\n")
    print(text_line(cells(row), WIDTHS) + ("" if not row["failures"] else "   FAIL: " + "; ".join(row["failures"])), flush=True)
    return 0


TUBE_LINE = re.compile(r"^\[ tube sum\] ")


def tube_summary(log_path, exit_code):
    """(lines for the report, failures) from the EngineTubeLong output."""
    lines, failed = [], []
    if not log_path or not os.path.exists(log_path):
        return lines, ["tube: no output"]
    text = open(log_path).read()
    for line in text.splitlines():
        if TUBE_LINE.match(line):
            lines.append(line[len("[ tube sum] "):])
        m = re.match(r"^\[  FAILED  \] (\S+EngineTubeLong[^\s,]+)", line)
        if m and m.group(1) not in failed:
            failed.append(m.group(1))
    failures = ["tube " + f for f in failed]
    if not re.search(r"^\[==========\] \d+ tests? from .* ran\.", text, re.M):
        running = re.findall(r"^\[ RUN      \] (\S+)", text, re.M)
        failures.append(f"tube: the test binary stopped (exit {exit_code}) before finishing"
                        + (f", in {running[-1]}" if running else ""))
    elif exit_code not in (0, None) and not failed:
        failures.append(f"tube: the test binary exited with {exit_code}")
    return lines, failures


def cmd_report(a):
    rows = [json.loads(line) for line in open(a.rows) if line.strip()]
    for r in rows:
        judge(r)
    order = {name: i for i, name in enumerate(a.order.split(","))} if a.order else {}
    rows.sort(key=lambda r: order.get(r["case"], len(order)))
    failures = []
    print(text_line(HEADER, WIDTHS))
    for r in rows:
        print(text_line(cells(r), WIDTHS))
        failures += [f"{r['case']}: {f}" for f in r["failures"]]
    tube_lines, tube_failures = [], []
    for k, log in enumerate(a.tube):
        lines, fails = tube_summary(log, a.tube_exit[k] if k < len(a.tube_exit) else None)
        tube_lines += lines
        tube_failures += fails
    if tube_lines:
        print("# tube against the exact reference (EngineTubeLong):")
        for line in tube_lines:
            print("  " + line)
    failures += tube_failures
    for f in failures:
        print("FAILED " + f)
    verdict = "PASS" if not failures else f"FAIL ({len(failures)} failed assertions)"
    estimate = ""
    if a.to_full:
        # The stepping loops scale with simulated time; setup (meshes, placement) does not, and is small.
        loops = sum(r[s]["wall_s"] for r in rows for s in ("step", "event") if r.get(s))
        full_s = loops * a.to_full + a.tube_wall * a.tube_to_full
        estimate = (f"estimated wall time of --full: {full_s:.0f} s = {full_s / 3600:.1f} h (stepping loops {loops:.0f} s x {a.to_full:g}"
                    + (f", tube {a.tube_wall:.0f} s x {a.tube_to_full:g}" if a.tube_wall else "") + ")")
        print(estimate)
    print(f"{verdict}: {len(rows)} cases x 2 schemes" + (f", {a.mode}" if a.mode else "") +
          (f", wall {a.wall:.0f} s" if a.wall else ""))
    if a.md:
        with open(a.md, "w") as f:
            if a.mode:
                f.write(f"Mode: {a.mode}" + (f"; wall time {a.wall:.0f} s" if a.wall else "") + ".\n\n")
            f.write("| " + " | ".join(HEADER) + " |\n|" + "---|" * len(HEADER) + "\n")
            for r in rows:
                f.write("| " + " | ".join(cells(r)) + " |\n")
            f.write("\n")
            if tube_lines:
                f.write("Tube against the exact reference (`EngineTubeLong`):\n\n")
                for line in tube_lines:
                    f.write(f"    {line}\n")
                f.write("\n")
            for fl in failures:
                f.write(f"- FAILED {fl}\n")
            f.write(f"\n{verdict}\n")
            if estimate:
                f.write(f"\n{estimate}\n")
    return 0 if not failures else 1


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("row")
    r.add_argument("--case", required=True)
    r.add_argument("--what", default="")
    r.add_argument("--duration", type=float, required=True)
    r.add_argument("--step", required=True)
    r.add_argument("--event", required=True)
    r.add_argument("--step-exit", type=int, default=0)
    r.add_argument("--event-exit", type=int, default=0)
    r.add_argument("--cylinder", type=int, default=0, help="facets round the cylinder part (inside check)")
    r.add_argument("--closed-part", action="store_true", help="a closed part without the radial check (the gear)")
    r.add_argument("--wall-bound", type=float, default=0.0, help="s, the wall-time bound each scheme's run had (run.sh)")
    r.add_argument("--out", required=True)
    t = sub.add_parser("report")
    t.add_argument("rows")
    t.add_argument("--order", default="")
    t.add_argument("--tube", action="append", default=[], help="an EngineTubeLong log (repeat per tube process)")
    t.add_argument("--md", default="")
    t.add_argument("--mode", default="")
    t.add_argument("--wall", type=float, default=0.0)
    t.add_argument("--tube-exit", type=int, action="append", default=[], help="exit code of each --tube's process, in order")
    t.add_argument("--tube-wall", type=float, default=0.0, help="s, wall time of the tube processes, summed")
    t.add_argument("--to-full", type=float, default=0.0, help="simulated time of --full over this run's (cases)")
    t.add_argument("--tube-to-full", type=float, default=0.0, help="the same for the tube")
    sub.add_parser("header")
    a = p.parse_args()
    if a.command == "header":
        print(text_line(HEADER, WIDTHS))
        return 0
    return cmd_row(a) if a.command == "row" else cmd_report(a)


if __name__ == "__main__":
    sys.exit(main())
