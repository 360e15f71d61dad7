#!/usr/bin/env bash
# check_same_metrics.sh CHECK_JSON A.json B.json PATH...
# Every number at PATH in B must equal the one in A to 1e-5 relative (check_json prints A's
# value to 6 significant digits): two routes to the same figure, e.g. a metric computed
# inside valve-simulate and again by a stage reading its output file.
set -u
check_json=$1 a=$2 b=$3
shift 3
failures=0
for path in "$@"; do
  value=$("$check_json" "$a" "$path" -1e300 1e300 | awk '{print $4}')
  if [ -z "$value" ]; then echo "FAIL $path: not in $a"; failures=$((failures + 1)); continue; fi
  range=$(awk -v v="$value" 'BEGIN { t = (v < 0 ? -v : v) * 1e-5 + 1e-9; printf "%.17g %.17g", v - t, v + t }')
  # shellcheck disable=SC2086
  "$check_json" "$b" "$path" $range || failures=$((failures + 1))
done
exit $((failures > 0))
