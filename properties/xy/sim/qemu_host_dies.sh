#!/usr/bin/env bash
# QEMU stops when its host dies (docs/qemu.md, "When the host dies"): the CLI of a
# `sim run --target qemu` killed with SIGKILL (no destructor runs) must not leave
# qemu-system-arm running: it must be gone within 5 s (the kernel kills it at once).
# Usage: qemu_host_dies.sh SOURCE_DIR
set -euo pipefail
cd "$1"
tmp=$(mktemp -d)
q=""
cleanup() { [[ -n $q ]] && kill -9 "$q" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
# manual_reversal: 14 s of emulated time, long enough to be killed in the middle.
./axisproof sim run --target qemu scenarios/xy/manual_reversal --out "$tmp/run" >"$tmp/cli.log" 2>&1 &
for _ in $(seq 1 1200); do   # up to 120 s: the first run may build the m4 image
  q=$(pgrep -f -- "path=$tmp/run/.*link\.sock" | head -1 || true)
  [[ -n $q ]] && break
  sleep 0.1
done
if [[ -z $q ]]; then echo "FAIL: no qemu-system-arm started"; tail -5 "$tmp/cli.log"; exit 1; fi
sleep 1   # the image runs and talks to its host
host=$(ps -o ppid= -p "$q" | tr -d ' ')
[[ -n $host && $host != 1 ]] || { echo "FAIL: QEMU ($q) has no host process"; exit 1; }
kill -9 "$host"
for _ in $(seq 1 50); do
  state=$(ps -o stat= -p "$q" 2>/dev/null || true)
  if [[ -z $state || $state == Z* ]]; then   # gone, or exited and not yet reaped by init
    echo "PASS: QEMU exited after its host (pid $host) was killed"; q=""; exit 0; fi
  sleep 0.1
done
echo "FAIL: QEMU ($q) still running 5 s after its host (pid $host) was killed"
exit 1
