#!/usr/bin/env bash
# check_fiber_trend.sh SUMMARY_CSV BENDING MIN_DIFFERENCE
# Seed Fig. 4.7: fibers parallel to the free edge coapt worse than fibers at 25 degrees. In
# study_aortic_mesh_variation's summary, the coapting area averaged over the three leaflets
# and the ten meshes must be at least MIN_DIFFERENCE mm^2 larger at 25 degrees than parallel,
# at bending modulus BENDING.
set -u
csv=$1 bending=$2 min_diff=$3
awk -F, -v b="$bending" -v d="$min_diff" '
  NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  $col["bending"] == b {
    area = ($col["area_0_mm2_mean"] + $col["area_1_mm2_mean"] + $col["area_2_mm2_mean"]) / 3
    mean[$col["fibers"]] = area
  }
  END {
    if (!("25deg" in mean) || !("parallel" in mean)) { print "missing 25deg or parallel rows for " b; exit 1 }
    diff = mean["25deg"] - mean["parallel"]
    printf "%s: coapting area 25deg %.1f mm2, parallel %.1f mm2, difference %.1f (required >= %s)\n", b, mean["25deg"], mean["parallel"], diff, d
    exit !(diff >= d)
  }' "$csv"
