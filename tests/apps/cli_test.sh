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

# Explicit Euler on a stiff square at 25 Hz: the amplitude grows every step until the body
# passes ten body sizes of displacement and is frozen.
write_diverging_scene() {
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
}

case "$case_name" in
  help)
    run 0 --help
    expect_output 'run' "the run subcommand"
    run 0 run --help
    expect_output '--out' "the --out option"
    run 0 plugins
    expect_output 'tensor_mass' "the tensor_mass plugin"
    expect_output '^  claims: momentum, topology_edits \(takes cuts\)$' "tensor_mass's claims"
    expect_output '^  claims: no_history \(takes no cuts\)$' "fd_debunne's claims (no cuts)"
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
    # Inputs that crashed (PLY face index out of range), hung (a PLY header line 'x end_header')
    # or loaded silently (an OBJ vertex 'v 0 0 abc') before issue 15.
    run 2 mesh-info "$src/tests/data/meshes/fuzz/ply_binary_index_postprocess.ply"
    expect_output 'ply_binary_index_postprocess\.ply: .*vertex index 33554432 is out of range' "the bad index"
    run 2 mesh-info "$src/tests/data/meshes/broken_ply_header.ply"
    expect_output 'broken_ply_header\.ply:9:' "the file and line"
    run 2 mesh-info "$src/tests/data/meshes/broken_obj_number.obj"
    expect_output "broken_obj_number\\.obj:4: .*found 'abc'" "the file, line and token"
    ;;
  broken_device_log)
    # A replayed sample at px = 1e30 once ran and reported 1.3e29 J of injected energy.
    printf '%s\n' "time_s,px,py,pz,qw,qx,qy,qz,vx,vy,vz,buttons,fx,fy,fz" \
      "0,0,0.1,0,1,0,0,0,0,0,0,0,0,0,0" "0.001,1e30,0.1,0,1,0,0,0,0,0,0,0,0,0,0" >far.csv
    run 2 run "$src/scenes/examples/stylus_poke.yaml" --duration 0.01 --replay far.csv --out out
    expect_output 'far\.csv:3: column 2 \(px\) = 1e\+30' "the log's line and column"
    [ -e out/report.json ] && fail "a run with a refused device log wrote a report"
    ;;
  absent_scene)
    run 2 run no_such_scene.yaml --out out
    expect_output 'no_such_scene\.yaml' "the absent file's name"
    ;;
  diverging_scene)
    write_diverging_scene
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
  duration_limits)
    # --duration 0 printed the whole double range (309 digits) as its bound.
    run 2 run "$src/scenes/examples/soft_drop.yaml" --duration 0
    expect_output 'expected a duration in s > 0' "what a duration is"
    grep -q '[0-9]\{40\}' "$work/out.txt" && fail "a bound printed with 40 digits or more"
    # 1e7 s reached std::bad_alloc (exit 1) when the recorders reserved for it.
    run 2 run "$src/scenes/examples/soft_drop.yaml" --duration 1e7
    expect_output 'clock\.duration_s: .*at most 3600000 ticks' "the key and the bound"
    sed 's/duration_s: 1.0/duration_s: 1e9/' "$src/scenes/examples/soft_drop.yaml" >long.yaml
    run 2 run long.yaml
    expect_output 'long\.yaml:[0-9]+:[0-9]+: clock\.duration_s: .*reserved before it starts' "file:line, key and why"
    # --duration replaces the file's duration before anything is sized from it.
    run 0 run long.yaml --duration 0.02 --out out
    grep -q '"ticks": 20,' out/report.json || fail "the run did not last the 20 ticks of --duration 0.02"
    ;;
  load_limits)
    cp "$src/scenes/examples/soft_drop.yaml" drop.yaml
    # A margin of 1000 m cost ~0.6 s of CPU a tick in edge-edge CCD.
    sed 's/thickness: 1.0e-4/thickness: 1000/' drop.yaml >thick.yaml
    run 2 run thick.yaml
    expect_output 'thick\.yaml:[0-9]+:[0-9]+: collision\.thickness: .*too thick for body .block.: at most 0\.5 of its mean surface edge' "the bound"
    # Every node fixed is legal (a held body is still touched, as a rigid surface) but said.
    run 0 run drop.yaml --duration 0.01 --set 'bodies.0.fixed=[{box: {min: [-1, -1, -1], max: [1, 1, 1]}}]'
    expect_output '^warning: --set bodies.0.fixed=.*: bodies\[0\]\.fixed: the fixed regions hold all 75 nodes .*never moves.*fix fewer nodes' "what to do"
    mkdir -p a_folder
    cat >folder_mesh.yaml <<'YAML'
