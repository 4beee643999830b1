#!/bin/bash -eu
# ClusterFuzzLite / OSS-Fuzz build script: builds every libFuzzer target of fuzz/ with the
# standard variables and copies it to $OUT, with its dictionary (<target>.dict) and its seed
# corpus (<target>_seed_corpus.zip).
#   CC CXX CFLAGS CXXFLAGS   compilers and flags (sanitizers and coverage instrumentation)
#   LIB_FUZZING_ENGINE       link flags of the engine (e.g. -fsanitize=fuzzer)
#   OUT                      where the binaries go;  WORK  scratch (default $OUT/../work)
# Runs locally too (ci/check-clusterfuzzlite, ctest fuzz.clusterfuzzlite_build_sh):
#   CC=clang CXX=clang++ CFLAGS='-fsanitize=address,fuzzer-no-link' \
#   CXXFLAGS='-fsanitize=address,fuzzer-no-link' LIB_FUZZING_ENGINE=-fsanitize=fuzzer \
#   OUT=/tmp/x .clusterfuzzlite/build.sh
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [[ -f $here/../CMakeLists.txt ]]; then root=$(cd "$here/.." && pwd)   # .clusterfuzzlite/build.sh in the tree
else root=${SRC:?}/axisproof; fi                                         # $SRC/build.sh in the image
work=${WORK:-$OUT/../work}/axisproof-build
mkdir -p "$OUT" "$work"
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
if [[ ! -f $work/CMakeCache.txt ]]; then
  cmake -S "$root" -B "$work" "${gen[@]}" \
    -DCMAKE_BUILD_TYPE= \
    -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX" \
    -DCMAKE_C_FLAGS="$CFLAGS" -DCMAKE_CXX_FLAGS="$CXXFLAGS" \
    -DAP_FUZZ=ON -DAP_FUZZ_ENGINE="$LIB_FUZZING_ENGINE"
else
  cmake "$work" >/dev/null
fi
mapfile -t names < <(cut -f1 "$work/fuzz_targets.txt")
if ((${#names[@]} == 0)); then
  echo "build.sh: no fuzz targets (fuzz/<group>/CMakeLists.txt calling ap_add_fuzz_target)" >&2
  exit 1
fi
targets=()
for n in "${names[@]}"; do targets+=("fuzz_$n"); done
cmake --build "$work" --parallel "${AP_JOBS:-2}" --target "${targets[@]}"
# A target's data sit in its profile's fuzz folder (the sixth column): corpus/<name>,
# dict/<name or group>.dict, and the options beside its sources.
while IFS=$'\t' read -r name group bin _replay _profile data; do
  cp "$bin" "$OUT/$name"
  # libFuzzer options (OSS-Fuzz's <target>.options, [libfuzzer] key = value), e.g. max_len.
  for o in "$data/$group/$name.options" "$data/$name.options"; do
    if [[ -f $o ]]; then cp "$o" "$OUT/$name.options"; break; fi
  done
  for d in "$data/dict/$name.dict" "$data/dict/$group.dict"; do
    if [[ -f $d ]]; then cp "$d" "$OUT/$name.dict"; break; fi
  done
  corpus=$data/corpus/$name
  if [[ -d $corpus ]] && [[ -n $(ls -A "$corpus") ]]; then
    rm -f "$OUT/${name}_seed_corpus.zip"
    if command -v zip >/dev/null; then (cd "$corpus" && zip -q -r "$OUT/${name}_seed_corpus.zip" .)
    else python3 -c 'import shutil,sys; shutil.make_archive(sys.argv[1], "zip", sys.argv[2])' "$OUT/${name}_seed_corpus" "$corpus"; fi
  fi
  echo "build.sh: $OUT/$name"
done <"$work/fuzz_targets.txt"
