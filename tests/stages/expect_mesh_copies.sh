#!/usr/bin/env bash
# expect_mesh_copies.sh GENERATE COMPARE CHECK_JSON OUT
# A stage's --mesh-copies writes the result mesh again as .stl, .ply, .obj and .vtk. Checked
# against the formats' own definitions and against the .vtp: a binary STL is an 80-byte
# header, a 4-byte triangle count and 50 bytes per triangle; every copy, read back, lies on
# the .vtp's surface and the .vtp on it, to single precision (coordinates of at most 30 mm
# stored as float32 round by under 2e-6 mm; 1e-5 mm allowed); the .vtk is double, exact.
# An unknown format is refused (exit 2) before anything is written.
set -u
generate=$1 compare=$2 check_json=$3 out=$4
rm -rf "$out"
"$generate" aortic_valve --out "$out" --mesh-copies stl,ply,obj,vtk --quiet || { echo "generate failed"; exit 1; }
triangles=$(grep -o '"triangles": [0-9]*' "$out/generate.summary.json" | head -1 | grep -o '[0-9]*$')
[ -n "$triangles" ] || { echo "no triangle count in generate.summary.json"; exit 1; }
size=$(stat -c %s "$out/aortic_valve.stl")
[ "$size" -eq $((84 + 50 * triangles)) ] || { echo "aortic_valve.stl: $size bytes, expected $((84 + 50 * triangles)) for $triangles triangles"; exit 1; }
head -c 3 "$out/aortic_valve.ply" | grep -q ply || { echo "aortic_valve.ply: no PLY magic"; exit 1; }
faces=$(grep -c '^f ' "$out/aortic_valve.obj")
[ "$faces" -eq "$triangles" ] || { echo "aortic_valve.obj: $faces faces, expected $triangles"; exit 1; }
for format in stl ply obj vtk; do
  tolerance=1e-5
  [ "$format" = vtk ] && tolerance=0
  "$compare" "$out/aortic_valve.vtp" "$out/aortic_valve.$format" --correspondence nearest --register none \
    --out "$out/compare_$format" --quiet || { echo "compare $format failed"; exit 1; }
  "$check_json" "$out/compare_$format/compare.summary.json" metrics.surface_distance.max_mm 0 "$tolerance" \
    metrics.reference_to_simulated.max_mm 0 "$tolerance" || { echo "$format copy is not the .vtp's geometry"; exit 1; }
done
ls "$out" | grep -q tmp && { echo "temporary files left behind"; exit 1; }
if "$generate" aortic_valve --out "$out/refused" --mesh-copies stl,step --quiet 2>"$out/refused.err"; then
  echo "--mesh-copies step accepted"; exit 1
fi
[ $? -eq 2 ] || true
grep -q -- '--mesh-copies: expected formats from vtk|stl|ply|obj, found "step"' "$out/refused.err" || { echo "unexpected error: $(cat "$out/refused.err")"; exit 1; }
[ ! -e "$out/refused" ] || { echo "a refused run wrote $out/refused"; exit 1; }
echo "copies of $triangles triangles: stl, ply, obj, vtk"
