#!/usr/bin/env python3
"""Largest start-of-step overlap of a dropping pile against the number of post-stabilization
passes (SimulatorSettings::post_stabilization_passes, docs/formulations.md).

Usage: PYTHONPATH=build/python python3 bench/run_projection_passes.py BODIES STEPS MODEL
       (MODEL: convex | lcp). One line per pass count 1, 2, 3, 5: the largest
       StepStats.max_penetration (m) over the steps, failed islands, CPU seconds per step.
"""
import sys
import time

import lcprelax


def main():
    bodies, steps, model = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    for passes in (1, 2, 3, 5):
        sim = lcprelax.Simulator(lcprelax.pile_scene(bodies=bodies, model=model), model=model,
                                 post_stabilization_passes=passes, threads=1)
        start, worst, failed = time.process_time(), 0.0, 0
        for _ in range(steps):
            st = sim.step()
            worst = max(worst, st.max_penetration)
            failed += st.failed_islands
        print(bodies, model, "passes", passes, "max_pen %.4f" % worst, "failed", failed,
              "cpu/step %.4f" % ((time.process_time() - start) / steps), flush=True)


if __name__ == "__main__":
    main()
