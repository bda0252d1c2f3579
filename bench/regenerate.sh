#!/usr/bin/env bash
# Regenerates the benchmark CSVs/texts in bench/results and the plots in bench/results/plots
# (the numbers the README and bench/README.md quote). Run from the repository root after
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2
# Usage: bench/regenerate.sh [BUILD_DIR] [--quick]
#   --quick: pile scaling only up to 200 bodies (the full 10..2,000 sweep took 17 min on
#   2 cores, 2026-11-24) and no Clp in the work-precision sweep.
# Every step writes its own files; a runner whose optional peer is missing (Clp, Siconos,
# Box2D) is skipped with a message. Machines are noisy: compare ratios within one run.
set -euo pipefail
BUILD=${1:-build}
QUICK=${2:-}
R=bench/results
B=$BUILD/bench
mkdir -p "$R"
run() { echo "== $*" >&2; "$@"; }

run "$B/run_maros_meszaros" tests/data/maros_meszaros --out "$R/maros_meszaros.csv" --time-limit 60 > "$R/maros_meszaros.txt"
# A 64-problem Maros-Meszaros set in the directory $MM64 (outside the repository), 20 s per problem.
MM64=${MM64:-}
if [ -n "$MM64" ] && [ -d "$MM64" ]; then run "$B/run_maros_meszaros" "$MM64" --out "$R/maros_meszaros_shared64.csv" --time-limit 20 > "$R/maros_meszaros_shared64.txt"; else echo "MM64 unset or not a directory: the 64-problem Maros-Meszaros run skipped" >&2; fi
run "$B/bench_qp_random" --benchmark_out="$R/qp_random.json" --benchmark_out_format=json > "$R/qp_random.txt"
run "$B/run_qp_scaling" --csv "$R/qp_scaling.csv" > "$R/qp_scaling.txt"
OMP_NUM_THREADS=1 run "$B/bench_lemke" --benchmark_out="$R/lemke.json" --benchmark_out_format=json > "$R/lemke_sparse_vs_dense.txt"
D=tests/data/siconos/fc2d
{ echo "# $B/run_lemke_columns (fc2d files, --repeat 3; then --pile-bodies 400 --pile-steps 70)"
  run "$B/run_lemke_columns" "$D/fc2d_granularflowonwall_00667_00000.dat" "$D/fc2d_granularflowonwall_02020_00213.dat" \
    tests/data/generated/fc2d_pile_00186_b60_s150.dat --repeat 3
  run "$B/run_lemke_columns" --pile-bodies 400 --pile-steps 70; } > "$R/lemke_columns.txt"
if [ -x "$B/run_lemke_peers" ]; then run "$B/run_lemke_peers" tests/data/siconos --out "$R/lemke_peers.csv" > "$R/lemke_peers.txt"; else echo "Siconos not built: lemke peers skipped" >&2; fi
if [ "$QUICK" = "--quick" ]; then
  run "$B/run_pile_scaling" --sizes 10,20,50,100,200 --csv "$R/pile_scaling.csv" > "$R/pile_scaling.txt"
  run "$B/run_work_precision" --clp "" --csv "$R/work_precision.csv"
else
  run "$B/run_pile_scaling" --sizes 10,20,50,100,200,500,1000,2000 --csv "$R/pile_scaling.csv" > "$R/pile_scaling.txt"
  run "$B/run_work_precision" --csv "$R/work_precision.csv"
fi
if [ -x "$B/run_pile_peers" ]; then
  run "$B/run_pile_peers" --pile-sizes 50,200 --settle-steps 400 --steps 20 --pyramid-steps 200 --lcp-max-bodies 200 \
    --csv "$R/pile_peers.csv" > "$R/pile_peers.txt"
else
  echo "Box2D not built: pile peers skipped" >&2
