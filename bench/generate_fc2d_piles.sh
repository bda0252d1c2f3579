#!/usr/bin/env bash
# Large fc2d test problems exported from `lcprelax pile` (convex model, the last step's
# contact problem before it is solved; models/src/fc2d_export.cpp) into bench/data/fc2d
# (not committed: 3.7 MB and 10.9 MB). Measured 2026-11-28 (2 shared cores, loaded):
#   800 bodies, 120 steps (settling) -> 2,331 contacts, 132 s
#   2,400 bodies, 90 steps (dropping) -> 6,808 contacts, about 19 min
# The small one kept in tests/data/generated was made the same way:
#   lcprelax pile --bodies 60 --steps 150 --export-fc2d fc2d_pile_00186_b60_s150.dat
# Usage: bench/generate_fc2d_piles.sh [BUILD_DIR]
set -euo pipefail
BUILD=${1:-build}
OUT=bench/data/fc2d
mkdir -p "$OUT"
"$BUILD/apps/lcprelax" pile --bodies 800 --steps 120 --export-fc2d "$OUT/fc2d_pile_02331_b800_s120.dat" --json
"$BUILD/apps/lcprelax" pile --bodies 2400 --steps 90 --export-fc2d "$OUT/fc2d_pile_06808_b2400_s90.dat" --json
