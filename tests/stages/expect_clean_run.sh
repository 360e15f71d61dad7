#!/usr/bin/env bash
# expect_clean_run.sh OUTDIR -- COMMAND...
# Stability contract for extreme inputs: COMMAND (a valve-simulate run writing to OUTDIR)
# ends within the ctest timeout with exit 0 (ok) or 3 (not_converged / failed), writes a
# summary whose status says which, never replaces a non-finite value in it, writes the
# deformed mesh when it reports ok and none when it reports failed.
set -u
out=$1
shift
[ "$1" = "--" ] && shift
rm -rf "$out"
"$@" >/dev/null 2>"$out.stderr"
rc=$?
summary="$out/simulate.summary.json"
if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then echo "exit $rc: $(cat "$out.stderr")"; exit 1; fi
if [ ! -f "$summary" ]; then echo "no summary written"; exit 1; fi
status=$(grep -o '"status": "[a-z_]*"' "$summary" | tail -1 | sed 's/.*: "//; s/"//')
if grep -q non_finite_values_replaced_by_null "$summary"; then echo "summary had non-finite values"; exit 1; fi
case "$status" in
  ok) [ "$rc" -eq 0 ] && [ -f "$out/closed.sim.vtp" ] || { echo "ok but exit $rc or no mesh"; exit 1; } ;;
  not_converged) [ "$rc" -eq 3 ] && [ -f "$out/closed.sim.vtp" ] || { echo "not_converged but exit $rc or no mesh"; exit 1; } ;;
  failed) [ "$rc" -eq 3 ] && [ ! -f "$out/closed.sim.vtp" ] || { echo "failed but exit $rc or a mesh written"; exit 1; } ;;
  *) echo "unexpected status '$status'"; exit 1 ;;
esac
reason=$(grep -o '"reason": "[^"]*"' "$summary" | tail -1)
echo "status $status ($reason)"
