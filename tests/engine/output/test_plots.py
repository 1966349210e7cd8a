"""The plot scripts on tiny CSVs: each writes a PNG; bad input exits 2 with a clear message.

Run by ctest as: /usr/bin/python3 test_plots.py SCRIPTS_DIR OUTPUT_DIR"""

import math
import os
import struct
import subprocess
import sys
import unittest

SCRIPTS = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "../../../scripts/plots")
OUTPUT = sys.argv[2] if len(sys.argv) > 2 else "/tmp/tacta-plot-tests"
PYTHON = "/usr/bin/python3"  # Debian's, with matplotlib


def write(name, text):
    path = os.path.join(OUTPUT, name)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)
    return path


def run(script, *args):
    return subprocess.run([PYTHON, os.path.join(SCRIPTS, script), *args],
                          capture_output=True, text=True, timeout=60, check=False)


def png_size(path):
    with open(path, "rb") as handle:
        header = handle.read(24)
    assert header[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", header[16:24])


class PlotScripts(unittest.TestCase):
    def assert_png(self, result, path):
        self.assertEqual(result.returncode, 0, result.stderr)
        width, height = png_size(path)
        self.assertGreater(width, 300)
        self.assertGreater(height, 200)

    def test_force_vs_time(self):
        rows = ["time_s,force_x_N,force_y_N,force_z_N,force_N,contact"]
        for i in range(50):
            t = i * 0.001
            fx, fy, fz = 0.1 * t, 2.0 * math.sin(60 * t), 0.0
            rows.append(f"{t},{fx},{fy},{fz},{math.sqrt(fx * fx + fy * fy)},1")
        trace = write("trace.csv", "\n".join(rows) + "\n")
        out = os.path.join(OUTPUT, "force.png")
        self.assert_png(run("force_vs_time.py", trace, out, "--peak-force", "3.3"), out)

    def test_phase_portrait(self):
        rows = ["time_s,node,x,y,z,vx,vy,vz"]
        for i in range(40):
            t = i * 0.01
            for node in (0, 5):
                rows.append(f"{t},{node},{math.cos(10 * t)},{math.sin(10 * t)},0,"
                            f"{-10 * math.sin(10 * t)},{10 * math.cos(10 * t)},0")
        trajectory = write("trajectory.csv", "\n".join(rows) + "\n")
        out = os.path.join(OUTPUT, "phase.png")
        self.assert_png(run("phase_portrait.py", trajectory, out, "--nodes", "0,5",
                            "--labels", "corner,centre"), out)

    def test_compare_bars(self):
        table = write("compare.csv", "model,tick_p50_ms,tick_p99_ms,max_displacement_m,energy_drift,extra\n"
                      "mass_spring,0.05,0.09,0.012,0.001,x\n"
                      "tensor_mass,0.08,0.15,0.011,,y\n")
        out = os.path.join(OUTPUT, "compare.png")
        self.assert_png(run("compare_bars.py", table, out), out)

    def test_missing_column_names_file_and_column(self):
        trace = write("bad_trace.csv", "time_s,force_N\n0,1\n")
        result = run("force_vs_time.py", trace, os.path.join(OUTPUT, "never.png"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("bad_trace.csv:1", result.stderr)
        self.assertIn("force_x_N", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(OUTPUT, "never.png")))

    def test_non_number_names_its_line(self):
        table = write("bad_compare.csv", "model,tick_p50_ms,tick_p99_ms,max_displacement_m,energy_drift\n"
                      "a,1,2,3,4\nb,1,fast,3,4\n")
        result = run("compare_bars.py", table, os.path.join(OUTPUT, "never2.png"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("bad_compare.csv:3", result.stderr)
        self.assertIn("'fast'", result.stderr)

    def test_missing_file_and_unknown_node(self):
        result = run("phase_portrait.py", os.path.join(OUTPUT, "absent.csv"), "x.png", "--nodes", "1")
        self.assertEqual(result.returncode, 2)
        self.assertIn("absent.csv", result.stderr)
        trajectory = write("one_node.csv", "time_s,node,x,y,z,vx,vy,vz\n0,1,0,0,0,0,0,0\n")
        result = run("phase_portrait.py", trajectory, os.path.join(OUTPUT, "n.png"), "--nodes", "9")
        self.assertEqual(result.returncode, 2)
        self.assertIn("no rows for node 9", result.stderr)


if __name__ == "__main__":
    os.makedirs(OUTPUT, exist_ok=True)
    unittest.main(argv=[sys.argv[0], "-v"])
