#!/usr/bin/env bash
# check_snakemake_failure.sh VALVE_PIPELINE WORK
# generate_fail.json through its exported Snakefile (snakemake -k): snakemake fails, the
# failing steps of run kind-hexagon (valve-generate exits 2) leave no stamp, so nothing
# counts as done for either route, and the native dry run over the folder runs exactly
# those 2 steps again while the other run's 2 are cached.
# Exit 77 (ctest: skipped) when snakemake is not on PATH.
set -u
command -v snakemake >/dev/null || { echo "skipped: snakemake is not on PATH"; exit 77; }
vp=$1 work=$2
pipeline=$(cd "$(dirname "$0")" && pwd)/data/generate_fail.json
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work"
"$vp" export --snakemake "$pipeline" --out "$work" --quiet || fail "export"
if snakemake -s "$work/Snakefile" -j2 -k > "$work.log" 2>&1; then fail "snakemake succeeded although a stage failed"; fi
grep -q "step mesh of run kind-hexagon exited with 2" "$work.log" || { cat "$work.log"; fail "no message for the failed step"; }
[ -e "$work/runs/kind-hexagon/.valve-cache/mesh.json" ] && fail "a failed step has a stamp"
[ -e "$work/runs/kind-square-patch/.valve-cache/again.json" ] || fail "the run that succeeded has no stamp"
"$vp" run "$pipeline" --out "$work" --dry-run > "$work.dry_run" || fail "dry run"
grep -q "^dry run: 2 step(s) would run, 2 cached" "$work.dry_run" || { cat "$work.dry_run"; fail "dry run counts"; }
echo "ok: the failed run's steps have no stamp; $(tail -1 "$work.dry_run")"
