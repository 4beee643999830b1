#!/usr/bin/env bash
# `axisproof frame` contract (docs/protocol.md): encode/decode round trip, typed errors with
# byte offsets, exit 0 only when every input decoded, 1 otherwise, 2 for usage errors.
# Usage: cli-frame.sh <path to axisproof>
set -u
ap=$1
. "$(dirname "$0")/../../cli-expect.sh"
expect 0 "encode issue example" "$ap" frame encode x=jog:+:fast y=goto:20000 sub=battery
frame=$out
[[ $frame == '>00002000002030200000100000000000000F98D;' ]] || { echo "FAIL encode bytes: $frame"; fail=1; }
expect 0 "decode it" "$ap" frame decode "$frame"
grep -q 'x: jog (id 2) data=2' <<<"$out" || { echo "FAIL decode fields: $out"; fail=1; }
grep -q 'sub0: battery (id 1)' <<<"$out" || { echo "FAIL decode subscriber: $out"; fail=1; }
bad=${frame/F98D/F98E}
expect 1 "decode corrupted" "$ap" frame decode "$frame" "$bad"
grep -q 'REJECTED bad_crc at byte 36' <<<"$out" || { echo "FAIL typed error: $out"; fail=1; }
expect 0 "decode capture from stdin" bash -c "printf '%s\n%s\n' '$frame' '<00508012000080340000000000000000000000000000000000000000000D168;' | '$ap' frame decode"
expect 1 "capture with garbage" bash -c "printf 'xx%s' '$frame' | '$ap' frame decode"
grep -q 'byte 0: GARBAGE xx' <<<"$out" || { echo "FAIL garbage report: $out"; fail=1; }
expect 1 "encode unknown command" "$ap" frame encode x=fly
expect 1 "encode out of range" "$ap" frame encode x=goto:-5
expect 2 "frame without subcommand" "$ap" frame
expect 2 "unknown option" "$ap" frame decode --bogus
exit $fail
