#!/usr/bin/env bash
# expect_exit.sh CODE -- COMMAND...
# Runs COMMAND and passes when it exits with CODE (for runs that are meant to fail but
# still write their outputs, unlike expect_failure.sh's nothing-written contract).
set -u
code=$1
shift
[ "$1" = "--" ] && shift
"$@"
rc=$?
if [ "$rc" -ne "$code" ]; then echo "expected exit $code, got $rc"; exit 1; fi
echo "ok: exit $rc"
