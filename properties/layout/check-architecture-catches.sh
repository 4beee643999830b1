#!/usr/bin/env bash
# ci/check-architecture must fail on each kind of disagreement, planted alone in scratch copies
# of docs/architecture.md and of the build's targets.tsv (or of ci/check-layers), and name it.
# Without this, a check that never fails passes. The planted edges use the build's own targets,
# found by folder, so the script names no profile and follows the tree as it changes.
# Usage: check-architecture-catches.sh SOURCE_ROOT BUILD_DIR
set -euo pipefail
src=$1 build=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
check=$src/ci/check-architecture
tsv=$build/targets.tsv
[[ -f $tsv && -f $build/declared_profiles/profiles.tsv ]] || { echo "no targets.tsv or profiles.tsv in $build: configure it"; exit 1; }

fresh() {
  cp "$src/docs/architecture.md" "$tmp/doc.md"
  cp "$tsv" "$tmp/targets.tsv"
  root=$src
}
run() { "$check" --root "$root" --build "$build" --doc "$tmp/doc.md" --targets "$tmp/targets.tsv"; }

fresh
run >"$tmp/out" || { cat "$tmp/out"; echo "the clean copies are rejected"; exit 1; }

# expect WHAT FRAGMENT...: the check, run on the scratch copies as planted, fails (exit 1, not
# an unreadable input) and prints every FRAGMENT.
expect() {
  local what=$1 fragment rc=0
  shift
  run >"$tmp/out" 2>&1 || rc=$?
  if ((rc != 1)); then cat "$tmp/out"; echo "not caught (exit $rc): $what"; exit 1; fi
  for fragment in "$@"; do
    grep -qF -- "$fragment" "$tmp/out" || { cat "$tmp/out"; echo "caught without naming it: $what"; exit 1; }
  done
  echo "caught: $what"
}
# A target of the build whose folder matches an awk regex (libraries first).
target_in() {
  awk -F'\t' -v re="$1" '$3 ~ re && $2 ~ /LIBRARY$/ {print $1; exit}' "$tmp/targets.tsv"
}
# Adds a link item to a target's LINK_LIBRARIES in the scratch targets.tsv.
add_link() {
  awk -F'\t' -v OFS='\t' -v t="$1" -v d="$2" '$1 == t {$4 = ($4 == "" ? d : $4 ";" d)} {print}' \
    "$tmp/targets.tsv" >"$tmp/t2" && mv "$tmp/t2" "$tmp/targets.tsv"
}

# A link edge the table forbids: a pc/ library linking a sim/ one.
fresh
from=$(target_in '^pc/') to=$(target_in '^sim/')
[[ -n $from && -n $to ]] || { echo "no pc/ or sim/ library in $tsv"; exit 1; }
add_link "$from" "$to"
expect "forbidden link pc/ -> sim/" "$from (" "links $to (" "pc/ may not link sim/"

# The MCU layers reach no model: a core/ library linking a models/ one.
fresh
from=$(target_in '^core/') to=$(target_in '^models/')
add_link "$from" "$to"
expect "forbidden link core/ -> models/" "core/ may not link models/"

# An arrow taken out of the table: sim/ may no longer use pc/. The build's sim/ -> pc/ edges
# and the diagram's arrow both break it.
fresh
sed -i '/^| `sim\/` |/s/`pc\/`, //' "$tmp/doc.md"
expect "sim/ -> pc/ removed from the table" "sim/ may not link pc/" "draws sim/ -> pc/, which the table forbids"

# A row for a layer that is not a folder of the tree, and a row naming one.
fresh
sed -i '/^| `protocol\/` |/a | `vendor/` | `vendor/`, `core/` | any |' "$tmp/doc.md"
expect "a row for a missing layer" "the table names layer vendor/, which is not a folder of the tree"
fresh
sed -i '/^| `core\/` |/s/`protocol\/` |/`protocol\/`, `drivers\/` |/' "$tmp/doc.md"
expect "a row naming a missing layer" "the table names layer drivers/, which is not a folder of the tree"

# A layer of the build without a row.
fresh
sed -i '/^| `bench\/` |/d' "$tmp/doc.md"
expect "a layer without a row" "the folder bench/ is a layer of the build (it has a CMakeLists.txt) and has no row"

# A target in a folder that no row places.
fresh
printf 'ap_stray\tSTATIC_LIBRARY\tvendor/stray\t\t\n' >>"$tmp/targets.tsv"
expect "a target outside every layer" "ap_stray (vendor/stray): its folder's layer vendor/ has no row"

# An arrow the table forbids: the pc/ box relabelled cli/, so sim/ draws an arrow to cli/.
fresh
sed -i 's/^ | pc\/  the PC side/ | cli\/ the PC side/' "$tmp/doc.md"
expect "an arrow the table forbids" "the diagram draws sim/ -> cli/, which the table forbids"

# A permission the diagram does not draw: the arrowhead into protocol/ taken out.
fresh
sed -i 's/^        v$/        |/' "$tmp/doc.md"
expect "a permission without an arrow" "the table lets core/ use protocol/, but no arrow of the diagram leads there"

# One profile's library linking another's (both in core/: the layer rule allows it).
fresh
mapfile -t names < <(cut -f1 "$build/declared_profiles/profiles.tsv")
from="" to=""
for a in "${names[@]}"; do
  for b in "${names[@]}"; do
    [[ $a == "$b" ]] && continue
    f=$(target_in "^core/$a/") t=$(target_in "^core/$b/")
    if [[ -n $f && -n $t ]]; then from=$f to=$t; break 2; fi
  done
done
[[ -n $from ]] || { echo "fewer than two profiles with a core library in $tsv"; exit 1; }
add_link "$from" "$to"
expect "a link between two profiles" "a profile links only its own folders and the shared ones"

# A shared library linking a profile's: pc/dds, the test bus, linking a core library of the
# first profile that has one.
fresh
from=$(target_in '^pc/dds$') to=""
for a in "${names[@]}"; do to=$(target_in "^core/$a/"); [[ -n $to ]] && break; done
add_link "$from" "$to"
expect "a shared library linking a profile's" "a shared folder links no profile's target"

# ci/check-layers' copy of a row drifting from the table (a scratch root of links to the tree).
fresh
root=$tmp/root; mkdir -p "$root/ci"
for e in "$src"/*; do [[ $(basename "$e") == ci ]] || ln -s "$e" "$root/"; done
cp "$src/ci/check-layers" "$root/ci/"
sed -i 's/^\( *"pc": *{\)"pc", /\1"pc", "models", /' "$root/ci/check-layers"
grep -q '"pc": *{"pc", "models", ' "$root/ci/check-layers" || { echo "ci/check-layers has no pc row to change"; exit 1; }
expect "ci/check-layers differs from the table" "ci/check-layers: its row for pc/"

echo "planted disagreements caught"
