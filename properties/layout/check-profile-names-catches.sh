#!/usr/bin/env bash
# ci/check-profile-names must fail on one planted violation of each of its rules, each alone in a
# scratch copy of the tree, and name the file (and line) it was planted in; what its rules allow
# (documentation, a README hunk of a mutant, a profile's own folders) must stay allowed. The
# copy holds whatever the tree holds now, so the planted places are compared with the copy's
# own report before the plant, not with an empty one. The profiles' names are read from their
# declarations: none is written here.
set -euo pipefail
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
t=$tmp/t
mkdir -p "$t"
# The files the checker sees (tracked and untracked, not ignored), as they are in the tree now.
git -C "$src" ls-files -z --cached --others --exclude-standard |
  (cd "$src" && tar --null --ignore-failed-read -T - -cf - 2>/dev/null) | tar -xf - -C "$t"
git -C "$t" init -q
check() { "$t/ci/check-profile-names" "$t" 2>/dev/null; }
names=($(sed -n 's/^ap_declare_profile(\([a-z][a-z0-9]*\).*/\1/p' "$t"/profiles/*.cmake))
((${#names[@]} >= 2)) || { echo "fewer than two declared profiles in $src/profiles"; exit 1; }
p=${names[0]} q=${names[1]}
before=$(check || true)

# plant RULE FILE CONTENT EXPECTED-LINE...: CONTENT appended to FILE (created if new); the check
# must fail, and each EXPECTED-LINE (a regex) must match a line of its report the unplanted copy
# did not print. Then FILE is put back.
plant() {
  local rule=$1 file=$2 content=$3 out new re
  shift 3
  if [[ -e $t/$file ]]; then cp -p "$t/$file" "$tmp/saved"; else rm -f "$tmp/saved"; fi
  mkdir -p "$(dirname "$t/$file")"
  printf '%b' "$content" >>"$t/$file"
  if out=$(check); then echo "not caught: $rule"; exit 1; fi
  new=$(comm -13 <(sort <<<"$before") <(sort <<<"$out"))
  for re in "$@"; do
    grep -qE -- "$re" <<<"$new" || { echo "wrong report for $rule: no line /$re/ among the new ones:"; echo "$new"; exit 1; }
  done
  if [[ -e $tmp/saved ]]; then cp -p "$tmp/saved" "$t/$file"; else rm -f "$t/$file"; fi
  echo "caught: $rule ($file)"
}
# allowed RULE FILE CONTENT: CONTENT appended to FILE adds nothing to the report.
allowed() {
  local rule=$1 file=$2 content=$3 out
  if [[ -e $t/$file ]]; then cp -p "$t/$file" "$tmp/saved"; else rm -f "$tmp/saved"; fi
  mkdir -p "$(dirname "$t/$file")"
  printf '%b' "$content" >>"$t/$file"
  out=$(check || true)
  [[ $out == "$before" ]] || { echo "wrongly reported: $rule"; comm -13 <(sort <<<"$before") <(sort <<<"$out"); exit 1; }
  if [[ -e $tmp/saved ]]; then cp -p "$tmp/saved" "$t/$file"; else rm -f "$t/$file"; fi
  echo "allowed: $rule ($file)"
}
n() { echo $(($(wc -l <"$t/$1") + 1)); }  # the line number of a line appended to FILE

f=sim/kit/include/sim/lockstep.hpp
plant "a shared comment names a profile" $f "// as the $p board does\n" "^$f:$(n $f): names profile '$p'"
f=cli/profile.hpp
plant "a shared help text names a profile" $f "inline const char* kHelp = \"default: ${p^^}\";\n" "^$f:$(n $f): names profile '$p'"
plant "a shared script's path names a profile" ci/check-$p-only '#!/bin/sh\n' "^ci/check-$p-only: the path names profile '$p'"
f=profiles/$p.cmake
plant "a declaration names another profile" $f "# unlike $q\n" "^$f:$(n $f): names profile '$q'"
f=$(cd "$t" && ls -d */"$p" | head -n 1)/planted.txt
plant "a profile's folder names another profile" $f "see $q\n" "^$f:1: names profile '$q'"
plant "a mutant's header names a profile" ci/mutants/harness/planted.patch \
      "Mutant: planted\nModels: a $p bug\nProfile: harness\n---\ndiff --git a/README.md b/README.md\n--- a/README.md\n+++ b/README.md\n@@ -1 +1 @@\n-$p\n+$q\n" \
      "^ci/mutants/harness/planted.patch:2: names profile '$p'"
plant "a mutant's hunk of a shared file names a profile" ci/mutants/harness/planted.patch \
      "Mutant: planted\nProfile: harness\n---\ndiff --git a/cli/profile.hpp b/cli/profile.hpp\n--- a/cli/profile.hpp\n+++ b/cli/profile.hpp\n@@ -1 +1 @@\n-// x\n+// $p\n" \
      "^ci/mutants/harness/planted.patch:9: names profile '$p' \(the diff of cli/profile.hpp, a shared file\)"
# The names come from the declarations: a new one (zz9) is checked as soon as it is declared.
f=sim/kit/include/sim/lockstep.hpp
printf 'ap_declare_profile(zz9 TITLE "t")\n' >"$t/profiles/zz9.cmake"
before_zz9=$before
before=$(check || true)
plant "a newly declared profile's name in a shared file" $f "// zz9\n" "^$f:$(n $f): names profile 'zz9'"
rm -f "$t/profiles/zz9.cmake"
before=$before_zz9

allowed "documentation names the profiles" docs/planted.md "$p and $q\n"
allowed "the README names the profiles" README.md "$p and $q\n"
allowed "a profile's folder names its profile" "$(cd "$t" && ls -d */"$p" | head -n 1)/planted.txt" "$p\n"
allowed "a mutant's README hunk names the profiles" ci/mutants/harness/planted.patch \
        "Mutant: planted\nProfile: harness\n---\ndiff --git a/README.md b/README.md\n--- a/README.md\n+++ b/README.md\n@@ -1 +1 @@ $p\n-$p\n+$q\n"
echo "planted violations caught"
