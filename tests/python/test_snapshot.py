# Simulation.snapshot: a PNG of the current state drawn headless (EGL) by the code `tacta snapshot`
# uses; the requested size, a real picture, and tacta.RenderError when EGL cannot start.
import os
import subprocess
import sys

import numpy as np
import pytest
import tacta

from conftest import ROOT, read_png_rgb


def pixels(path):
    width, height, rows = read_png_rgb(path)
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 3)


def test_snapshot_of_the_current_state(tmp_path):
    sim = tacta.Simulation(str(ROOT / "scenes/liver_palpation.yaml"))
    sim.step(200)
    out = tmp_path / "pictures" / "liver.png"
    assert sim.snapshot(str(out), width=160, height=120) == (160, 120)
    image = pixels(out)
    assert image.shape == (120, 160, 3)
    luminance = image @ np.array([0.2126, 0.7152, 0.0722])
    assert luminance.std() > 5.0  # not a blank picture
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 50  # a shaded body has many colours
    assert sim.tick == 200  # drawing does not step


def test_same_picture_as_the_command_line(tacta_bin, tmp_path):
    scene = ROOT / "scenes/liver_palpation.yaml"
    cli_png, py_png = tmp_path / "cli.png", tmp_path / "py.png"
    subprocess.run([str(tacta_bin), "snapshot", str(scene), "--at", "0.25", "--out", str(cli_png),
                    "--width", "200", "--height", "150", "--quiet"], check=True)
    sim = tacta.Simulation(str(scene))
    sim.advance_to(0.25)
    sim.snapshot(str(py_png), width=200, height=150)
    differ = np.any(pixels(cli_png) != pixels(py_png), axis=2)
    # Same state, same drawing code; only the overlay's measured tick time may differ.
    assert differ.mean() < 0.01, f"{differ.mean():.2%} of the pixels differ"


def test_bad_size_is_a_value_error(tmp_path):
    sim = tacta.Simulation(str(ROOT / "scenes/liver_palpation.yaml"))
    with pytest.raises(ValueError, match="outside 1"):
        sim.snapshot(str(tmp_path / "x.png"), width=0)
    assert not (tmp_path / "x.png").exists()


def test_no_egl_raises_render_error(tmp_path):
    # GLVND with no vendor library: EGL has no display to open, as on a machine without Mesa.
    code = (
        "import sys, tacta\n"
        "sim = tacta.Simulation(sys.argv[1])\n"
        "try:\n"
        "    sim.snapshot(sys.argv[2], width=32, height=32)\n"
        "except tacta.RenderError as e:\n"
        "    print('RenderError:', e)\n"
    )
    env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES=str(tmp_path / "no_vendor.json"),
               __EGL_VENDOR_LIBRARY_DIRS=str(tmp_path))
    out = tmp_path / "never.png"
    done = subprocess.run([sys.executable, "-c", code, str(ROOT / "scenes/liver_palpation.yaml"), str(out)],
                          env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "RenderError: headless render: opening an EGL display" in done.stdout, done.stdout
    assert "libegl-mesa0" in done.stdout
    assert not out.exists()
    assert issubclass(tacta.RenderError, RuntimeError)
