# Cutting from Python (Simulation.cut, Simulation.body_revision): a plane through the cantilever
# separates it (nodes copied, mass kept, the far piece falls freely) or removes the cell it passes
# through (exactly that cell's mass goes); a blade that misses changes nothing in any of the three
# accepted shapes; bad shapes and modes raise ValueError, a model that takes no cuts SceneError; a
# checkpoint of a cut beam resumes bit for bit; a realtime run makes its cut events.
import numpy as np
import pytest
import tacta

from conftest import beam_scene

RHO = 1100.0  # kg/m^3, beam_scene's density
CELL = 0.05  # m: beam_scene's 8 x 1 x 1 cells over 0.4 x 0.05 x 0.05


def beam(model="corotational_fem"):
    scene = beam_scene(model=model)
    scene["bodies"][0]["material"]["rayleigh_mass"] = 0.0  # no drag on a falling piece
    return tacta.Simulation.from_dict(scene)


def plane_at_x(x):
    """Two triangles (2, 3, 3) filling the plane x = const well past the beam's section."""
    p0, p1, p2, p3 = [x, -1, -1], [x, 1, -1], [x, 1, 1], [x, -1, 1]
    return np.array([[p0, p1, p2], [p0, p2, p3]], dtype=float)


def total_mass(sim):
    return float(np.sum(sim.body("beam").masses))


def test_a_separating_plane_copies_the_section_nodes_and_keeps_the_mass():
    sim = beam()
    before = total_mass(sim)
    tets_before = sim.cut("beam", plane_at_x(5.0))["tets"]  # a blade that misses: the counts
    assert sim.body_revision("beam") == 0
    # Just past the nodes at x = 0.2: every tet on one side has its centroid at x <= 0.1875, on
    # the other at x >= 0.2125, so exactly the square face x = 0.2 (two triangles) opens.
    summary = sim.cut("beam", plane_at_x(0.201))
    assert summary["changed"] and summary["revision"] == 1
    assert summary["faces_separated"] == 2
    assert summary["nodes_added"] == 4  # the section's 2 x 2 nodes, each copied once
    assert summary["tets_removed"] == 0 and summary["nodes_removed"] == 0
    assert summary["nodes"] == 36 + 4 and summary["tets"] == tets_before
    assert sim.body_revision("beam") == 1
    body = sim.body("beam")  # views are taken again after a cut
    assert body.positions.shape == (40, 3)
    assert total_mass(sim) == pytest.approx(before, rel=1e-12)


def test_the_separated_piece_falls_freely():
    sim = beam()
    sim.cut("beam", plane_at_x(0.201), mode="separate")
    body = sim.body("beam")
    rest = body.rest_positions.copy()
    free = rest[:, 0] > 0.2 + 0.5 * CELL  # nodes of the far piece, off the opened section
    attached = rest[:, 0] < 0.2 - 0.5 * CELL
    start = body.positions.copy()
    ticks = 200
    sim.step(ticks)
    now = sim.body("beam").positions
    drop = start[free, 1] - now[free, 1]
    # Implicit Euler under constant g from rest: g dt^2 n (n + 1) / 2 = g t^2 / 2 (1 + 1/n).
    t = ticks * 1e-3
    expected = 0.5 * 9.81 * t * t * (1 + 1 / ticks)
    assert drop == pytest.approx(np.full(drop.shape, expected), rel=0.01)
    # The clamped stub only sags and rings (about 6 mm at its end): it stays held.
    assert np.max(np.abs(start[attached, 1] - now[attached, 1])) < 0.1 * expected


def test_a_removal_takes_out_the_cell_the_blade_passes_through():
    sim = beam()
    before = total_mass(sim)
    tets_before = sim.cut("beam", plane_at_x(5.0))["tets"]
    # x = 0.301 passes through the inside of every tet of the cell [0.30, 0.35] and of no other.
    summary = sim.cut(sim.body("beam"), plane_at_x(0.301), mode="remove")
    assert summary["changed"] and summary["revision"] == 1
    assert summary["tets_removed"] == tets_before // 8  # one cell's tets
    assert summary["tets"] == tets_before - summary["tets_removed"]
    assert summary["nodes_added"] == 0 and summary["faces_separated"] == 0
    assert total_mass(sim) == pytest.approx(before - RHO * CELL**3, rel=1e-12)


