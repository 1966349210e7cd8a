# Bad input raises tacta.SceneError (a ValueError) naming file, line, column and key.
import pytest
import tacta

from conftest import beam_scene


def test_bad_scene_file_names_file_line_and_key(tmp_path):
    scene = tmp_path / "bad.yaml"
    scene.write_text(
        "name: bad\n"
        "bodies:\n"
        "  - name: b\n"
        "    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [1, 1, 1]}}\n"
        "    material: {youngs_modulus: -5, poisson_ratio: 0.3}\n"
        "    model: tensor_mass\n")
    with pytest.raises(tacta.SceneError) as caught:
        tacta.Simulation(str(scene))
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.file.endswith("bad.yaml")
    assert error.line == 5 and error.column > 0
    assert "youngs_modulus" in error.key
    assert "bad.yaml:5" in str(error)


def test_bad_override_names_the_key(root):
    with pytest.raises(tacta.SceneError) as caught:
        tacta.Simulation(str(root / "scenes/liver_palpation.yaml"), overrides={"bodies.*.model": "tensor_mas"})
    assert caught.value.key == "bodies[0].model"
    assert "did you mean 'tensor_mass'" in str(caught.value)


def test_missing_file_and_bad_dict():
    with pytest.raises(tacta.SceneError):
        tacta.Simulation("/nonexistent/scene.yaml")
    scene = beam_scene()
    scene["bodies"][0]["material"]["poisson_ratio"] = 0.7
    with pytest.raises(tacta.SceneError) as caught:
        tacta.Simulation.from_dict(scene)
    assert "poisson_ratio" in caught.value.key and caught.value.line > 0
