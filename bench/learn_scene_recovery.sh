#!/usr/bin/env bash
# Parameter recovery on a 30-body learning pile (lcprelax learn scene), every learned
# parameter perturbed by 25%. Runs (RUNS, default all three):
#   relaxed     the relaxed loss on data of the LCP model, 800 epochs of Adam (lr 0.01,
#               decay 0.01);
#   relaxed_robust the same with each transition's loss ℓ entering as the Cauchy robust loss
#               0.05·log(1 + ℓ/0.05) (--robust-scale 0.05, learn/robust.hpp);
#               relaxed_robust_c001 with c = 0.01;
#   relaxed_mn  the same with --mass-normalized true (a2 = 0.1 divided by each island's mean
#               mass, docs/formulations.md); relaxed_mn_a1 with a2 = 1 (1/kg); relaxed_a001
#               without the normalization and a2 = 0.01 (the normalized weight's size on
#               these ~10 kg bodies);
#   relaxed_portfolio the relaxed loss with --portfolio and L-BFGS (apps/learn_scene_portfolio.hpp):
#               L-BFGS alone and Adam (400 epochs, lr 0.01, decay 0.01) then L-BFGS, at most
#               300 L-BFGS epochs each;
#   convex      the convex loss on data of the convex model, unbiased (deviation penalty in
#               phase 2 only, phase-1 regularization 1e-6), Levenberg–Marquardt (--optimizer
#               lm), at most 200 epochs;
#   convex_geo  the same with the geodesic acceleration (--lm-geodesic);
#   convex_map  the same in two runs: first with a Gaussian prior on the free parameters
#               centred on the initial values (--prior-weight $PRIOR, default 1), then
#               without it from the first run's result (--init-from), which removes the
#               prior's bias; the first run's JSON is kept as <run>_<bodies>_seed<S>.stage1
#               (at most $STAGE1_EPOCHS epochs, default 40: the biased minimum is only a
#               start);
#   convex_adam_lm the same in two runs: first Adam on the same loss for $ADAM_EPOCHS epochs
#               (default 300; lr 0.02, decay 0.003: the CLI's defaults), then LM from its result
#               (--init-from); the first run's JSON kept as <run>_<bodies>_seed<S>.stage1;
#   convex_portfolio the same with --portfolio (learn/portfolio.hpp): LM alone, Adam
#               ($ADAM_EPOCHS epochs) then LM, and LM on the default convex loss (40 epochs)
#               then on the unbiased one, all from the same start; the lowest training loss kept;
#   convex_lcp  the same convex loss and optimizer on data of the LCP model (outside the
#               convex model's class: what it recovers there).
# Writes bench/results/learn_scene_recovery/<run>_<bodies>_seed<S>.json (the CLI's JSON) and
# bench/results/learn_scene_recovery.csv (one row per JSON in that folder: the largest
# relative error per parameter kind; vertices in units of their class radius). Each run
# takes 2–15 min on 2 cores. Run from the repository root after building.
# Usage: bench/learn_scene_recovery.sh [BUILD_DIR] [SEEDS (default "1")] [BODIES (default 30)] [RUNS]
set -euo pipefail
BUILD=${1:-build}
SEEDS=${2:-1}
BODIES=${3:-30}
RUNS=${4:-relaxed convex convex_lcp}
PRIOR=${PRIOR:-1}
STAGE1_EPOCHS=${STAGE1_EPOCHS:-40}
ADAM_EPOCHS=${ADAM_EPOCHS:-300}
R=bench/results
OUT=$R/learn_scene_recovery
mkdir -p "$OUT"
LM="--optimizer lm --phase1-deviation 0 --phase1-regularization 1e-6"
for seed in $SEEDS; do
  for run in $RUNS; do
    case $run in
      relaxed) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01" ;;
      relaxed_mn) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01 --mass-normalized true" ;;
      relaxed_mn_a1) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01 --mass-normalized true --complementarity-weight 1" ;;
      relaxed_a001) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01 --complementarity-weight 0.01" ;;
      relaxed_robust) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01 --robust-scale 0.05" ;;
      relaxed_robust_c001) args="--method relaxed --epochs 800 --lr 0.01 --lr-decay 0.01 --robust-scale 0.01" ;;
      relaxed_portfolio) args="--method relaxed --optimizer lbfgs --epochs 300 --portfolio --portfolio-adam-epochs 400 --lr 0.01 --lr-decay 0.01" ;;
      convex) args="--method convex $LM --epochs 200" ;;
      convex_geo) args="--method convex $LM --epochs 200 --lm-geodesic" ;;
      convex_portfolio) args="--method convex $LM --epochs 200 --portfolio --portfolio-adam-epochs $ADAM_EPOCHS" ;;
      convex_map|convex_adam_lm) ;;
      convex_lcp) args="--method convex --data-model lcp $LM --epochs 200" ;;
      *) echo "unknown run '$run' (relaxed, relaxed_robust, relaxed_robust_c001, relaxed_mn, relaxed_mn_a1, relaxed_a001, relaxed_portfolio, convex, convex_geo, convex_map, convex_adam_lm, convex_portfolio, convex_lcp)" >&2; exit 2 ;;
    esac
    f="$OUT/${run}_${BODIES}_seed${seed}.json"
    if [ "$run" = convex_map ]; then
      echo "== learn scene --method convex $LM --epochs $STAGE1_EPOCHS --prior-weight $PRIOR --bodies $BODIES --seed $seed" >&2
      # shellcheck disable=SC2086
      "$BUILD/apps/lcprelax" learn scene --method convex $LM --epochs "$STAGE1_EPOCHS" --prior-weight "$PRIOR" --bodies "$BODIES" \
        --seed "$seed" --json > "$OUT/${run}_${BODIES}_seed${seed}.stage1"
      args="--method convex $LM --epochs 200 --init-from $OUT/${run}_${BODIES}_seed${seed}.stage1"
    fi
    if [ "$run" = convex_adam_lm ]; then
      ADAM="--method convex --optimizer adam --phase1-deviation 0 --phase1-regularization 1e-6 --epochs $ADAM_EPOCHS"
      echo "== learn scene $ADAM --bodies $BODIES --seed $seed" >&2
      # shellcheck disable=SC2086
      "$BUILD/apps/lcprelax" learn scene $ADAM --bodies "$BODIES" --seed "$seed" --json \
        > "$OUT/${run}_${BODIES}_seed${seed}.stage1"
      args="--method convex $LM --epochs 200 --init-from $OUT/${run}_${BODIES}_seed${seed}.stage1"
    fi
    echo "== learn scene $args --bodies $BODIES --seed $seed" >&2
    # shellcheck disable=SC2086
    "$BUILD/apps/lcprelax" learn scene $args --bodies "$BODIES" --seed "$seed" --json > "$f"
  done