name: folder_mesh
bodies:
  - name: b
    mesh: {file: a_folder}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: tensor_mass
YAML
    run 2 run folder_mesh.yaml
    expect_output 'folder_mesh\.yaml:4:18: bodies\[0\]\.mesh\.file: .*a_folder is a directory' "a folder, at the scene's line"
    sed 's/file: a_folder/file: gone.obj/' folder_mesh.yaml >missing_mesh.yaml
    run 2 run missing_mesh.yaml
    expect_output 'missing_mesh\.yaml:4:18: bodies\[0\]\.mesh\.file: no such file: .*gone\.obj' "the scene's line"
    # A missing embedded surface (`mesh.surface`) is named at its own key too.
    cp "$src/assets/meshes/liver.msh" .
    sed 's/file: a_folder}/file: liver.msh, surface: gone_surface.obj}/' folder_mesh.yaml >missing_surface.yaml
    run 2 run missing_surface.yaml
    expect_output 'missing_surface\.yaml:4:[0-9]+: bodies\[0\]\.mesh\.surface: no such file: .*gone_surface\.obj' "the surface key's line"
    ;;
  quiet_fault)
    # The diverging square of diverging_scene, with -q: the fault is still an error on stderr.
    write_diverging_scene
    "$tacta" run diverges.yaml -q >stdout.txt 2>"$work/out.txt"
    [ $? -eq 1 ] || fail "a fault under -q did not exit 1"
    [ -s stdout.txt ] && fail "-q printed to stdout"
    expect_output '^error: runtime fault: body square at t = [0-9.]+ s: .*frozen' "the fault on stderr"
    ;;
  realtime_report)
    # What the kernel granted the haptic thread, and the resident memory around the loop.
    run 0 run "$src/scenes/examples/soft_drop.yaml" --realtime --duration 0.2 --haptic-cpu 0 --out out
    for key in '"realtime": \{' '"scheduler": "SCHED_' '"memory_locked": ' '"haptic_cpu": ' '"rss_start": [1-9]' '"rss_end": [1-9]' \
               '"rss_every_10s": \[' '"spun_waits": [0-9]' '"late_wakeups": [0-9]' '"over_budget_ticks": [0-9]' \
               '"warm_up_over_budget_ticks": [0-9]' '"max_tick_cpu_ms": '; do
      grep -Eq "$key" out/report.json || fail "report.json has no /$key/"
    done
    run 2 run "$src/scenes/examples/soft_drop.yaml" --realtime --duration 0.2 --set clock.haptic_cpu=99999
    expect_output 'clock\.haptic_cpu: expected an integer in \[-1, ' "the CPU range"
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
  mesh_formats)
    # OFF and VTK PolyData surfaces (issue 24) in mesh-info and as scene bodies; refusals name
    # file and line. Binary legacy VTK tets load as a volume.
    meshes="$src/tests/data/meshes"
    for f in pyramid.off pyramid_binary.vtk pyramid_appended_base64.vtp vtk9/sphere_strips_default.vtp; do
      run 0 mesh-info "$meshes/$f"
      expect_output 'closed: yes' "a closed surface ($f)"
    done
    run 0 mesh-info "$meshes/vtk9/cube_tets_binary.vtk"
    expect_output 'tets: 6' "a binary legacy tet mesh"
    run 0 mesh-info "$meshes/uv_indices_without_vt.obj"
    expect_output 'warning: ignored, as a simulation does not use them: texture coordinates' "the one warning"
    run 2 mesh-info "$meshes/broken_off_index.off"
    expect_output "broken_off_index\.off:15: vertex index '5' is out of range" "the file, line and index"
    run 2 mesh-info "$meshes/broken_polydata_binary.vtk"
    expect_output 'broken_polydata_binary\.vtk:9: .*truncated' "the file and line of the cut data"
    run 2 mesh-info "$meshes/broken_zlib_size.vtp"
    expect_output 'broken_zlib_size\.vtp:11: .*cannot inflate' "the forged zlib header refused"
    cp "$meshes/pyramid_appended_base64.vtp" "$meshes/pyramid_ascii.vtk" "$meshes/pyramid_coff.off" .
    cat >formats.yaml <<'YAML'
