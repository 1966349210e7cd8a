#!/usr/bin/env bash
# `tacta check-plugin` as a plugin author runs it. Usage:
#   check_plugin_test.sh TACTA passes PLUGIN            every check passes or is skipped (exit 0)
#   check_plugin_test.sh TACTA broken BROKEN_SO         exit 1, the broken checks named
#   check_plugin_test.sh TACTA fails_exactly PLUGIN 'CHECK|CHECK...'
#                                                       exit 1, and the failing checks are exactly
#                                                       these (a check a sanitizer build skips is
#                                                       dropped from the set)
#   check_plugin_test.sh TACTA bad_input DEVICE_NAME    exit 2 for an unknown name, a missing file,
#                                                       a plugin of another kind
set -u
tacta=$1
mode=$2
plugin=$3
failures=0
fail() { echo "FAIL [$mode $plugin]: $*" >&2; failures=$((failures + 1)); }
out=$(mktemp)
trap 'rm -f "$out"' EXIT

# run EXPECTED_EXIT ARGS...: output in $out, exit code checked.
run() {
  local expected=$1
  shift
  "$tacta" check-plugin "$@" >"$out" 2>&1
  local rc=$?
  [ "$rc" -eq "$expected" ] || fail "tacta check-plugin $* exited $rc, expected $expected"
}
expect() { grep -Eq -- "$1" "$out" || fail "output does not show /$1/"; }

case $mode in
  passes)
    run 0 "$plugin"
    expect '^  PASS  force at rest: max \|f\| [^ ]+ N'
    expect '^  PASS  step on a worker thread'
    expect '^  PASS  checkpoint: a fresh instance, .* 0 position/velocity doubles differ'
    expect '^  (PASS  topology edits: separation .*; removal |SKIP  topology edits: not claimed)'
    grep -q '^  FAIL' "$out" && fail "a check failed"
    ;;
  broken)
    run 1 "$plugin"
    expect '^  FAIL  force at rest: max \|f\| 1 N \(internal_forces\), limit'
    expect '^  FAIL  net internal force'
    # Under a sanitizer tacta cannot count malloc and says so; elsewhere the malloc is caught.
    if ! grep -q '^  SKIP  no allocation in step' "$out"; then
      expect '^  FAIL  no allocation in step: [1-9][0-9]* heap allocations'
    fi
    expect '^  PASS  parameter schema'
    # Neither save_state/load_state nor the NO_HISTORY claim: a restore could not continue it.
    expect '^  FAIL  checkpoint: not checkpointable'
    ;;
  fails_exactly)
    expected=$(printf '%s\n' "${4:-}" | tr '|' '\n' | sed '/^$/d' | sort)
    "$tacta" check-plugin "$plugin" >"$out" 2>&1
    rc=$?
    skipped=$(sed -n 's/^  SKIP  \([^:]*\):.*/\1/p' "$out" | sort)
    expected=$(comm -23 <(printf '%s\n' "$expected") <(printf '%s\n' "$skipped") | sed '/^$/d')
    failed=$(sed -n 's/^  FAIL  \([^:]*\):.*/\1/p' "$out" | sort)
    [ "$failed" = "$expected" ] || fail "failing checks: [${failed//$'\n'/, }], expected [${expected//$'\n'/, }]"
    want_rc=1
    [ -z "$expected" ] && want_rc=0
    [ "$rc" -eq "$want_rc" ] || fail "tacta check-plugin $plugin exited $rc, expected $want_rc"
    ;;
  bad_input)
    run 2 "${plugin}_typo"
    expect 'no model plugin named'
    run 2 "$plugin"
    expect "is a [a-z]+ plugin, not a model plugin"
    run 2 /no/such/plugin.so
    expect 'no such plugin file'
    ;;
esac
[ "$failures" -eq 0 ] || { sed 's/^/    /' "$out" >&2; exit 1; }
echo "ok [$mode $plugin]"