fi
run "$B/run_stiff_report" --csv "$R/stiff_report.csv" > "$R/stiff_report.md"
run "$B/run_fragility" --csv "$R/fragility.csv" > "$R/fragility.txt"
run "$B/run_softening" --csv "$R/softening.csv" > "$R/softening.txt"
mkdir -p "$R/plots"
run "$B/run_gradient_landscape" --csv "$R/gradient_landscape.csv" --plots "$R/plots" > "$R/gradient_landscape.txt"
run python3 bench/softening_table.py --landscape "$R/gradient_landscape.csv" --softening "$R/softening.csv" \
  > "$R/softening_table.md"
run "$B/run_learning_curves" --csv "$R/learning_curves.csv" --plot "$R/plots/learning_curves.png" \
  > "$R/learning_curves.txt"
run "$B/run_learning_curves" --methods hard --sizes 3000,10000 --csv "$R/learning_curves_hard_10k.csv" \
  > "$R/learning_curves_hard_10k.txt"
# The polygon and the 30-body pile on the scene path (relaxed loss; Adam as the CLIs, and L-BFGS
# for the polygon); the pile at N = 10, 30 only (a run at N = 30 takes 2-5 min on 1 thread).
run "$B/run_learning_curves_scene" --scene polygon --params physical,structured --sizes 10,30,100,300,1000 --seeds 5 \
  --test 400 --sanity-size 100 --epochs 300 --csv "$R/learning_curves_scene_polygon.csv" \
  --plot "$R/plots/learning_curves_scene_polygon.png" > "$R/learning_curves_scene_polygon.txt"
run "$B/run_learning_curves_scene" --scene polygon --params residual --sizes 10,30,100,300,1000 --seeds 5 \
  --test 400 --sanity-size 0 --epochs 300 --csv "$R/learning_curves_scene_polygon_residual.csv" \
  --plot "$R/plots/learning_curves_scene_polygon_residual.png" > "$R/learning_curves_scene_polygon_residual.txt"
run "$B/run_learning_curves_scene" --scene polygon --params physical,structured --optimizer lbfgs --epochs 100 \
  --sizes 10,30,100,300,1000 --seeds 5 --test 400 --sanity-size 0 --csv "$R/learning_curves_scene_polygon_lbfgs.csv" \
  > "$R/learning_curves_scene_polygon_lbfgs.txt"
run "$B/run_learning_curves_scene" --scene polygon --params physical --optimizer lbfgs --epochs 100 \
  --sizes 3000,10000 --seeds 5 --test 400 --sanity-size 0 --csv "$R/learning_curves_scene_polygon_lbfgs_10k.csv" \
  > "$R/learning_curves_scene_polygon_lbfgs_10k.txt"
# The hard loss with the lcp model's per-contact LCP block, free (elementwise) and tied.
# L-BFGS (as the block's curves): Adam's fixed step (0.02 per entry) moves the block's entries
# (1/kg, kg, m/s) off the truth even when started there (sanity line of an Adam run: 38% error).
run "$B/run_learning_curves_scene" --scene polygon --params physical,block_tied,block --loss hard --optimizer lbfgs \
  --epochs 100 --sizes 10,30,100,300,1000,3000,10000 --seeds 5 --test 400 --sanity-size 100 \
  --csv "$R/learning_curves_scene_polygon_hard.csv" --plot "$R/plots/learning_curves_scene_polygon_hard.png" \
  > "$R/learning_curves_scene_polygon_hard.txt"
# Two-stage: the physical parameters by the relaxed loss (L-BFGS) first, then the hard loss.
run "$B/run_learning_curves_scene" --scene polygon --params physical,block_tied,block --loss hard --optimizer lbfgs \
  --epochs 100 --start relaxed --sizes 10,30,100,300,1000,3000 --seeds 5 --test 400 --sanity-size 0 \
  --csv "$R/learning_curves_scene_polygon_hard_staged.csv" \
  --plot "$R/plots/learning_curves_scene_polygon_hard_staged.png" > "$R/learning_curves_scene_polygon_hard_staged.txt"
