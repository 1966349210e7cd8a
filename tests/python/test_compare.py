# tacta.compare: the table of `tacta compare` (the same engine code) as a list of dicts, with the
# same numbers as the command line's compare.json on the same scene; bad input is a SceneError.
import json
import subprocess

import pytest
import tacta

from conftest import ROOT

SCENE = ROOT / "scenes/examples/beam_under_gravity.yaml"
MEASURED = {"tick_p50_ms", "tick_p99_ms"}  # wall-clock tick durations: differ from run to run


def test_same_table_as_the_command_line(tacta_bin, tmp_path):
    models = ["corotational_fem", "tensor_mass:integrator=implicit_euler"]
    subprocess.run([str(tacta_bin), "compare", str(SCENE), "--models", ",".join(models), "--duration", "0.2",
                    "--set", "output.plots=[]", "--reference", "corotational_fem", "--out", str(tmp_path / "cli"),
                    "--quiet"], check=True)
    expected = json.loads((tmp_path / "cli" / "compare.json").read_text())["models"]
    rows = tacta.compare(str(SCENE), models=models, overrides={"output.plots": []}, duration=0.2,
                         reference="corotational_fem")
    assert [r["model"] for r in rows] == models
    assert set(rows[0]) == set(expected[0])
    for row, cli in zip(rows, expected):
        for key in set(cli) - MEASURED:
            assert row[key] == cli[key], (row["model"], key)
        assert row["tick_p50_ms"] > 0 and row["tick_p99_ms"] >= row["tick_p50_ms"]
    assert rows[0]["displacement_ratio"] == 1.0 and rows[1]["difference_from_reference_m"] > 0
    assert rows[0]["faults"] == 0 and rows[0]["max_displacement_m"] > 1e-3


def test_out_dir_writes_what_the_command_line_writes(tmp_path):
    rows = tacta.compare(str(SCENE), models=["tensor_mass"], duration=0.05, out_dir=str(tmp_path),
                         overrides={"output.plots": []})
    assert (tmp_path / "compare.json").exists() and (tmp_path / "compare.csv").exists()
    assert (tmp_path / "tensor_mass" / "report.json").exists()
    assert json.loads((tmp_path / "compare.json").read_text())["models"][0]["state_hash"] == rows[0]["state_hash"]


def test_bad_input_raises_before_any_run(tmp_path):
    with pytest.raises(tacta.SceneError, match="did you mean 'tensor_mass'") as caught:
        tacta.compare(str(SCENE), models=["corotational_fem", "tensor_mas"], out_dir=str(tmp_path / "x"))
    assert caught.value.file == "--models" and caught.value.key == "tensor_mas"
    assert not (tmp_path / "x" / "corotational_fem").exists()  # nothing ran
    with pytest.raises(tacta.SceneError, match="named twice"):
        tacta.compare(str(SCENE), models=["tensor_mass", "tensor_mass"])
    with pytest.raises(tacta.SceneError, match="--reference"):
        tacta.compare(str(SCENE), models=["tensor_mass"], reference="mass_spring")
    with pytest.raises(ValueError, match="duration"):
        tacta.compare(str(SCENE), models=["tensor_mass"], duration=-1)
