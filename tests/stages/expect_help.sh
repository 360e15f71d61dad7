#!/usr/bin/env bash
# expect_help.sh STAGE_NAME -- COMMAND...
# COMMAND (a stage given --help) exits 0, prints its usage on stdout (the text names the
# stage and its --out flag), nothing on stderr.
set -u
name=$1
shift
[ "$1" = "--" ] && shift
err=$(mktemp)
out=$("$@" 2>"$err")
rc=$?
if [ "$rc" -ne 0 ]; then echo "exit $rc, expected 0: $(cat "$err")"; rm -f "$err"; exit 1; fi
if [ -s "$err" ]; then echo "stderr not empty: $(cat "$err")"; rm -f "$err"; exit 1; fi
rm -f "$err"
case "$out" in *"$name"*"--out"*) ;; *) echo "usage lacks '$name ... --out': $out"; exit 1 ;; esac
echo "$out" | head -1