run "$B/run_learning_curves_scene" --scene pile30 --params physical,structured --sizes 10,30 --seeds 5 \
  --test 30 --sanity-size 10 --epochs 300 --csv "$R/learning_curves_scene_pile30.csv" \
  --plot "$R/plots/learning_curves_scene_pile30.png" > "$R/learning_curves_scene_pile30.txt"
# The pile at N = 100 (8-16 min per run on 1 thread; the committed structured rows were run seed
# by seed with --first-seed S --seeds 1 --truth-loss and appended).
run "$B/run_learning_curves_scene" --scene pile30 --params physical,structured --sizes 100 --seeds 5 --test 30 \
  --sanity-size 0 --epochs 300 --csv "$R/learning_curves_scene_pile30_n100.csv" > "$R/learning_curves_scene_pile30_n100.txt"
# The pile at N = 1,000: mini-batches of 100 and 30 epochs, i.e. the same 300 Adam steps of 100
# samples as the full-batch runs at N = 100 (--batch), on 2 threads (same numbers as 1); 11-18 min
# per seed and parameterization. The committed files were made seed by seed (--first-seed S
# --seeds 1, which gives the same rows; bench/README.md), so their .txt is laid out differently.
run "$B/run_learning_curves_scene" --scene pile30 --params physical,structured --sizes 1000 --seeds 5 --test 30 \
  --sanity-size 0 --epochs 300 --batch 100 --threads 2 --csv "$R/learning_curves_scene_pile30_n1000.csv" \
  > "$R/learning_curves_scene_pile30_n1000.txt"
# Why the pile stops there: the training loss at the true theta (--epochs 0: no training), and
# L-BFGS from Adam's end point on seed 1.
{ run "$B/run_learning_curves_scene" --scene pile30 --params physical --sizes 30,100,1000 --seeds 5 --test 1 \
    --sanity-size 0 --epochs 0 --truth-loss | grep "training loss"
  run "$B/run_learning_curves_scene" --scene pile30 --params physical --sizes 1000 --seeds 1 --test 30 --sanity-size 0 \
    --epochs 300 --batch 100 --optimizer adam+lbfgs --polish 20 --truth-loss \
    --csv "$R/learning_curves_scene_pile30_n1000_polish.csv"
} > "$R/learning_curves_scene_pile30_n1000_diagnosis.txt"
# The friction table's normal softness (compliance, erp: an implicit spring–damper per material
# pair) learned alongside the physical parameters: on the rigid truth (relaxed; relaxed then
# hard), and on data of a soft truth (compliance 0.1 1/kg, erp 0.2) where the rigid physical
# model is misspecified.
run "$B/run_learning_curves_scene" --scene polygon --params softness --optimizer lbfgs --epochs 100 \
  --sizes 10,30,100,300,1000 --seeds 5 --test 400 --sanity-size 100 \
  --csv "$R/learning_curves_scene_polygon_softness.csv" > "$R/learning_curves_scene_polygon_softness.txt"
run "$B/run_learning_curves_scene" --scene polygon --params softness --loss hard --optimizer lbfgs --epochs 100 \
  --start relaxed --sizes 10,30,100,300,1000 --seeds 5 --test 400 --sanity-size 0 \
  --csv "$R/learning_curves_scene_polygon_softness_staged.csv" > "$R/learning_curves_scene_polygon_softness_staged.txt"
run "$B/run_learning_curves_scene" --scene polygon --params physical,softness --true-compliance 0.1 --true-erp 0.2 \
  --optimizer lbfgs --epochs 100 --sizes 10,30,100,300,1000 --seeds 5 --test 400 --sanity-size 100 \
  --csv "$R/learning_curves_scene_polygon_soft_truth.csv" \
  --plot "$R/plots/learning_curves_scene_polygon_soft_truth.png" > "$R/learning_curves_scene_polygon_soft_truth.txt"
