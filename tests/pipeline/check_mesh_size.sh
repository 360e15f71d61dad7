#!/usr/bin/env bash
# check_mesh_size.sh CSV REFERENCE MESH TOLERANCE
# In a study_mesh_size table, the mean error of MESH against REFERENCE must be within
# TOLERANCE mm of the x1 mesh's (seed 5.3.3: refining did not change the accuracy).
set -u
csv=$1 reference=$2 mesh=$3 tol=$4
awk -F, -v r="$reference" -v m="$mesh" -v tol="$tol" '
  $3 == r && $1 == "x1" { base = $4 }
  $3 == r && $1 == m { y = $4; found = 1 }
  END {
    if (!base || !found) { print "missing x1 or " m " row for " r; exit 1 }
    d = y - base
    printf "%s vs %s: mean %.4f mm, x1 %.4f mm, difference %+.4f (allowed +-%s)\n", m, r, y, base, d, tol
    exit !(d <= tol && d >= -tol)
  }' "$csv"
