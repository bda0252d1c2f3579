#!/usr/bin/env python3
"""The learning-curve table of issue 20 from bench/run_learning_curves' CSV: per
parameterization and training loss, the smallest training set whose median held-out
next-state error over the seeds is <= 1% (and whose largest is), the median error and the
mean stick/slip mode error at N = 1,000 (or the largest N run), the median RMS of the
predicted v⁺ over the held-out transitions that truly stick (in units of μmg/m), and the
sample evaluations that failed during training (summed over the seeds). Standard library only.

    bench/learning_curve_table.py [--csv bench/results/learning_curves.csv [--csv MORE.csv]]
        > bench/results/learning_curves.md
"""
import argparse
import csv
import statistics
from collections import defaultdict


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", action="append", help="CSV of run_learning_curves (repeat to merge runs)")
    a = ap.parse_args()
    paths = a.csv or ["bench/results/learning_curves.csv"]
    runs = defaultdict(lambda: defaultdict(list))
    order = []
    for path in paths:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                key = (r["param"], r["method"])
                if key not in runs:
                    order.append(key)
                runs[key][int(r["samples"])].append(r)
    print("| parameterization | loss | N for median error ≤ 1% | N for every seed ≤ 1% | "
          "median error at N = 1,000 | mode error at N = 1,000 | RMS v̂⁺ where it truly sticks (μmg/m), N = 1,000 | "
          "failed evaluations in training, N = 1,000 | median error (mode error) at the largest N |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key in order:
        by_n = runs[key]
        sizes = sorted(by_n)
        errs = {n: [float(r["test_error"]) for r in by_n[n]] for n in sizes}
        med = next((str(n) for n in sizes if statistics.median(errs[n]) <= 0.01), "> %d" % sizes[-1])
        every = next((str(n) for n in sizes if max(errs[n]) <= 0.01), "> %d" % sizes[-1])
        n = 1000 if 1000 in by_n else sizes[-1]
        mode = statistics.mean(float(r["mode_error"]) for r in by_n[n])
        failed = sum(int(r["train_failed"]) for r in by_n[n])
        stick = statistics.median(float(r["stick_speed"]) for r in by_n[n])
        last = sizes[-1]
        last_mode = statistics.mean(float(r["mode_error"]) for r in by_n[last])
        print("| %s | %s | %s | %s | %.3g | %.3g | %.2g | %d | %.3g (%.3g) at %d |" % (
            key[0], key[1], med, every, statistics.median(errs[n]), mode, stick, failed,
            statistics.median(errs[last]), last_mode, last))


if __name__ == "__main__":
    main()
