#!/bin/bash
# check_render.sh RENDER_EXE MESH.vtp OUT_DIR ARRAY
# Renders MESH coloured by ARRAY. Where a display or xvfb-run is available the stage must
# write valid PNGs for both views and a summary with status ok; elsewhere it must say
# "skipped" in the summary and still exit 0.
set -u
exe=$1 mesh=$2 out=$3 array=$4
rm -rf "$out"
"$exe" "$mesh" --out "$out" --array "$array" --quiet || { echo "valve-render exited $?"; exit 1; }
summary="$out/render.summary.json"
[ -f "$summary" ] || { echo "no summary"; exit 1; }
if grep -q '"skipped"' "$summary"; then
  if [ -n "${DISPLAY:-}" ] || command -v xvfb-run >/dev/null; then echo "skipped although a display is possible"; exit 1; fi
  echo "skipped (no display, no xvfb-run)"; exit 0
fi
stem=$(basename "$mesh" .vtp)
for view in top side; do
  png="$out/${stem}_${view}.png"
  [ -s "$png" ] || { echo "missing $png"; exit 1; }
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "$png is not a PNG"; exit 1; }
  # A blank picture compresses to a few hundred bytes; a rendered mesh with edges does not.
  [ "$(stat -c %s "$png")" -gt 20000 ] || { echo "$png looks blank"; exit 1; }
done
echo "ok"
