#!/usr/bin/env bash
# check_sensitivity.sh CSV PARAMETER CHANGE_PCT MIN MAX
# From a study_sensitivity table (first data row: the baseline run), the sensitivity of the
# mean error to PARAMETER changed by CHANGE_PCT, S = (y - y_baseline) / (CHANGE_PCT / 100),
# must lie in [MIN, MAX] mm per 100 % change.
set -u
csv=$1 parameter=$2 change=$3 min=$4 max=$5
awk -F, -v p="$parameter" -v c="$change" -v lo="$min" -v hi="$max" '
  NR == 2 { base = $4 }
  NR > 2 && $1 == p && $2 == c { y = $4; found = 1 }
  END {
    if (!base) { print "no baseline row"; exit 1 }
    if (!found) { print "no row for " p " " c " %"; exit 1 }
    s = (y - base) / (c / 100)
    printf "%s %+d %%: mean %.4f mm (baseline %.4f), S = %.3f mm per 100 %% (expected %s..%s)\n", p, c, y, base, s, lo, hi
    exit !(s >= lo && s <= hi)
  }' "$csv"
