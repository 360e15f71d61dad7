#!/usr/bin/env bash
# check_snakemake_route.sh VALVE_PIPELINE P.json WORK STEPS [CHANGED "DUE RULES" [STAGE ...]]
# Runs P.json natively (WORK/native) and through its exported Snakefile with snakemake -j2
# (WORK/snakemake), then checks:
#   a) the same tables (time columns aside) and byte-identical meshes (compare_route_outputs.py);
#   b) each route ran STEPS stage invocations (native: the pipeline.log files; snakemake: the
#      stamps), required pipelines included;
#   c) a second snakemake has nothing to do (snakemake -n);
#   d) the native runner's --dry-run over the snakemake folder finds every step cached;
#   e) with CHANGED named: it and the STAGEs run as copies in WORK/bin; after the copy of
#      CHANGED changes (a rebuild), snakemake -n has exactly the DUE RULES (sorted) to run.
# Exit 77 (ctest: skipped) when snakemake is not on PATH.
set -u
command -v snakemake >/dev/null || { echo "skipped: snakemake is not on PATH"; exit 77; }
vp=$1 pipeline=$2 work=$3 steps=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
export OPENBLAS_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work/bin"
stage_dir=()
changed=${1:-} due_expected=${2:-}
[ $# -ge 2 ] && shift 2
if [ -n "$changed" ]; then
  for s in "$changed" "$@"; do cp "$(dirname "$vp")/$s" "$work/bin/$s" || fail "no stage $s beside $vp"; done
  stage_dir=(--stage-dir "$work/bin")
fi

"$vp" run "$pipeline" --out "$work/native" --jobs 2 --quiet "${stage_dir[@]}" || fail "native run"
"$vp" export --snakemake "$pipeline" --out "$work/snakemake" --quiet "${stage_dir[@]}" || fail "export"
snakemake -s "$work/snakemake/Snakefile" -j2 > "$work/snakemake.log" 2>&1 || { tail -30 "$work/snakemake.log"; fail "snakemake run"; }

python3 "$here/compare_route_outputs.py" "$work/native" "$work/snakemake" || fail "a) outputs differ"

native_steps=$(find "$work/native" -name pipeline.log -exec cat {} + | grep -c " ok exit ")
snake_steps=$(find "$work/snakemake" -path '*/.valve-cache/*.json' | wc -l)
echo "steps run: native $native_steps, snakemake $snake_steps (expected $steps)"
[ "$native_steps" -eq "$steps" ] && [ "$snake_steps" -eq "$steps" ] || fail "b) step counts"

snakemake -s "$work/snakemake/Snakefile" -n > "$work/again.log" 2>&1 || fail "c) snakemake -n failed"
grep -q "Nothing to be done" "$work/again.log" || { cat "$work/again.log"; fail "c) a second snakemake has work to do"; }
echo "second snakemake: nothing to be done"

"$vp" run "$pipeline" --out "$work/snakemake" --dry-run "${stage_dir[@]}" > "$work/dry_run.log" || fail "d) dry run"
grep -q "^dry run: 0 step(s) would run, $steps cached" "$work/dry_run.log" || { cat "$work/dry_run.log"; fail "d) native dry run"; }
tail -1 "$work/dry_run.log"

if [ -n "$changed" ]; then
  printf '\0' >> "$work/bin/$changed"  # a rebuilt stage: same behaviour, another hash
  snakemake -s "$work/snakemake/Snakefile" -n > "$work/rebuilt.log" 2>&1 || fail "e) snakemake -n failed"
  due=$(grep -Eo '^(rule|localrule) [A-Za-z0-9_]+' "$work/rebuilt.log" | awk '$2 != "all" {print $2}' | sort | tr '\n' ' ')
  echo "after $changed changed, due: $due"
  [ "$due" = "$due_expected " ] || { cat "$work/rebuilt.log"; fail "e) expected due: $due_expected"; }
fi
echo "ok"
