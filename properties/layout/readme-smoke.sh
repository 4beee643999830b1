#!/usr/bin/env bash
# A cheap smoke of each command README.md shows, run as a user runs it (./axisproof from the
# source root, the ci/ scripts), so a command that no longer builds or starts fails `axisproof
# test`. One ctest per command (readme.<key>); `readme.every_command_has_a_smoke` fails when the
# README shows a command that has no case here. `./axisproof bench` here builds the release
# preset's benchmarks and lists them (a filter that matches nothing must be an error); running
# one is the gate's "benchmarks (release)" stage.
# Usage: readme-smoke.sh ROOT BUILD_DIR KEY
set -uo pipefail
root=$1 build=$2 key=$3
cd "$root" || exit 2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/readme-smoke.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
preset=$(basename "$build")   # build/<preset> (CMakePresets.json binaryDir)
# The profile the README's commands run without --profile: the one declared DEFAULT, read from
# the declarations' output (no profile is named here; docs/profiles.md).
default_profile() {  # FIELD: 1 name, 2 title (profiles.tsv)
  awk -F'\t' -v f="$1" '$6 == 1 { print $f; exit }' "$build/declared_profiles/profiles.tsv" 2>/dev/null
}
default=$(default_profile 1)
ere_quote() { sed 's/[][\.*^$(){}?+|/]/\\&/g' <<<"$1"; }

fail() { echo "FAIL readme.$key: $*"; exit 1; }
need_default() { [[ -n $default ]] || fail "$build/declared_profiles/profiles.tsv declares no default profile"; }
# expect RC OUTPUT_REGEX COMMAND...: run, show the tail, check the exit status and the output.
expect() {
  local want=$1 re=$2 rc
  shift 2
  echo "\$ $*"
  out=$("$@" 2>&1)
  rc=$?
  printf '%s\n' "$out" | tail -n 12
  [[ $rc -eq $want ]] || fail "'$*' exited $rc, want $want"
  [[ -z $re ]] || grep -qE -- "$re" <<<"$out" || fail "'$*' printed nothing matching /$re/"
}

# The commands README.md shows: `./axisproof SUB` and `ci/SCRIPT`, one key each.
readme_keys() {
  { grep -oE '\./axisproof [a-z]+' README.md | awk '{print "axisproof-" $2}'
    grep -oE '(^|[^a-z./-])ci/[a-z0-9][a-z0-9-]+' README.md | sed -E 's|.*ci/||' |
      while read -r s; do [[ -f ci/$s && -x ci/$s ]] && echo "ci-$s"; done; } | sort -u
}