def test_a_blade_that_misses_changes_nothing_in_every_shape():
    sim = beam()
    sim.step(5)
    positions = sim.body("beam").positions.copy()
    far = plane_at_x(5.0)
    for triangles in (far, far.reshape(6, 3), far.reshape(-1), far.tolist()):
        summary = sim.cut("beam", triangles)
        assert not summary["changed"] and summary["revision"] == 0
        assert summary["nodes"] == 36 and summary["nodes_added"] == 0
    assert sim.body_revision(sim.body("beam").handle) == 0
    assert np.array_equal(sim.body("beam").positions, positions)


def test_bad_blades_and_modes_raise():
    sim = beam()
    with pytest.raises(ValueError, match="mode must be 'remove' or 'separate'"):
        sim.cut("beam", plane_at_x(0.201), mode="carve")
    with pytest.raises(ValueError, match=r"got shape \(2, 2\)"):
        sim.cut("beam", np.zeros((2, 2)))
    with pytest.raises(ValueError, match="9n flat"):
        sim.cut("beam", np.zeros(10))
    bad = plane_at_x(0.201)
    bad[0, 0, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        sim.cut("beam", bad)
    with pytest.raises(tacta.SceneError, match="did you mean 'beam'"):
        sim.cut("beem", plane_at_x(0.201))
    assert sim.body_revision("beam") == 0


def test_a_model_that_takes_no_cuts_refuses_them():
    sim = beam(model="fd_debunne")
    with pytest.raises(tacta.SceneError, match="does not take topology edits"):
        sim.cut("beam", plane_at_x(0.201))
    assert sim.body_revision("beam") == 0


def test_views_taken_before_a_cut_stay_readable_and_hold_the_state_at_the_cut():
    sim = beam()
    sim.step(20)
    old = sim.body("beam").positions
    held = old.copy()
    sim.cut("beam", plane_at_x(0.201))
    # The engine keeps the pre-cut arrays: the old view reads the state at the cut, not freed memory.
    np.testing.assert_array_equal(old, held)
    sim.step(20)
    np.testing.assert_array_equal(old, held)  # it no longer follows the body
    assert sim.body("beam").positions.shape[0] == held.shape[0] + 4  # the section's 4 nodes copied


def test_a_checkpoint_of_a_cut_beam_resumes_bit_for_bit():
    straight = beam()
    straight.advance_to(0.02)
    straight.cut("beam", plane_at_x(0.201))
    straight.advance_to(0.08)

    first = beam()
    first.advance_to(0.02)
    first.cut("beam", plane_at_x(0.201))
    first.advance_to(0.05)
    data = first.checkpoint()
    del first

    resumed = beam()
    resumed.restore(data)
    assert resumed.body_revision("beam") == 1
    resumed.advance_to(0.08)
    assert resumed.report()["state_hash"] == straight.report()["state_hash"]
    assert np.array_equal(resumed.body("beam").positions, straight.body("beam").positions)


def test_a_realtime_run_makes_the_scenes_cut_events():
    """A cut event in a realtime run is made on the cut worker and installed at a tick boundary."""
    scene = beam_scene()
    x = 0.201
    scene["events"] = [{"time": 0.02, "cut": {"body": "beam", "mode": "separate",
                                               "quad": [[x, -1, -1], [x, 1, -1], [x, 1, 1], [x, -1, 1]]}}]
    sim = tacta.Simulation.from_dict(scene)
    mass = total_mass(sim)
    sim.run(duration=0.06, realtime=True)
    assert sim.body_revision("beam") == 1
    assert sim.body("beam").positions.shape[0] > 9 * 2 * 2  # the section's nodes were copied
    assert total_mass(sim) == pytest.approx(mass, rel=1e-12)
