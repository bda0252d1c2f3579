#!/usr/bin/env python3
"""Generate README.md's table of measured results from the files in bench/results/.

Every number in the table is read or computed here from a result file written by a bench
program (bench/README.md has the command that regenerates each file); none is typed. The
targets in the "target" column are the project's goals (constants below), not
measurements; whether each is reached is decided from the measured number.

The table sits in README.md between the lines ``<!-- results:begin -->`` and
``<!-- results:end -->``; the "what structure to learn" table (learning curves per
parameterization, from bench/learning_curve_table.py's summaries of the learning-curve CSVs)
between ``<!-- structure:begin -->`` and ``<!-- structure:end -->``.

    python3 scripts/readme_results.py            # print the generated block
    python3 scripts/readme_results.py --write    # rewrite README.md's block in place
    python3 scripts/readme_results.py --check    # exit 1 (with a diff) if README.md differs

Exit status 2 when a result file, a line it needs or the README's markers are missing.

``--readme PATH`` and ``--results DIR`` point at another README or result directory.
Python 3 standard library only.
"""
import argparse
import csv
import difflib
import json
import math
import os
import re
import statistics
import sys

BEGIN = "<!-- results:begin -->"
END = "<!-- results:end -->"
STRUCTURE_BEGIN = "<!-- structure:begin -->"
STRUCTURE_END = "<!-- structure:end -->"
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from learning_curve_table import load_runs, summary  # noqa: E402  (bench/, standard library only)

# The project's goals (not measurements).
TARGET_MM_SOLVED = 0.95     # share of the shared Maros-Meszaros set solved at 1e-9
TARGET_MM_SGM_RATIO = 0.5   # shifted geometric mean of run time, lcprelax / Clp barrier
TARGET_BACKWARD = 0.2       # backward / forward time of a QP solve (n >= 10,000)
TARGET_PILE_SLOPE = 1.3     # log-log slope of the pile's CPU time per step against contacts
TARGET_THREADS = 1.8        # learning samples/s, 2 threads / 1 thread
TARGET_LEARN_ERROR = 0.01   # largest relative parameter error for "recovered"
TARGET_FC2D_2020_SECONDS = 2.0  # Lemke on the 2,020-contact granular fc2d problem
TARGET_QP_LAYER = 10.0      # dense batched PyTorch reference / QpLayer, batch 1,024, 2 threads
TARGET_BOX2D_RATIO = 10.0   # settled pile, lcprelax CPU time per step / Box2D's (200, 1,000, 2,000 bodies)
TARGET_LCP_PILE_SECONDS = 2.0  # LCP contact model, 500-body pile, wall time per step


class ResultError(Exception):
    pass


# ---------------------------------------------------------------- reading
def path_of(results, name):
    return os.path.join(results, name)


