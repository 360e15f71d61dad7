#!/usr/bin/env bash
# check_format.sh PHANTOM SEGMENT CHECK_JSON FORMAT DIR: a coarse phantom written as FORMAT
# and as NRRD segments to the same voxel counts and the same physical origin and spacing.
set -eu
phantom=$1 segment=$2 check=$3 format=$4 dir=$5
rm -rf "$dir"
"$phantom" mitral --spacing 0.5 --noise 0 --out "$dir/nrrd" --quiet
"$phantom" mitral --spacing 0.5 --noise 0 --format "$format" --out "$dir/other" --quiet
case $format in mha) image=open.mha ;; nii) image=open.nii.gz ;; dicom) image=open.dicom ;; esac
"$segment" "$dir/nrrd/open.nrrd" --out "$dir/seg_nrrd" --threshold 500 --quiet
"$segment" "$dir/other/$image" --out "$dir/seg_other" --threshold 500 --quiet
ref=$(sed -n 's/.*"tissue": \([0-9]*\).*/\1/p' "$dir/seg_nrrd/segment.summary.json" | head -1)
[ -n "$ref" ] || { echo "no tissue count in the NRRD summary"; exit 1; }
"$check" "$dir/seg_other/segment.summary.json" metrics.voxels.tissue "$ref" "$ref" \
  metrics.spacing_mm.0 0.4999 0.5001 metrics.spacing_mm.2 0.4999 0.5001
for axis in 0 1 2; do
  o=$(tr -d ' \n' < "$dir/seg_nrrd/segment.summary.json" | sed -n "s/.*\"origin_mm\":\[\([^]]*\)\].*/\1/p" | cut -d, -f$((axis + 1)))
  "$check" "$dir/seg_other/segment.summary.json" metrics.origin_mm.$axis "$(awk -v o="$o" 'BEGIN{print o - 0.001}')" "$(awk -v o="$o" 'BEGIN{print o + 0.001}')"
done
