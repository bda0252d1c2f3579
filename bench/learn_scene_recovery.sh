#!/usr/bin/env bash
# Parameter recovery on a 30-body learning pile (lcprelax learn scene), each method on data
# of its own model (relaxed: the LCP model; convex: the convex model), every learned
# parameter perturbed by 25%, 800 epochs of Adam (lr 0.01, decay 0.01). Writes
# bench/results/learn_scene_recovery/<method>_<bodies>_seed<S>.json (the CLI's JSON) and
# bench/results/learn_scene_recovery.csv (one row per run: the largest relative error per
# parameter kind; vertices in units of their class radius). Each run takes 5–15 min on 2
# cores. Run from the repository root after building.
# Usage: bench/learn_scene_recovery.sh [BUILD_DIR] [SEEDS (default "1")] [BODIES (default 30)]
set -euo pipefail
BUILD=${1:-build}
SEEDS=${2:-1}
BODIES=${3:-30}
R=bench/results
OUT=$R/learn_scene_recovery
mkdir -p "$OUT"
for seed in $SEEDS; do
  for m in relaxed convex; do
    f="$OUT/${m}_${BODIES}_seed${seed}.json"
    echo "== learn scene --method $m --bodies $BODIES --seed $seed" >&2
    "$BUILD/apps/lcprelax" learn scene --method "$m" --bodies "$BODIES" --seed "$seed" --epochs 800 \
      --lr 0.01 --lr-decay 0.01 --json > "$f"
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
    print(",".join([os.path.basename(f)[:-5], j["method"], str(j["epochs"]), j["stop_reason"].replace(",", ";"),
                    "%.1f" % j["seconds"], str(j["transitions"]), "%.4g" % j["final_loss"], "%.4g" % e["mu"],
                    worst("mass"), worst("inertia"), worst(".vertex"), str(j["failed"])]))
PY
column -s, -t < "$R/learn_scene_recovery.csv"