done
python3 - "$OUT" > "$R/learn_scene_recovery.csv" <<'PY'
import glob, json, os, sys
print("run,method,epochs,stop_reason,seconds,transitions,final_loss,mu,mass,inertia,vertex,failed")
for f in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    j = json.load(open(f))
    e = j["relative_error"]
    def worst(tag):
        v = [x for k, x in e.items() if (tag in k if tag == ".vertex" else k.endswith(tag))]
        return "%.4g" % max(v) if v else ""
    epochs, seconds = j["epochs"], j["seconds"]
    if os.path.exists(f[:-5] + ".stage1"):  # two-stage runs: both runs' epochs and time
        s1 = json.load(open(f[:-5] + ".stage1"))
        epochs, seconds = epochs + s1["epochs"], seconds + s1["seconds"]
    stop = j["stop_reason"]
    if "chosen_recipe" in j:  # portfolio runs: which recipe was kept, the others' losses
        others = ["%s loss %.3g" % (r["recipe"], r["final_loss"]) for r in j["portfolio"] if r["recipe"] != j["chosen_recipe"]]
        stop = "kept %s (%s): %s" % (j["chosen_recipe"], "; ".join(others), stop)
    print(",".join([os.path.basename(f)[:-5], j["method"], str(epochs), stop.replace(",", ";"),
                    "%.1f" % seconds, str(j["transitions"]), "%.4g" % j["final_loss"], "%.4g" % e["mu"],
                    worst("mass"), worst("inertia"), worst(".vertex"), str(j["failed"])]))
PY
column -s, -t < "$R/learn_scene_recovery.csv"
