# Stepping from Python is the engine's lockstep run: the same state hash as `tacta run --lockstep`
# on the same scene, however the ticks are split into step() calls.
import json
import subprocess

import tacta


def cli_hash(tacta_bin, scene, duration, out, extra=()):
    subprocess.run([str(tacta_bin), "run", str(scene), "--lockstep", "--duration", str(duration), "--quiet",
                    "--out", str(out), *extra], check=True)
    return json.loads((out / "report.json").read_text())["state_hash"]


def test_liver_demo_matches_the_command_line(root, tacta_bin, tmp_path):
    scene = root / "scenes/liver_palpation.yaml"
    expected = cli_hash(tacta_bin, scene, 0.3, tmp_path,
                        extra=("--set", "output.frames=false", "--set", "output.vtk=false", "--set", "output.plots=[]"))
    sim = tacta.Simulation(str(scene))
    assert sim.advance_to(0.3) == 300
    assert sim.report()["state_hash"] == expected


def test_split_steps_and_overrides_match(root, tacta_bin, tmp_path):
    scene = root / "scenes/examples/beam_under_gravity.yaml"
    expected = cli_hash(tacta_bin, scene, 0.25, tmp_path, extra=("--set", "bodies.*.model=tensor_mass",
                                                                 "--set", "output.plots=[]"))
    sim = tacta.Simulation(str(scene), overrides={"bodies.*.model": "tensor_mass"})
    for n in (1, 7, 42, 200):
        sim.step(n)
    assert sim.tick == 250
    assert sim.report()["state_hash"] == expected
