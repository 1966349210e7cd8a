#!/usr/bin/env python3
"""The mesh corpus smoke test: every mesh file under assets/ and tests/data/ (found by walking the
folders, so a new format's files join by themselves) either runs as a scene body for 0.1 s of
simulation (`tacta run`, the default tet budget, corotational_fem, the top quarter held), in one
piece per surface shell with held nodes, or is refused with exit 2 and a message naming the file
and, for a text format, the line. Files meant to be bad are named broken_* or lie in a fuzz/
folder (fuzzer findings kept as regressions); REFUSED lists the others that must be refused.
Usage: mesh_corpus_test.py TACTA SRC WORK"""
import concurrent.futures
import json
import os
import pathlib
import re
import subprocess
import sys
import time

tacta, src, work = sys.argv[1], pathlib.Path(sys.argv[2]).resolve(), pathlib.Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
NOT_MESHES = {".md", ".py", ".csv", ".txt", ".json", ".supp"}  # documentation, scripts, tables
FOLDERS = ["assets", "tests/data"]
# Bad files that cannot name a line: what the message must say instead (a whole-file property,
# or a binary or JSON format with no lines).
NO_LINE = {
    "broken_empty.msh": "unsupported surface format",       # empty: no format to read
    "broken_flat_tet.msh": "zero volume",                    # a tet's shape, found after reading
    "broken_no_tets.msh": "no tetrahedra",
    "broken_obj_named_gltf.gltf": "does not parse",          # JSON, read by a library
    "broken_surface.dae": "unsupported surface format",
    "broken_unknown.dat": "unsupported surface format",
    "gltf_strip_without_positions.gltf": "no POSITION",
    "ply_binary_index_postprocess.ply": "out of range",      # binary: the item is named
}
REFUSED = {"SimpleBeamHexa.msh": "no tetrahedra"}  # SOFA's hexahedral beam: Tacta steps tets
# A hang guard, not a speed test: 0.1 s of simulation takes well under a second of wall time
# per body in the optimised build; ASan and a loaded 2-core machine stay far inside this.
HANG_GUARD_S = 120


def corpus():
    for folder in FOLDERS:
        for path in sorted((src / folder).rglob("*")):
            if path.is_file() and path.suffix.lower() not in NOT_MESHES and path.name != "LICENSE":
                yield path


def meant_bad(path):
    return path.name.startswith("broken_") or "fuzz" in path.parts or path.name in REFUSED


def check(path):
    """One file: a list of failures (empty when it does what it should) and a line of output."""
    rel = path.relative_to(src)
    info = json.loads(subprocess.run([tacta, "mesh-info", "--json", str(path)],
                                     capture_output=True, text=True).stdout or "{}")
    lo, hi = (info["bounds_min_m"], info["bounds_max_m"]) if "bounds_min_m" in info else ([0] * 3, [1] * 3)
    scale = 0.1 / max(max(h - l for h, l in zip(hi, lo)), 1e-12)  # every body about 10 cm across
    top = hi[1] * scale - 0.25 * (hi[1] - lo[1]) * scale  # the top quarter is held
    scene = work / (str(rel).replace("/", "_") + ".yaml")
    scene.write_text(f"""name: corpus
gravity: [0, -9.81, 0]
clock: {{mode: lockstep, duration_s: 0.1}}
bodies:
  - name: body
    mesh: {{file: {path}, scale: {scale!r}}}
    material: {{youngs_modulus: 1.0e5, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 5}}
    model: corotational_fem
    fixed: [{{box: {{min: [-1, {top!r}, -1], max: [1, 1, 1]}}}}]
""")
    out = work / scene.stem
    start = time.monotonic()
    try:
        run = subprocess.run([tacta, "run", str(scene), "--out", str(out)], capture_output=True,
                             text=True, timeout=HANG_GUARD_S)
    except subprocess.TimeoutExpired:
        return [f"{rel}: still running after {HANG_GUARD_S} s (hang guard)"], ""
    seconds = time.monotonic() - start
    if meant_bad(path):
        if run.returncode != 2:
            return [f"{rel}: exit {run.returncode}, expected 2 (refused): {run.stdout[-300:]}"], ""
        message = run.stderr
        want = REFUSED.get(path.name) or NO_LINE.get(path.name)
        if str(path) not in message:
            return [f"{rel}: refused without naming the file: {message[:300]}"], ""
        if want is not None and want not in message:
            return [f"{rel}: refused without saying '{want}': {message[:300]}"], ""
        if want is None and not re.search(re.escape(str(path)) + r":\d+:", message):
            return [f"{rel}: refused without naming the line: {message[:300]}"], ""
        return [], f"{rel}: refused ({seconds:.2f} s): {message.strip().splitlines()[0][:160]}"
    if run.returncode != 0:
        return [f"{rel}: exit {run.returncode}, expected 0: {run.stderr.strip()[:300]}"], ""
    body = json.loads((out / "report.json").read_text())["bodies"][0]
    summary = body["mesh"]["summary"]
    failures = []
    counted = re.search(r"(\d+) piece\(s\)", summary)  # voxels and volume files say it
    pieces = int(counted.group(1)) if counted else 1
    shells = body["mesh"].get("surface_shells", 1)  # a volume file: one piece wanted
    if pieces > max(shells, 1):
        failures.append(f"{rel}: {pieces} pieces for {shells} surface shell(s): {summary}")
    held = re.search(r"body body \(corotational_fem\): \d+ nodes \((\d+) fixed\)", run.stdout)
    if not held or int(held.group(1)) == 0:
        failures.append(f"{rel}: no node held: {run.stdout[:300]}")
    return failures, f"{rel}: {summary} ({seconds:.2f} s)"


failures = []
with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
    for found, line in pool.map(check, corpus()):
        if line:
            print(line)
        failures += found
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