run "$B/run_learning_curves_scene" --scene polygon --params physical,softness --true-compliance 0.1 --true-erp 0.2 \
  --loss hard --optimizer lbfgs --epochs 100 --start relaxed --sizes 10,30,100,300,1000 --seeds 5 --test 400 \
  --sanity-size 0 --csv "$R/learning_curves_scene_polygon_soft_truth_staged.csv" \
  > "$R/learning_curves_scene_polygon_soft_truth_staged.txt"
run "$B/run_learning_curves_scene" --scene pile30 --params physical,softness --true-compliance 0.02 --true-erp 0.2 \
  --optimizer lbfgs --epochs 100 --sizes 10,30 --seeds 5 --test 30 --sanity-size 10 \
  --csv "$R/learning_curves_scene_pile30_soft_truth.csv" \
  --plot "$R/plots/learning_curves_scene_pile30_soft_truth.png" > "$R/learning_curves_scene_pile30_soft_truth.txt"
{ head -1 "$R/learning_curves_scene_polygon.csv"
  for f in polygon polygon_residual polygon_lbfgs polygon_lbfgs_10k polygon_hard polygon_hard_staged \
           polygon_softness polygon_softness_staged polygon_soft_truth polygon_soft_truth_staged pile30 pile30_n100 \
           pile30_n1000 pile30_soft_truth; do
    tail -n +2 "$R/learning_curves_scene_$f.csv"
  done
} > "$R/learning_curves_scene.csv"
cat "$R"/learning_curves_scene_{polygon,polygon_residual,polygon_lbfgs,polygon_lbfgs_10k,polygon_hard,polygon_hard_staged,polygon_softness,polygon_softness_staged,polygon_soft_truth,polygon_soft_truth_staged,pile30,pile30_n100,pile30_n1000,pile30_soft_truth}.txt > "$R/learning_curves_scene.txt"
run python3 bench/learning_curve_table.py --csv "$R/learning_curves.csv" --csv "$R/learning_curves_hard_10k.csv" \
  --scene-csv "$R/learning_curves_scene.csv" > "$R/learning_curves.md"
run "$B/bench_learn_block" --benchmark_min_time=0.5 > "$R/learn_block.txt"
run "$B/bench_learn_polygon" --benchmark_min_time=0.5 > "$R/learn_polygon.txt"
run "$B/run_learn_throughput" --threads 1,2 --csv "$R/learn_throughput.csv" > "$R/learn_throughput.txt"
run "$B/run_kkt_backends" --csv "$R/kkt_backends.csv" > "$R/kkt_backends.txt"
# The same on 2 MPI ranks, appended, when the build has PETSc/MPI and mpiexec exists.
if command -v mpiexec > /dev/null && "$B/run_learn_throughput" --check-mpi; then
  if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
  MPI=(mpiexec -n 2 --oversubscribe)
  run "${MPI[@]}" "$B/run_learn_throughput" --threads 1 --csv "$R/learn_throughput.csv" --append >> "$R/learn_throughput.txt"
  run "${MPI[@]}" "$B/run_kkt_backends" --backends mumps_distributed --csv "$R/kkt_backends.csv" --append >> "$R/kkt_backends.txt"
else
  echo "no PETSc/MPI build or no mpiexec: the 2-rank rows are skipped" >&2
fi
run "$B/run_learn_convergence" --csv "$R/learn_convergence.csv" > "$R/learn_convergence.txt"
run "$B/run_learn_convergence" --problems polygon --polygon-data cli --polygon-epochs 300 \
  --csv "$R/learn_convergence_polygon_cli.csv" \
  > "$R/learn_convergence_polygon_cli.txt"
run "$B/run_report_plots" --results "$R" --out "$R/plots"
# PyTorch QpLayer against a dense batched PyTorch interior point (needs the Python module and torch).
if PYTHONPATH="$BUILD/python" python3 -c "import lcprelax.torch" 2>/dev/null; then
  PYTHONPATH="$BUILD/python" run python3 bench/run_qp_layer.py --csv "$R/qp_layer.csv" > "$R/qp_layer.txt"
else
  echo "lcprelax.torch not importable (module not built or no torch): qp_layer skipped" >&2
fi
