# Sourced by the CLI contract scripts (properties/*/cli-*.sh): run a command, keep its output
# in $out, and record a failure in $fail when its exit status is not the wanted one.
fail=0
expect() {  # expect <wanted status> <description> <command...>
  local want=$1 what=$2; shift 2
  out=$("$@" 2>&1); got=$?
  if [[ $got != "$want" ]]; then echo "FAIL $what: exit $got, wanted $want"; echo "$out"; fail=1; fi
}
