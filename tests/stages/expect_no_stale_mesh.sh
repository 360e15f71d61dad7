#!/usr/bin/env bash
# expect_no_stale_mesh.sh VALVE_SIMULATE SCENE OUTDIR
# A run that succeeds writes closed.sim.vtp; a failed run (exit 3) into the same folder must
# then leave its failed summary and no mesh: "a failed one writes no mesh" (valve-simulate).
set -u
sim=$1 scene=$2 out=$3
rm -rf "$out"
"$sim" --scene "$scene" --model mass_spring --out "$out" --quiet || { echo "the first run failed"; exit 1; }
[ -f "$out/closed.sim.vtp" ] || { echo "the first run wrote no closed.sim.vtp"; exit 1; }
# 1000 MPa tears the membrane: the run fails (numerical failure, exit 3).
"$sim" --scene "$scene" --model mass_spring --pressure "1000 MPa" --out "$out" --quiet 2>/dev/null
rc=$?
[ "$rc" -eq 3 ] || { echo "expected exit 3 from the failing run, got $rc"; exit 1; }
# The top-level status (the summary is indented by two spaces per level).
grep -q '^  "status": "failed"' "$out/simulate.summary.json" || { echo "the summary does not say failed"; exit 1; }
[ ! -e "$out/closed.sim.vtp" ] || { echo "closed.sim.vtp from the first run is still there"; exit 1; }
echo "ok: the failed run left its summary and no mesh"