def read_csv(results, name):
    try:
        with open(path_of(results, name), newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise ResultError(f"cannot read bench/results/{name}: {e}")


def read_text(results, name):
    try:
        with open(path_of(results, name), encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        raise ResultError(f"cannot read bench/results/{name}: {e}")


def search(pattern, text, name):
    m = re.search(pattern, text, re.MULTILINE)
    if not m:
        raise ResultError(f"bench/results/{name}: no line matches /{pattern}/")
    return m


def only(rows, name, **keys):
    found = [r for r in rows if all(r[k] == v for k, v in keys.items())]
    if len(found) != 1:
        raise ResultError(f"bench/results/{name}: {len(found)} rows with {keys}, expected 1")
    return found[0]


# ---------------------------------------------------------------- formatting
def g(x, digits=2):
    """x with `digits` significant digits, plain notation between 1e-3 and 1e5."""
    x = float(x)
    if x == 0 or not math.isfinite(x):
        return str(x) if not math.isfinite(x) else "0"
    e = int(math.floor(math.log10(abs(x))))
    if -3 <= e < 6:
        decimals = digits - 1 - e
        if decimals < 0:
            return f"{round(x, decimals):,.0f}"
        return f"{x:,.{decimals}f}"
    return f"{x:.{digits - 1}e}".replace("e-0", "e-").replace("e+0", "e").replace("e+", "e")


def pct(x, digits=2):
    return g(100.0 * x, digits) + "%"


def seconds(x, digits=2):
    x = float(x)
    if x < 1e-3:
        return g(x * 1e6, digits) + " µs"
    if x < 1:
        return g(x * 1e3, digits) + " ms"
    return g(x, digits) + " s"


def goal(x):
    return f"{x:g}"


def verdict(reached):
    return "reached" if reached else "**not reached**"


def src(*names):
    return ", ".join(f"`{n}`" for n in names)


# ---------------------------------------------------------------- rows
def maros_meszaros(results, csv_name, txt_name, with_targets):
    rows = read_csv(results, csv_name)
    text = read_text(results, txt_name)
    n = len(rows)
    solved = sum(r["lcp_success"] == "1" for r in rows)
    clp = sum(r["clp_success"] == "1" for r in rows)
    clp_strict = sum(r["clp_success_strict"] == "1" for r in rows)
    eps = search(r"^Summary over (\d+) problems \(eps ([0-9.e+-]+), time limit (\d+) s", text, txt_name)
    if int(eps.group(1)) != n:
        raise ResultError(f"{txt_name} summarizes {eps.group(1)} problems, {csv_name} has {n}")
    limit = eps.group(3)
    lcp_sgm = float(search(r"^\s*lcprelax\s+success\s+(\d+).*sgm time ([0-9.]+) s", text, txt_name).group(2))
    clp_sgm = float(search(r"^\s*clp\s+success\s+(\d+).*sgm time ([0-9.]+) s", text, txt_name).group(2))
    ratio = lcp_sgm / clp_sgm
    what = f"Maros–Meszaros, {n} problems, solved at 1e-9 (time limit {limit} s)"
    res = (f"lcprelax {solved} / {n} ({pct(solved / n, 3)}); Clp barrier {clp} (lenient), "
           f"{clp_strict} (same strict test)")
    out = []
    if with_targets:
        out.append((what, res, f"≥ {goal(100 * TARGET_MM_SOLVED)}%: {verdict(solved / n >= TARGET_MM_SOLVED)}",
                    src(csv_name)))
        out.append((f"Maros–Meszaros, {n} problems, shifted geometric mean of run time (failures at the limit)",
                    f"lcprelax {seconds(lcp_sgm, 3)}, Clp barrier {seconds(clp_sgm, 3)}: ratio {g(ratio, 2)}",
                    f"≤ {goal(TARGET_MM_SGM_RATIO)}: {verdict(ratio <= TARGET_MM_SGM_RATIO)}", src(txt_name)))
    else:
        out.append((what + ", shifted geometric mean",
                    res + f"; {seconds(lcp_sgm, 2)} vs {seconds(clp_sgm, 3)} (ratio {g(ratio, 2)})",
                    "", src(csv_name, txt_name)))
    return out


def qp_backward(results):
    name, txt = "qp_scaling.csv", "qp_scaling.txt"
    rows = read_csv(results, name)
    worst = max(float(r["backward_over_forward"]) for r in rows)
    big = max(rows, key=lambda r: int(r["n"]))
    slope = float(search(r"^slope vs n \(all sizes.*forward CPU ([0-9.]+)", read_text(results, txt), txt).group(1))
    sizes = sorted(int(r["n"]) for r in rows)
    return [(f"QP backward pass / forward solve, random sparse QPs n = {sizes[0]:,}–{sizes[-1]:,}",
             f"≤ {g(worst, 2)} at every n; n = {int(big['n']):,}: forward {seconds(big['forward_cpu_s'])}, "
             f"backward {seconds(big['backward_cpu_s'])} CPU; forward time ∝ n^{g(slope, 3)}",
             f"≤ {goal(TARGET_BACKWARD)}: {verdict(worst <= TARGET_BACKWARD)}", src(name, txt))]


def lemke(results):
    name = "lemke_peers.csv"
    rows = read_csv(results, name)
    lcp = [r for r in rows if r["kind"] == "lcp"]
    files = sorted({r["problem"] for r in lcp})
    ours = sum(r["ok"] == "1" for r in lcp if r["solver"] == "lcprelax_sparse")
    theirs = sum(r["ok"] == "1" for r in lcp if r["solver"] == "siconos_lemke")
    out = [("Lemke on the Siconos LCP test files",
            f"lcprelax {ours} / {len(files)}, Siconos numerics' Lemke {theirs} / {len(files)}", "",
            src(name))]
    fc2d = [r for r in rows if r["kind"] == "fc2d" and r["solver"] == "lcprelax_purify"]
    for r in sorted(fc2d, key=lambda r: -int(r["contacts"]))[:2]:
        t = float(r["seconds"])
        lem = only(rows, name, problem=r["problem"], solver="siconos_fc2d_lemke")
        nsgs = only(rows, name, problem=r["problem"], solver="siconos_fc2d_nsgs")
        ok = "solved" if r["ok"] == "1" else f"not solved ({r['status']})"
        out.append((f"fc2d `{r['problem']}` ({int(r['contacts']):,} contacts), Lemke from a purified PGS start",
                    f"lcprelax {ok} in {seconds(t)}; time / Siconos Lemke {g(t / float(lem['seconds']), 2)} "
                    f"({seconds(lem['seconds'])}), / Siconos NSGS {g(t / float(nsgs['seconds']), 2)} "
                    f"({seconds(nsgs['seconds'])})", "", src(name)))
    big = "lemke_purify_2020.csv"
    r = only(read_csv(results, big), big, problem="fc2d_granularflowonwall_02020_00213", solver="lcprelax_purify")
    t = float(r["seconds"])
    out.append(("fc2d `fc2d_granularflowonwall_02020_00213` (2,020 contacts), Lemke from a purified PGS start, "
                "Siconos fc2d error ≤ 1e-10",
                f"{'solved' if r['ok'] == '1' else 'not solved (' + r['status'] + ')'} in {seconds(t)} "
                f"({int(r['iterations']):,} pivots, error {g(r['error'])})",
                f"≤ {goal(TARGET_FC2D_2020_SECONDS)} s: {verdict(r['ok'] == '1' and t <= TARGET_FC2D_2020_SECONDS)}",
                src(big)))
    return out


def pile_peers(results):
    # pile_peers.csv: each engine drops and settles its own pile; pile_peers_lcp_piles.csv:
    # every engine from a pile that the LCP model dropped and saved (run_pile_peers
    # --pile-scene). Each lcprelax row is compared with the Box2D row of its own file.
    name, saved = "pile_peers.csv", "pile_peers_lcp_piles.csv"
    rows = read_csv(results, name)
    sources = [(name, [r for r in rows if r["test"] == "pile"], ""),
               (saved, read_csv(results, saved), ", saved LCP pile")]
    ratios, pens, within, box_pen = [], [], [], []
    for source, piles, where in sources:
        for bodies in sorted({int(r["bodies"]) for r in piles}):
            box = only(piles, source, bodies=str(bodies), engine="box2d")
            box_pen.append(float(box["max_penetration"]))
            for r in piles:
                if int(r["bodies"]) == bodies and r["engine"] != "box2d":
                    model = {"lcprelax_lcp": "LCP model", "lcprelax_convex": "convex model"}[r["engine"]]
                    ratio = float(r['cpu_per_step']) / float(box['cpu_per_step'])
                    ratios.append(f"{model} {g(ratio, 2)}× ({bodies} bodies{where})")
                    pens.append(float(r["max_penetration"]))
                    if ratio <= TARGET_BOX2D_RATIO:
                        within.append((bodies, f"{model}, {bodies} bodies{where}"))
    pyr = {r["engine"]: float(r["drift"]) for r in rows if r["test"] == "pyramid"}
    return [("Settled pile, CPU time per step, lcprelax / Box2D 2.4",
             "; ".join(ratios),
             f"≤ {goal(TARGET_BOX2D_RATIO)}× at 200, 1,000 and 2,000 bodies: "
             f"{verdict({200, 1000, 2000} <= {b for b, _ in within})}"
             + (f" (within it: {'; '.join(t for _, t in within)})" if within else ""), src(name, saved)),
            ("Settled pile, largest penetration; resting 210-box pyramid, drift in 200 steps",
             f"lcprelax ≤ {g(max(pens) * 1e3, 2)} mm, Box2D {g(min(box_pen) * 1e3, 2)}–{g(max(box_pen) * 1e3, 2)} mm; "
             f"drift: LCP model {g(pyr['lcprelax_lcp'])} m, convex {g(pyr['lcprelax_convex'])} m, "
             f"Box2D {g(pyr['box2d'])} m", "", src(name, saved))]


def pile_scaling(results):
    name, txt = "pile_scaling.csv", "pile_scaling.txt"
    text = read_text(results, txt)
    slope = float(search(r"^slope log\(cpu s/step\) vs log\(contacts\), convex T=1: all sizes ([0-9.]+)",
                         text, txt).group(1))
    rows = [r for r in read_csv(results, name)
            if r["phase"] == "window" and r["model"] == "convex" and r["threads"] == "1"]
    big = max(rows, key=lambda r: int(r["bodies"]))
    small = min(rows, key=lambda r: int(r["bodies"]))
    return [("Pile step (convex model, 1 thread), CPU time against contacts",
             f"∝ contacts^{g(slope, 3)} from {g(float(small['contacts_mean']), 2)} to "
             f"{float(big['contacts_mean']):,.0f} contacts; {int(big['bodies']):,} bodies: "
             f"{seconds(big['cpu_per_step'])} per step",
             f"slope ≤ {goal(TARGET_PILE_SLOPE)}: {verdict(slope <= TARGET_PILE_SLOPE)}", src(name, txt))]


def lcp_pile(results):
    name = "pile_scaling_lcp_windows.csv"
    rows = [r for r in read_csv(results, name) if r["phase"] == "window" and r["bodies"] == "500"]
    if not rows:
        raise ResultError(f"bench/results/{name}: no 500-body window rows")
    rows.sort(key=lambda r: int(r["seed"]))
    times = [float(r["seconds_per_step"]) for r in rows]
    within = sum(t <= TARGET_LCP_PILE_SECONDS for t in times)
    per_seed = "; ".join(f"seed {r['seed']} {seconds(r['seconds_per_step'], 3)} ({float(r['work_mean']):,.0f} pivots)"
                         for r in rows)
    failed = sum(int(r["failed_islands"]) for r in rows)
    return [(f"Pile with the LCP contact model, 500 bodies, {rows[0]['steps']} steps after a 150-step convex "
             f"settle, wall time per step (1 thread)",
             f"{per_seed}; failed islands {failed}",
             f"≤ {goal(TARGET_LCP_PILE_SECONDS)} s: {verdict(within == len(rows))} "
             f"(within it: {within} of {len(rows)} seeds)", src(name))]


def lcp_pile_slope(results):
    name, txt = "pile_scaling_lcp_slope.csv", "pile_scaling_lcp_slope.txt"
    text = read_text(results, txt)
    slope = float(search(r"^slope log\(wall s/step\) vs log\(contacts\), lcp T=1: all sizes ([0-9.]+)",
                         text, txt).group(1))
    rows = [r for r in read_csv(results, name) if r["phase"] == "window" and r["model"] == "lcp"]
    big = max(rows, key=lambda r: int(r["bodies"]))
    small = min(rows, key=lambda r: int(r["bodies"]))
    return [("Pile with the LCP contact model (8-step windows after a 150-step convex settle, 1 thread), "
             "wall time per step against contacts",
             f"∝ contacts^{g(slope, 3)} from {float(small['contacts_mean']):,.0f} to "
             f"{float(big['contacts_mean']):,.0f} contacts; {int(big['bodies']):,} bodies: "
             f"{seconds(big['seconds_per_step'])} per step ({float(big['work_mean']):,.0f} pivots), "
             f"failed islands {sum(int(r['failed_islands']) for r in rows)}", "", src(name, txt))]


def lcp_pile_drop(results):
    # Seed 1 (the default scene) and seed 2, each one run with one build.
    files = (("seed 1", "pile_lcp_1000_drop.json"), ("seed 2", "pile_lcp_1000_drop_seed2.json"))
    runs = []
    for seed, name in files:
        try:
            runs.append((seed, json.loads(read_text(results, name))))
        except json.JSONDecodeError as e:
            raise ResultError(f"bench/results/{name}: {e}")
    first = runs[0][1]
    complete = all(run["failed_islands"] == 0 and run["steps"] == 400 for _, run in runs)
    parts = [f"{seed}: failed islands {run['failed_islands']}, inexact answers {run['inaccurate_islands']}; "
             f"{seconds(run['seconds_per_step'])} per step on average, up to {run['contacts_max']:,} contacts; "
             f"largest penetration {g(run['max_penetration'] * 1e3, 2)} mm" for seed, run in runs]
    return [(f"Pile with the LCP contact model, {first['bodies']:,} bodies dropped, {first['steps']} steps (1 thread)",
             "; ".join(parts),
             f"1,000 bodies, 400 steps, no failed island: {verdict(complete)}",
             src(files[0][1], "pile_lcp_1000_drop.txt", files[1][1]))]


def learn_block(results):
    name = "learn_convergence.csv"
    rows = [r for r in read_csv(results, name) if r["problem"] == "block" and r["init"] == "10x"]
    parts = []
    for method in ("hard", "relaxed", "convex"):
        mine = sorted((r for r in rows if r["method"] == method), key=lambda r: int(r["epoch"]))
        first, last = mine[0], mine[-1]
        hit = next((r for r in mine if float(r["error"]) <= TARGET_LEARN_ERROR), None)
        tail = (f"≤ 1% after {seconds(hit['seconds'])}" if hit else
                f"error {g(first['error'])} → {g(last['error'])} after {last['epoch']} epochs")
        parts.append(f"{method}: {tail}")
    return [("Learning μ of a sliding block from 10× the truth (Adam, 1 thread)", "; ".join(parts),
             "", src(name))]


def learn_scene(results):
    name = "learn_scene_recovery.csv"
    rows = read_csv(results, name)
    kinds = ("mu", "mass", "inertia", "vertex")

    def worst(r):
        return max(float(r[k]) for k in kinds)

    robust = [r for r in rows if re.fullmatch(r"relaxed_robust_30_seed\d+", r["run"])]
    plain = [r for r in rows if re.fullmatch(r"relaxed_30_seed\d+", r["run"])]
    lm = only(rows, name, run="convex_30_seed1")
    n_ok = sum(worst(r) <= TARGET_LEARN_ERROR for r in plain)
    return [("Recovering all 31 parameters of a 30-body pile from 25% off (largest relative error)",
             f"relaxed loss + robust loss: ≤ {pct(max(worst(r) for r in robust))} on {len(robust)} of "
             f"{len(robust)} seeds; relaxed without it: {n_ok} of {len(plain)} seeds ≤ 1% "
             f"(worst {pct(max(worst(r) for r in plain))}); convex loss + Levenberg–Marquardt on convex-model "
             f"data: {g(worst(lm))} in {lm['epochs']} epochs", "", src(name))]


def learn_cost(results):
    names = ("learn_scene_small.csv", "learn_scene_large.csv")
    rows = [r for n in names for r in read_csv(results, n) if r["method"] == "relaxed"]
    ratios = [float(r["ratio"]) for r in rows]
    big = max(rows, key=lambda r: int(r["contacts"]))
    return [("Relaxed loss + gradient of one scene step / one simulator step",
             f"{g(min(ratios), 3)}–{g(max(ratios), 3)} ({rows and min(int(r['contacts']) for r in rows)}–"
             f"{int(big['contacts']):,} contacts; {int(big['bodies']):,} bodies: {seconds(big['evaluate_s'])})",
             "", src(*names))]


def learn_hard_warm(results):
    name = "learn_hard_warm_basis.txt"
    text = read_text(results, name)
    found = re.findall(r"time cold / stored: ([0-9.]+); pivots cold / stored: ([0-9.]+)", text)
    if not found:
        raise SystemExit(f"{name}: no 'time cold / stored' line")
    time = [float(t) for t, _ in found]
    piv = [float(p) for _, p in found]
    return [("Hard-loss scene training with each transition's stored Lemke bases / cold starts "
             "(30 and 100 bodies, same run)",
             f"{g(min(time), 3)}–{g(max(time), 3)}× less time, {g(min(piv), 3)}–{g(max(piv), 3)}× fewer pivots "
             f"({len(found)} runs)", "", src(name))]


def learn_threads(results):
    name = "learn_throughput.csv"
    rows = read_csv(results, name)
    two = [r for r in rows if r["ranks"] == "1" and r["threads"] == "2"]
    one = [r for r in rows if r["ranks"] == "1" and r["threads"] == "1"]
    lo = min(float(r["speedup_vs_1x1"]) for r in two)
    hi = max(float(r["speedup_vs_1x1"]) for r in two)
    rate = [float(r["samples_per_s"]) for r in one]
    return [("Learning throughput (block and polygon; hard, relaxed, convex), 2 threads / 1 thread",
             f"{g(lo, 3)}–{g(hi, 3)} (one run); 1 thread: {g(min(rate), 3)}–{g(max(rate), 3)} samples/s",
             f"≥ {goal(TARGET_THREADS)}: {verdict(lo >= TARGET_THREADS)}", src(name))]


def qp_layer(results):
    name = "qp_layer.csv"
    rows = read_csv(results, name)
    big = only(rows, name, batch="1024", threads="2", engine="dense")
    one = only(rows, name, batch="1024", threads="1", engine="dense")
    sparse = only(rows, name, batch="1024", threads="2", engine="sparse")
    ratio = float(big["reference_over_lcprelax"])
    return [("PyTorch `QpLayer` forward + backward per sample, relaxed block QP (9 variables), batch 1,024, "
             "against a dense batched PyTorch interior point",
             f"2 threads: lcprelax {g(big['lcprelax_us_per_sample'])} µs (dense engine, the default here; "
             f"sparse engine {g(sparse['lcprelax_us_per_sample'])} µs), reference "
             f"{g(big['reference_us_per_sample'])} µs (reference / lcprelax {g(ratio)}); 1 thread: "
             f"{g(one['lcprelax_us_per_sample'])} µs vs {g(one['reference_us_per_sample'])} µs",
             f"≥ {goal(TARGET_QP_LAYER)}: {verdict(ratio >= TARGET_QP_LAYER)}", src(name))]


def ratio_name(case):
    """'plank 1000000x on boxes' -> 'plank 1e6× on boxes'."""
    return re.sub(r"\b1(0{3,})x\b", lambda m: f"1e{len(m.group(1))}×", case)


def stiff(results):
    name = "stiff_report.csv"
    rows = read_csv(results, name)
    bad = [r for r in rows if r["status"].startswith("failed")]
    names = "; ".join(f"{ratio_name(r['case'])} ({r['model']})" for r in bad)
    return [("Stiff and extreme cases (mass ratios, μ = 0…1e6, Δt 1e-6…0.1 s, Murty, infeasible, NaN)",
             f"{len(rows) - len(bad)} of {len(rows)} end with a solution or the expected status; "
             f"failed islands in {len(bad)}: {names}", "", src(name))]


def softening(results):
    name = "softening.csv"
    rows = [r for r in read_csv(results, name) if r["scene"] == "pile"]
    pen = "; ".join(f"{r['softening']} {g(float(r['max_penetration']) * 1e3, 2)} mm" for r in rows)
    gain = max(float(r["max_step_energy_gain"]) for r in rows)
    # run_softening's default: one post-stabilization pass (the simulator's 5 would project
    # every softening's overlap to the 0.1 mm slop)
    return [(f"Convex model's normal softenings, falling pile ({rows[0]['steps']} steps, one position "
             "projection per step): penetration, largest one-step energy gain",
             f"{pen}; energy gain {g(gain)}", "", src(name))]


def fragility(results):
    name = "fragility.csv"
    rows = read_csv(results, name)
    err = [float(r["error"]) for r in rows]
    slopes = sum(math.isfinite(float(r["slope_derived"])) for r in rows)
    txt = "fragility.txt"
    worst = search(r"^worst error over measurable thresholds and slopes: ([0-9.e+-]+)",
                   read_text(results, txt), txt).group(1)
    return [("Stick/slip fragility of the LCP: closed-form thresholds (`docs/structure.md`) vs Lemke",
             f"{len(err)} thresholds and {slopes} slopes, worst disagreement {g(worst)}",
             "", src(name, txt))]


def generate(results):
    rows = []
    rows += maros_meszaros(results, "maros_meszaros_shared64.csv", "maros_meszaros_shared64.txt", True)
    rows += maros_meszaros(results, "maros_meszaros.csv", "maros_meszaros.txt", False)
    rows += qp_backward(results)
    rows += lemke(results)
    rows += pile_peers(results)
    rows += pile_scaling(results)
    rows += lcp_pile(results)
    rows += lcp_pile_slope(results)
    rows += lcp_pile_drop(results)
    rows += learn_block(results)
    rows += learn_scene(results)
    rows += learn_cost(results)
    rows += learn_hard_warm(results)
    rows += learn_threads(results)
    rows += qp_layer(results)
    rows += stiff(results)
    rows += softening(results)
    rows += fragility(results)
    lines = [BEGIN,
             "<!-- generated by scripts/readme_results.py from bench/results/; edit the script, "
             "not this table -->",
             "| measurement | result | target | file in `bench/results/` |",
             "|---|---|---|---|"]
    for what, result, target, source in rows:
        cells = [c.replace("|", "\\|") for c in (what, result, target, source)]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append(END)
    return "\n".join(lines) + "\n"


def generate_structure(results):
    """Per model, parameterization and loss: the training transitions for a median held-out
    next-state error <= 1%, and the median error and stick/slip mode error at N = 1,000 (or
    the largest N run)."""
    lines = [STRUCTURE_BEGIN,
             "<!-- generated by scripts/readme_results.py from bench/results/learning_curves*.csv; "
             "edit the script, not this table -->",
             "| model | parameterization | loss | transitions for median error ≤ 1% | N | "
             "median next-state error at N | stick/slip mode error at N |",
             "|---|---|---|---|---|---|---|"]
    tables = [("learning_curves.csv", ("param", "method"), lambda k: ("block (1-D)",) + k),
              ("learning_curves_scene.csv", ("scene", "param", "method"), lambda k: k)]
    for name, fields, label in tables:
        if not os.path.exists(path_of(results, name)):
            raise ResultError(f"cannot read bench/results/{name}")
        runs, order = load_runs([path_of(results, name)], fields)
        for key in order:
            _, errs, med, _, n, mode = summary(runs[key])
            model, param, loss = label(key)
            median = statistics.median(errs[n])
            lines.append(f"| {model} | {param} | {loss} | {med} | {n:,} | {g(median)} | {g(mode)} |")
    lines.append(STRUCTURE_END)
    return "\n".join(lines) + "\n"


def split(text, path, begin=BEGIN, end_marker=END):
    b, e = text.find(begin), text.find(end_marker)
    if b < 0 or e < b:
        raise ResultError(f"{path}: the markers {begin} and {end_marker} were not found (in this order)")
    end = text.find("\n", e)
    end = len(text) if end < 0 else end + 1
    return text[:b], text[b:end], text[end:]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help="rewrite the README's block in place")
    mode.add_argument("--check", action="store_true", help="exit 1 with a diff if the README's block differs")
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"))
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    args = ap.parse_args(argv)
    try:
        blocks = [(BEGIN, END, generate(args.results)),
                  (STRUCTURE_BEGIN, STRUCTURE_END, generate_structure(args.results))]
        if not (args.write or args.check):
            sys.stdout.write("".join(b for _, _, b in blocks))
            return 0
        with open(args.readme, encoding="utf-8") as f:
            text = f.read()
        new_text, diffs = text, []
        for begin, end, block in blocks:
            head, old, tail = split(new_text, args.readme, begin, end)
            if old != block:
                diffs += difflib.unified_diff(old.splitlines(True), block.splitlines(True),
                                              f"{args.readme} (current)", "generated from bench/results")
            new_text = head + block + tail
    except (ResultError, OSError, KeyError, ValueError) as e:
        print(f"readme_results: {type(e).__name__}: {e}", file=sys.stderr)
        return 2
    if args.write:
        if new_text != text:
            with open(args.readme, "w", encoding="utf-8") as f:
                f.write(new_text)
            print(f"readme_results: {args.readme}: results tables rewritten")
        else:
            print(f"readme_results: {args.readme}: results tables already up to date")
        return 0
    if not diffs:
        return 0
    sys.stdout.writelines(diffs)
    print(f"readme_results: {args.readme}: a results table differs from bench/results/; "
          "run python3 scripts/readme_results.py --write", file=sys.stderr)
    return 1

if __name__ == "__main__":
    sys.exit(main())
