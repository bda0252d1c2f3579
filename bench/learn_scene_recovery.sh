#!/usr/bin/env bash
# Parameter recovery on learning piles (lcprelax learn scene): each method on data from its
# own model (relaxed and hard: the LCP model; convex: the convex model), every learned
# parameter perturbed by 25%, for several seeds and pile sizes. Writes
# bench/results/learn_scene_recovery.csv (one row per run: the largest relative error per
# parameter kind; vertices in units of their class radius) and the full JSON results to
# bench/results/learn_scene_recovery/. Run from the repository root after building.
# Usage: bench/learn_scene_recovery.sh [BUILD_DIR]
set -euo pipefail
BUILD=${1:-build}
R=bench/results
OUT=$R/learn_scene_recovery
mkdir -p "$OUT"
CSV=$R/learn_scene_recovery.csv
echo "method,bodies,seed,epochs,stop_reason,seconds,transitions,final_loss,mu,mass,inertia,vertex,failed" > "$CSV"
run() {  # method bodies seed extra-args...
  local m=$1 n=$2 s=$3
  shift 3
  local f="$OUT/${m}_${n}_seed${s}.json"
  echo "== learn scene --method $m --bodies $n --seed $s $*" >&2
  "$BUILD/apps/lcprelax" learn scene --method "$m" --bodies "$n" --seed "$s" --json "$@" > "$f"
  python3 - "$f" "$m" "$n" "$s" >> "$CSV" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
e = j["relative_error"]
def worst(kind):
    v = [x for k, x in e.items() if k.endswith(kind) or (kind == "vertex" and ".vertex" in k)]
    return "%.4g" % max(v) if v else ""
print(",".join([sys.argv[2], sys.argv[3], sys.argv[4], str(j["epochs"]), j["stop_reason"].replace(",", ";"),
                "%.1f" % j["seconds"], str(j["transitions"]), "%.4g" % j["final_loss"], "%.4g" % e["mu"],
                worst("mass"), worst("inertia"), worst("vertex"), str(j["failed"])]))
PY
}
for seed in 1 2 3; do
  run relaxed 30 "$seed"
  run convex 30 "$seed"
done
run relaxed 60 1
run convex 60 1
column -s, -t < "$CSV"
