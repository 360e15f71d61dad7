#!/usr/bin/env bash
# expect_no_partial_output.sh VALVE_GENERATE OUTDIR
# A stage that fails half way through its outputs leaves none of them: here the third of
# three meshes cannot be written (a folder squats its name), so the first two must go too.
set -u
gen=$1 out=$2
rm -rf "$out"
mkdir -p "$out/sq_3.vtp"
err=$("$gen" square_patch --out "$out" --count 3 --name sq --seed 1 --quiet 2>&1 >/dev/null)
rc=$?
[ "$rc" -ne 0 ] || { echo "expected a failure, got exit 0"; exit 1; }
printf '%s\n' "$err" | grep -q "sq_3.vtp" || { echo "stderr does not name sq_3.vtp: $err"; exit 1; }
left=$(find "$out" -type f)
[ -z "$left" ] || { echo "files left behind: $left"; exit 1; }
echo "ok: exit $rc, nothing left ($err)"
