# Checkpoint and restore from Python: sim.checkpoint() gives bytes (and writes a file when asked),
# sim.restore() takes bytes or a path; a restored run continues bit for bit, and a checkpoint of
# another scene is refused with ValueError saying so.
import pytest

import tacta

FAST = {"output.frames": "false", "output.vtk": "false", "output.plots": "[]"}


def demo(root, **overrides):
    return tacta.Simulation(str(root / "scenes/liver_palpation.yaml"), overrides={**FAST, **overrides})


def test_restored_run_continues_bit_for_bit(root, tmp_path):
    straight = demo(root)
    straight.advance_to(0.7)

    first = demo(root)
    first.advance_to(0.5)  # the stylus presses the liver from about 0.4 s
    path = tmp_path / "demo.ckpt"
    data = first.checkpoint(str(path))
    assert isinstance(data, bytes) and data[:8] == b"TACTACKP"
    assert path.read_bytes() == data
    del first

    from_bytes = demo(root)
    assert from_bytes.restore(data) == []  # sim_stylus carries its own state: nothing left out
    assert from_bytes.tick == 500
    from_bytes.advance_to(0.7)
    from_file = demo(root)
    from_file.restore(path)
    from_file.advance_to(0.7)
    expected = straight.report()["state_hash"]
    assert from_bytes.report()["state_hash"] == expected
    assert from_file.report()["state_hash"] == expected


def test_checkpoint_of_another_scene_is_refused(root):
    first = demo(root)
    first.step(5)
    data = first.checkpoint()
    other = demo(root, **{"bodies.*.model": "mass_spring"})
    with pytest.raises(ValueError, match="another scene"):
        other.restore(data)
    with pytest.raises(ValueError, match="truncated"):
        demo(root).restore(data[:200])