case $key in
  list) readme_keys ;;
  every_command_has_a_smoke)
    known=" axisproof-gate axisproof-test axisproof-prove axisproof-fuzz axisproof-sim axisproof-frame axisproof-regs
            axisproof-gcode axisproof-bench ci-mutate ci-nightly-fuzz ci-coverage ci-m4-build ci-fresh-machine
            ci-compare-gate-results ci-check-workflows axisproof-panel "
    known=" $(echo $known) "
    n=0
    for k in $(readme_keys); do
      n=$((n + 1))
      [[ $known == *" $k "* ]] || fail "README.md shows '$k' but properties/layout/readme-smoke.sh has no smoke for it"
    done
    ((n >= 10)) || fail "found only $n commands in README.md: the extraction is broken"
    echo "ok: $n README commands, each with a smoke" ;;
  axisproof-gate)
    # Every stage skipped: the gate must still parse, print the table, write the reports and
    # the release manifest, and fail (a skipped stage is NOT RUN, and NOT RUN fails the gate).
    stages=(build-dev build-asan tests proofs fuzz e2e mutation coverage m4 qemu bench)
    args=()
    for s in "${stages[@]}"; do args+=(--skip "$s"); done
    expect 1 'NOT RUN' ./axisproof gate --out "$tmp/out" --junit "$tmp/junit.xml" "${args[@]}"
    [[ $(grep -c 'NOT RUN' <<<"$out") -ge ${#stages[@]} ]] || fail "the verdict table lists fewer than ${#stages[@]} NOT RUN stages"
    for f in gate/report.md gate/report.html release/manifest.json; do [[ -s $tmp/out/$f ]] || fail "gate wrote no $f"; done
    grep -q '<testsuite' "$tmp/junit.xml" || fail "gate wrote no JUnit XML"
    need_default
    grep -q "profile $default" <<<"$out" || fail "the verdict does not name the profile it judged"
    # The profiles the commands know (docs/profiles.md), and a name they do not know.
    expect 0 "^$default +$(ere_quote "$(default_profile 2)")" ./axisproof gate --profile list
    expect 2 '--profile: nosuch not in \{list,' ./axisproof gate --profile nosuch
    # Shards (docs/ci.md "Shards"): two shards, every stage skipped, joined into one verdict,
    # which equals the single-machine one stage by stage; a missing shard is named.
    expect 2 'needs 1 <= I <= N' ./axisproof gate --shard 3/2
    for i in 1 2; do expect 1 'NOT RUN' ./axisproof gate --shard "$i/2" --out "$tmp/shard-$i" "${args[@]}"; done
    expect 1 'verdict .*: FAIL' ./axisproof gate join "$tmp/shard-1" "$tmp/shard-2" --out "$tmp/joined" --junit "$tmp/joined.xml"
    for f in gate/report.md gate/report.html gate/result.json release/manifest.json; do [[ -s $tmp/joined/$f ]] || fail "gate join wrote no $f"; done
    expect 0 'equal' ci/compare-gate-results "$tmp/out" "$tmp/joined"
    expect 1 'shard 2/2 missing' ./axisproof gate join "$tmp/shard-1" --out "$tmp/joined-1" ;;
  ci-compare-gate-results)
    # Covered with the shards above (axisproof-gate); here: unreadable input is exit 2.
    expect 2 'no result.json' ci/compare-gate-results "$tmp/nothing" "$tmp/nothing" ;;
  ci-check-workflows)
    # The workflow files the README points a team to (docs/ci.md), against this build's CLI.
    expect 0 'no problems' ci/check-workflows --cli "$build/cli/axisproof" ;;
  axisproof-test)
    expect 0 '100% tests passed' ./axisproof test --preset "$preset" -R '^cli\.unknown_subcommand_exits_2$' ;;
  axisproof-prove)
    expect 0 '1 obligations: 1 proved' ./axisproof prove --only axis.dd.monotone
    # Two processes (docs/proofs.md): the second one's outcomes must reach the table and the count.
    expect 0 '^5 obligations: 5 proved, 0 failed, 0 unknown' ./axisproof prove --only axis.dd. --jobs 2
    [[ $(grep -c '^axis\.dd\..* PROVED ' <<<"$out") -eq 5 ]] || fail "prove --jobs 2: the table does not list the 5 obligations as PROVED" ;;
  axisproof-fuzz)
    [[ -n $(find "$build/fuzz" -name fuzz_frame_parser -type f 2>/dev/null) ]] ||
      fail "$build has no libFuzzer binaries (this smoke is registered only where AP_FUZZ_BINARIES is on)"
    expect 0 'frame_parser' ./axisproof fuzz --target frame_parser --time 2 --jobs 1 --no-save --build-dir "$build" ;;
  axisproof-sim)
    need_default
    expect 0 '' ./axisproof sim run scenarios/$default/absolute_20mm --out "$tmp/sim"
    [[ -s $tmp/sim/absolute_20mm/trace.csv ]] || fail "sim run wrote no trace.csv"
    # `sim board` in another process, the PC joining it (docs/sim.md).
    domain=$((100 + RANDOM % 100))
    ./axisproof sim board --domain "$domain" --boards 1 --idle-timeout 60 >"$tmp/board.log" 2>&1 &
    board=$!
    expect 0 '' ./axisproof sim run scenarios/$default/absolute_20mm --domain "$domain" --join --out "$tmp/join"
    wait "$board" || fail "sim board exited $? ($(tail -3 "$tmp/board.log"))"
    # The same run on the default profile's Cortex-M4 image under QEMU (docs/qemu.md).
    expect 0 'ihold_irun: PASS' ./axisproof sim run --target qemu scenarios/$default/ihold_irun --out "$tmp/qemu"
    grep -qx 'divergences 0' "$tmp/qemu/ihold_irun/qemu.txt" || fail "the QEMU run wrote no qemu.txt or diverged" ;;
  axisproof-frame)
    # The frames docs/protocol.md prints for these commands.
    expect 0 '' ./axisproof frame encode seq=1 x=stop y=goto:20000
    frame=$(tail -n 1 <<<"$out")
    grep -qF -- "$frame" docs/protocol.md || fail "encode printed '$frame', which docs/protocol.md does not show"
    expect 0 'goto' ./axisproof frame decode "$frame"
    need_default
    expect 0 'goto' ./axisproof frame decode --profile "$default" "$frame" ;;
  axisproof-panel)
    # Every declared profile's panel starts, serves its page and its tables, and ends on SIGTERM
    # (docs/panel.md); a profile without one says so (exit 2). The browser tests are in the
    # profiles' properties folders.
    get() { python3 -c 'import sys, urllib.request; print(urllib.request.urlopen(sys.argv[1], timeout=10).read().decode())' "$1"; }
    served=0
    while IFS=$'\t' read -r name _; do
      [[ -n $name ]] || continue
      ./axisproof panel --profile "$name" --port 0 >"$tmp/panel.out" 2>&1 &
      pid=$!
      for _ in $(seq 1 300); do
        grep -q 'http://127.0.0.1:' "$tmp/panel.out" && break
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.2
      done
      url=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$tmp/panel.out" | head -1)
      if [[ -z $url ]]; then
        wait "$pid"
        rc=$?
        [[ $rc -eq 2 ]] && grep -q 'has no panel yet' "$tmp/panel.out" && { echo "profile $name: no panel"; continue; }
        fail "panel --profile $name printed no URL (exit $rc): $(cat "$tmp/panel.out")"
      fi
      expect 0 '<title>' get "$url"
      expect 0 '"title"' get "${url}api/info"
      kill -TERM "$pid"
      wait "$pid"
      rc=$?
      [[ $rc -eq 0 ]] || fail "axisproof panel --profile $name exited $rc after SIGTERM"
      served=$((served + 1))
    done <"$build/declared_profiles/profiles.tsv"
    ((served >= 1)) || fail "no profile serves a panel" ;;
  axisproof-regs)
    expect 0 'IHOLD_IRUN' ./axisproof regs
    expect 0 '^register,address,access,field,mask,shift,width,signed' ./axisproof regs --format csv
    expect 0 'IHOLD_IRUN' ./axisproof regs decode 90 00 07 0C 03 ;;
  axisproof-gcode)
    # The thesis's Tab. 3 (seed-003.md §5.2): row 15 as printed there, then the program end to
    # end over the DDS bus (docs/cnc.md) with its outputs; a line the strict dialect refuses.
    expect 0 ' 15 +0,2 +3 +25,5 +160,5 +26 ' ./axisproof gcode --table3
    # The program is the one README.md shows.
    program=$(grep -oE '\./axisproof gcode [^ `]+\.gcode' README.md | head -n 1 | cut -d' ' -f3)
    [[ -f $program ]] || fail "README.md shows no './axisproof gcode PROGRAM.gcode' whose program exists"
    name=$(basename "$program" .gcode)
    expect 0 "scenario $name: PASS" ./axisproof gcode "$program" --dialect thesis --out "$tmp/gcode"
    for f in trace.csv path.csv path.svg profile.svg; do [[ -s $tmp/gcode/$name/$f ]] || fail "gcode wrote no $f"; done
    printf 'N1  G1 X1\n' > "$tmp/bad.gcode"
    expect 2 'bad.gcode:1:4: BadSpacing' ./axisproof gcode "$tmp/bad.gcode" --dialect thesis ;;  # the second space
  axisproof-bench)
    # Builds the release benchmarks (what broke on a fresh clone) and lists them; the gate's
    # "benchmarks (release)" stage runs one.
    expect 2 'no benchmark matches' ./axisproof bench --filter '^no such benchmark$' ;;
  ci-mutate)
    patches=$(ls ci/mutants/*/*.patch | wc -l)
    ((patches > 0)) || fail "no mutant in ci/mutants/*/"
    expect 0 '' ci/mutate --list
    [[ $(grep -cE '^[a-z0-9]+-' <<<"$out") -ge $patches ]] || fail "ci/mutate --list names fewer mutants than the $patches patches" ;;
  ci-nightly-fuzz)
    # Its two parts, `axisproof fuzz` and `ci/coverage corpus`, have smokes of their own; here
    # its usage (it writes to fuzz/corpus, which a test must not).
    expect 0 'nightly' ci/nightly-fuzz --help
    expect 2 'usage' ci/nightly-fuzz --no-such-option ;;
  ci-coverage)
    # A profile of one instrumented test, reported as the gate does (--build-dir, --profiles).
    grep -q '^AP_COVERAGE:BOOL=ON' "$build/CMakeCache.txt" || fail "$build is not built with coverage"
    mkdir -p "$tmp/prof"
    need_default
    LLVM_PROFILE_FILE="$tmp/prof/%m.profraw" "$build/properties/$default/protocol/protocol_unit" --gtest_brief=1 >/dev/null 2>&1 ||
      fail "protocol_unit failed"
    expect 0 'branch' ci/coverage tests --build-dir "$build" --profiles "$tmp/prof" ;;
  ci-m4-build)
    expect 0 'flash' ci/m4-build --out "$tmp/m4" ;;
  ci-fresh-machine)
    # The real run needs tens of minutes and the package mirror (README.md): usage only.
    expect 0 'debootstrap' ci/fresh-machine --help
    expect 2 'unknown argument' ci/fresh-machine --no-such-option ;;
  *) echo "readme-smoke.sh: unknown key '$key'" >&2; exit 2 ;;
esac
echo "ok readme.$key"
