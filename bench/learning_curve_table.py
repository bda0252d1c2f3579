#!/usr/bin/env python3
"""The learning-curve table of issue 20 from bench/run_learning_curves' CSV: per
parameterization and training loss, the smallest training set whose median held-out
next-state error over the seeds is <= 1% (and whose largest is), the median error and the
mean stick/slip mode error at N = 1,000 (or the largest N run), the median RMS of the
predicted v⁺ over the held-out transitions that truly stick (in units of μmg/m), and the
sample evaluations that failed during training (summed over the seeds). Standard library only.

    bench/learning_curve_table.py [--csv bench/results/learning_curves.csv [--csv MORE.csv]]
        [--scene-csv bench/results/learning_curves_scene.csv] > bench/results/learning_curves.md

With --scene-csv (bench/run_learning_curves_scene's CSV, repeatable) a second table follows:
per scene (polygon, pile30), parameterization and loss, the smallest N whose median
held-out error is <= 1% (and whose largest is), and the median error, the mean stick/slip
mode error and the failed evaluations (held-out predictions; training) at N = 1,000 or the
largest N run.
"""
import argparse
import csv
import statistics
from collections import defaultdict


def load_runs(paths, key_fields):
    """Rows of the CSVs grouped by key (key_fields' values) and training size, keys in order of
    first appearance."""
    runs = defaultdict(lambda: defaultdict(list))
    order = []
    for path in paths:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                key = tuple(r[k] for k in key_fields)
                if key not in runs:
                    order.append(key)
                runs[key][int(r["samples"])].append(r)
    return runs, order


def summary(by_n):
    """Sizes, test errors per size, the smallest N whose median (med) and largest (every) error
    is <= 1%, the reporting N (1,000 or the largest run) and the mean mode error there."""
    sizes = sorted(by_n)
    errs = {n: [float(r["test_error"]) for r in by_n[n]] for n in sizes}
    med = next((str(n) for n in sizes if statistics.median(errs[n]) <= 0.01), "> %d" % sizes[-1])
    every = next((str(n) for n in sizes if max(errs[n]) <= 0.01), "> %d" % sizes[-1])
    n = 1000 if 1000 in by_n else sizes[-1]
    mode = statistics.mean(float(r["mode_error"]) for r in by_n[n])
    return sizes, errs, med, every, n, mode


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", action="append", help="CSV of run_learning_curves (repeat to merge runs)")
    ap.add_argument("--scene-csv", action="append", default=[], help="CSV of run_learning_curves_scene (repeatable)")
    a = ap.parse_args()
    runs, order = load_runs(a.csv or ["bench/results/learning_curves.csv"], ("param", "method"))
    print("| parameterization | loss | N for median error ≤ 1% | N for every seed ≤ 1% | "
          "median error at N = 1,000 | mode error at N = 1,000 | RMS v̂⁺ where it truly sticks (μmg/m), N = 1,000 | "
          "failed evaluations in training, N = 1,000 | median error (mode error) at the largest N |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key in order:
        by_n = runs[key]
        sizes, errs, med, every, n, mode = summary(by_n)
        failed = sum(int(r["train_failed"]) for r in by_n[n])
        stick = statistics.median(float(r["stick_speed"]) for r in by_n[n])
        last = sizes[-1]
        last_mode = statistics.mean(float(r["mode_error"]) for r in by_n[last])
        print("| %s | %s | %s | %s | %.3g | %.3g | %.2g | %d | %.3g (%.3g) at %d |" % (
            key[0], key[1], med, every, statistics.median(errs[n]), mode, stick, failed,
            statistics.median(errs[last]), last_mode, last))

    if a.scene_csv:
        scene_table(a.scene_csv)


def scene_table(paths):
    runs, order = load_runs(paths, ("scene", "param", "method"))
    print()
    print("Polygon and 30-body pile (bench/run_learning_curves_scene; loss `relaxed` = relaxed step loss by "
          "Adam, `relaxed/lbfgs` by L-BFGS, `hard/lbfgs` the hard loss by L-BFGS, `relaxed+hard/lbfgs` the hard loss "
          "from the physical parameters the relaxed loss learned first; N counts transitions of the whole scene):")
    print()
    print("| scene | parameterization | loss | seeds | N for median error ≤ 1% | N for every seed ≤ 1% | N used below | "
          "median error | mode error | failed predictions | failed evaluations in training |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for key in order:
        by_n = runs[key]
        sizes, errs, med, every, n, mode = summary(by_n)
        print("| %s | %s | %s | %d | %s | %s | %d | %.3g | %.3g | %d | %d |" % (
            key[0], key[1], key[2], len(by_n[n]), med, every, n, statistics.median(errs[n]), mode,
            sum(int(r["failed"]) for r in by_n[n]), sum(int(r["train_failed"]) for r in by_n[n])))


if __name__ == "__main__":
    main()
