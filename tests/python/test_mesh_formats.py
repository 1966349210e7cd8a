# Surface formats of issue 24 through the Python module: a body from a VTK PolyData file (.vtp,
# appended zlib) with a legacy .vtk fine surface and one from an OFF file load and step; a broken
# OFF is a SceneError that names the file and line.
import pytest

import tacta

MESHES = "tests/data/meshes"


def scene(mesh):
    return {
        "name": "python_formats",
        "clock": {"duration_s": 0.05},
        "bodies": [{
            "name": "pyramid",
            "mesh": mesh,
            "material": {"youngs_modulus": 5.0e3, "poisson_ratio": 0.3, "density": 1000},
            "model": "corotational_fem",
            "fixed": [{"box": {"min": [-1, -1, -1], "max": [2, 2, 0.1]}}],
        }],
    }


def test_vtp_body_with_a_legacy_vtk_surface_steps(root):
    sim = tacta.Simulation.from_dict(scene({"file": "pyramid_appended_base64.vtp",
                                            "surface": "pyramid_ascii.vtk"}),
                                     base_dir=str(root / MESHES))
    body = sim.bodies["pyramid"]
    assert body.node_count > 5  # voxelised
    assert body.surface.shape == (6, 3)  # the embedded surface: the quad base fanned, 4 sides
    assert sim.step(20) == 20


def test_off_body_steps(root):
    sim = tacta.Simulation.from_dict(scene({"file": "pyramid_cnoff.off"}), base_dir=str(root / MESHES))
    assert sim.step(20) == 20
    assert sim.bodies["pyramid"].surface.shape == (6, 3)


def test_broken_off_names_file_and_line(root):
    with pytest.raises(tacta.SceneError, match=r"broken_off_index\.off:15: vertex index '5'"):
        tacta.Simulation.from_dict(scene({"file": "broken_off_index.off"}), base_dir=str(root / MESHES))
