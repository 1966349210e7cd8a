#!/usr/bin/env bash
# Tests of the `tacta` command line: exit codes (0 ok, 1 runtime fault, 2 bad input), messages
# that name file:line:column, and the files a run writes.
# Usage: cli_test.sh TACTA_BINARY SOURCE_DIR WORK_DIR CASE
set -u
tacta=$1
src=$2
work=$3/$4
case_name=$4
rm -rf "$work" && mkdir -p "$work"
cd "$work" || exit 1

failures=0
fail() { echo "FAIL [$case_name]: $*" >&2; failures=$((failures + 1)); }

# run EXPECTED_EXIT ARGS...: runs tacta, keeps stdout+stderr in $work/out.txt, checks the exit code.
run() {
  local expected=$1
  shift
  "$tacta" "$@" >"$work/out.txt" 2>&1
  local rc=$?
  if [ "$rc" -ne "$expected" ]; then
    fail "tacta $* exited $rc, expected $expected; output:"
    sed 's/^/    /' "$work/out.txt" | head -20 >&2
  fi
}
# expect_output REGEX WHAT: the last run's output matches the extended regex.
expect_output() {
  if ! grep -Eq -- "$1" "$work/out.txt"; then
    fail "output does not show $2 (/$1/); output:"
    sed 's/^/    /' "$work/out.txt" | head -20 >&2
  fi
}
expect_file() { [ -s "$1" ] || fail "missing or empty: $1"; }

case "$case_name" in
  help)
    run 0 --help
    expect_output 'run' "the run subcommand"
    run 0 run --help
    expect_output '--out' "the --out option"
    run 0 plugins
    expect_output 'tensor_mass' "the tensor_mass plugin"
    run 0 mesh-info "$src/assets/meshes/liver.msh"
    expect_output '[0-9]+' "counts"
    run 0 mesh-info --help
    ;;
  broken_scene)
    # A YAML syntax error: an unclosed flow sequence on line 3.
    printf 'name: broken\ngravity: [0, -9.81, 0]\nbodies: [\n  {name: a\n' >syntax.yaml
    run 2 run syntax.yaml --out out
    expect_output 'syntax\.yaml:[0-9]+:[0-9]+' "file:line:column"
    # An unknown key (a typo) on line 6, column 5.
    cat >typo.yaml <<'YAML'
name: typo
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    modle: tensor_mass
YAML
    run 2 run typo.yaml --out out
    expect_output 'typo\.yaml:6:5:' "file:line:column of the unknown key"
    expect_output "did you mean 'model'" "a did-you-mean hint"
    [ -e out/report.json ] && fail "a scene that does not load wrote a report"
    ;;
  broken_mesh)
    head -n 15 "$src/assets/meshes/cube_low_res.msh" >truncated.msh
    run 2 mesh-info truncated.msh
    expect_output 'truncated\.msh' "the mesh file's name"
    cat >uses_truncated.yaml <<'YAML'
name: uses_truncated
bodies:
  - name: cube
    mesh: {file: truncated.msh}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: tensor_mass
YAML
    run 2 run uses_truncated.yaml --out out
    expect_output 'truncated\.msh' "the mesh file's name"
    ;;
  absent_scene)
    run 2 run no_such_scene.yaml --out out
    expect_output 'no_such_scene\.yaml' "the absent file's name"
    ;;
  diverging_scene)
    # Explicit Euler on a stiff square at 25 Hz: the amplitude grows every step until the body
    # passes ten body sizes of displacement and is frozen.
    cat >diverges.yaml <<'YAML'
name: diverges
gravity: [0, 0, 0]
clock: {haptic_rate_hz: 25, render_rate_hz: 5, duration_s: 20}
bodies:
  - name: square
    mesh: unit_square
    material: {lame_lambda: 100.0, lame_mu: 100.0, density: 1.0}
    model: {name: fd_debunne, integrator: explicit_euler}
    initial:
      displacement: [{node: 3, value: [-0.05, -0.05, 0]}]
YAML
    run 1 run diverges.yaml --out out
    expect_file out/report.json
    grep -q '"faults"' out/report.json || fail "report.json lists no faults"
    grep -Eq '"frozen": true' out/report.json || fail "report.json does not say the body was frozen"
    expect_output 'FROZEN' "the frozen body"
    ;;
  seed_case_b)
    run 0 run "$src/scenes/seed/unit_square_case_b.yaml" --out out
    expect_file out/phase_portrait.png
    expect_file out/trajectory.csv
    expect_file out/report.json
    # A PNG starts with its 8-byte signature.
    [ "$(head -c 8 out/phase_portrait.png | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
      fail "phase_portrait.png is not a PNG"
    grep -q '"ticks": 9472' out/report.json || fail "report.json does not give the paper's 9472 iterations"
    ;;
  mesh_tetrahedralize)
    # A closed surface into conforming tets (Gmsh), a scene body made the same way, and the refusals.
    run 0 mesh tetrahedralize "$src/assets/meshes/Bunny.stl" bunny.msh
    expect_output 'tets: [0-9]+' "the tet count"
    expect_output 'dihedral angle: min [0-9.]+' "the smallest dihedral angle"
    expect_output 'radius ratio.*min [0-9.]+' "the radius ratio"
    expect_file bunny.msh
    run 0 mesh-info bunny.msh
    expect_output 'format: gmsh-4.1' "the written file read back"
    expect_output 'dihedral angle: min' "the quality of a tet mesh"
    run 2 mesh tetrahedralize "$src/assets/meshes/stylus.obj" stylus.msh
    expect_output 'stylus\.obj.*4 open edges' "the open surface refused, with its hole count"
    [ -e stylus.msh ] && fail "an open surface wrote a mesh"
    run 2 mesh tetrahedralize "$src/assets/meshes/liver.obj" liver.msh --min-dihedral 40
    expect_output 'short of the 40' "the quality asked for and not reached"
    cp "$src/assets/meshes/liver.obj" .
    cat >tets.yaml <<'YAML'
name: tets
clock: {duration_s: 0.05}
bodies:
  - name: liver
    mesh: {file: liver.obj, scale: 0.01, tetrahedralize: {max_volume: 1.0e-7}}
    material: {youngs_modulus: 3.0e3, poisson_ratio: 0.4, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, 0.04, -1], max: [1, 1, 1]}}]
YAML
    run 0 run tets.yaml --out out
    expect_output 'tetrahedralized' "what the body became"
    ;;
  *)
    fail "unknown case"
    ;;
esac

[ "$failures" -eq 0 ] && echo "ok [$case_name]"
exit $((failures > 0))
