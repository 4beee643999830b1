#!/usr/bin/env bash
# Usage errors exit 2 with exactly one line on stderr; --help exits 0.
set -uo pipefail
cli=$1
for args in "nonsense" "gate --no-such-option"; do
  err=$("$cli" $args 2>&1 >/dev/null); rc=$?
  [[ $rc -eq 2 ]] || { echo "'$args' exited $rc, want 2"; exit 1; }
  lines=$(printf '%s\n' "$err" | wc -l)
  [[ $lines -eq 1 ]] || { echo "'$args' printed $lines lines: $err"; exit 1; }
done
for sub in gate test prove fuzz sim bench; do
  "$cli" $sub --help >/dev/null || { echo "$sub --help failed"; exit 1; }
done
echo ok
