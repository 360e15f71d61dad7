#!/usr/bin/env bash
# expect_failure.sh CODE OUTDIR PATTERN -- COMMAND...
# Runs COMMAND and checks the bad-input contract: exit code CODE, exactly one line on
# stderr matching PATTERN, and no output files (other than none) left in OUTDIR.
set -u
code=$1 out=$2 pattern=$3
shift 3
[ "$1" = "--" ] && shift
rm -rf "$out"
err=$("$@" 2>&1 >/dev/null)
rc=$?
if [ "$rc" -ne "$code" ]; then echo "expected exit $code, got $rc; stderr: $err"; exit 1; fi
lines=$(printf '%s\n' "$err" | grep -c .)
if [ "$lines" -ne 1 ]; then echo "expected one stderr line, got $lines: $err"; exit 1; fi
if ! printf '%s' "$err" | grep -q -- "$pattern"; then echo "stderr does not mention '$pattern': $err"; exit 1; fi
if [ -d "$out" ] && [ -n "$(find "$out" -type f)" ]; then echo "files left behind:"; find "$out" -type f; exit 1; fi
echo "ok: exit $rc, $err"
