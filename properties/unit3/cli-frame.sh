#!/usr/bin/env bash
# `axisproof frame decode --profile unit3` (docs/unit3.md "The wire"): the thesis's strings
# decode to what the thesis says they mean, typed errors name the byte, a capture is cut at
# `;`, the unit's refusal replies are named, and a scenario runs through `sim run --profile`.
# Usage: cli-frame.sh <path to axisproof>
set -u
ap=$1
. "$(dirname "$0")/../cli-expect.sh"
has() { grep -qF -- "$1" <<<"$out" || { echo "FAIL $2: no '$1' in: $out"; fail=1; }; }
expect 0 "thesis examples" "$ap" frame decode --profile unit3 'Y000000000016000;' 'Y000000000000500;'
has 'line 1: OK move Y by 16000 counts' "full-step example"
has 'line 2: OK move Y by 500 counts' "1/32 example"
expect 1 "mode digit 6" "$ap" frame decode --profile unit3 'M506;'
has 'REJECTED mode_out_of_range at byte 3' "typed error"
expect 0 "a report" "$ap" frame decode --profile unit3 'Z-000000000000000500;'
has 'report Z counter -500' "report"
expect 0 "capture" bash -c "printf 'D+-+;\r\nM505;T046;C;G;' | '$ap' frame decode --profile unit3"
has '5 command(s) decoded, 0 rejected' "capture count"
expect 1 "capture with a lost byte" bash -c "printf 'X00000000016000;G;' | '$ap' frame decode --profile unit3"
has 'byte 0: REJECTED bad_length' "lost byte"
expect 0 "refusals" "$ap" frame decode --profile unit3 'E20;' 'E02;'
has 'line 1: OK refusal E20 busy' "unit refusal named"
has 'line 2: OK refusal E02 bad_length' "line error named"
expect 1 "unknown refusal" "$ap" frame decode --profile unit3 'E19;'
has 'REJECTED unknown refusal code 19' "unknown code"
out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT
src=$(cd "$(dirname "$0")/../.." && pwd)
expect 0 "a bundled scenario" "$ap" sim run --profile unit3 "$src/scenarios/unit3/thesis_full_step.scn" --out "$out_dir"
has 'PASS' "scenario verdict"
[[ -s $out_dir/thesis_full_step/trace.csv && -s $out_dir/thesis_full_step/waveforms.vcd ]] || { echo "FAIL outputs: no trace.csv / waveforms.vcd in $out_dir/thesis_full_step"; fail=1; }
expect 0 "its proofs" "$ap" prove --profile unit3
has '5 obligations: 5 proved' "unit3 obligations"
exit $fail