name: formats
clock: {duration_s: 0.05}
bodies:
  - name: from_vtp
    mesh: {file: pyramid_appended_base64.vtp, surface: pyramid_ascii.vtk, scale: 0.05}
    material: {youngs_modulus: 3.0e3, poisson_ratio: 0.3, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, -1, -1], max: [1, 1, 0.01]}}]
  - name: from_off
    mesh: {file: pyramid_coff.off, scale: 0.05, translate: [0.2, 0, 0]}
    material: {youngs_modulus: 3.0e3, poisson_ratio: 0.3, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, -1, -1], max: [1, 1, 0.01]}}]
YAML
    run 0 run formats.yaml --out out
    expect_file out/report.json
    sed 's/pyramid_coff\.off/broken_off_index.off/' formats.yaml >broken_formats.yaml
    cp "$meshes/broken_off_index.off" .
    run 2 run broken_formats.yaml --out out2
    expect_output "broken_off_index\.off:15: " "the mesh file and line from a scene"
    ;;
  checkpoint_resume)
    # The demo to 1.2 s straight, then with a checkpoint at 0.55 s (the stylus in contact) and a
    # run resumed from it: the same final state hash; a checkpoint of another scene is refused.
    demo="$src/scenes/liver_palpation.yaml"
    hash_of() { grep -Eo '"state_hash": *"[0-9a-f]+"' "$1/report.json" | grep -Eo '[0-9a-f]{16}'; }
    run 0 run "$demo" --lockstep --duration 1.2 --set output.plots=[] --set output.frames=false --out straight
    run 0 run "$demo" --lockstep --duration 1.2 --set output.plots=[] --set output.frames=false \
      --checkpoint-at 0.55 --checkpoint demo.ckpt --out first
    expect_output "checkpoint at t = 0.55 s written to demo.ckpt" "where the checkpoint went"
    expect_file demo.ckpt
    run 0 run "$demo" --lockstep --duration 1.2 --set output.plots=[] --set output.frames=false \
      --resume demo.ckpt --out resumed
    [ -n "$(hash_of straight)" ] || fail "no state hash in the straight run's report.json"
    [ "$(hash_of resumed)" = "$(hash_of straight)" ] ||
      fail "resumed state hash $(hash_of resumed), straight $(hash_of straight)"
    [ "$(hash_of first)" = "$(hash_of straight)" ] ||
      fail "the run that wrote the checkpoint ends at $(hash_of first), straight $(hash_of straight)"
    # The scene key does what --resume does (a path in --set is relative to the working folder).
    run 0 run "$demo" --lockstep --duration 1.2 --set output.plots=[] --set output.frames=false \
      --set clock.resume=demo.ckpt --out keyed
    [ "$(hash_of keyed)" = "$(hash_of straight)" ] ||
      fail "clock.resume state hash $(hash_of keyed), straight $(hash_of straight)"
    run 2 run "$demo" --lockstep --set clock.resume=absent.ckpt
    expect_output "clock.resume.*no checkpoint file at" "an absent checkpoint named at its key"
    run 2 run "$demo" --lockstep --duration 1.2 --set bodies.*.model=mass_spring --resume demo.ckpt
    expect_output "another scene" "a checkpoint of another scene refused"
    head -c 1000 demo.ckpt >cut.ckpt
    run 2 run "$demo" --lockstep --duration 1.2 --resume cut.ckpt
    expect_output "cut\.ckpt.*truncated" "a truncated checkpoint refused, named"
    ;;
  *)
    fail "unknown case"
    ;;
esac

[ "$failures" -eq 0 ] && echo "ok [$case_name]"
exit $((failures > 0))
