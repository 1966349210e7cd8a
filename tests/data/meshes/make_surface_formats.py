#!/usr/bin/env python3
"""Writes the hand-made OFF and VTK PolyData files of this folder (standard library only):
   python3 tests/data/meshes/make_surface_formats.py
Each good file is the same closed square pyramid (base [0,1]^2 at z = 0, apex (0.5, 0.5, 1),
volume 1/3 m^3): the base a quad (fan-triangulated by the readers), the four sides as two
triangle strips (VTK) or triangles (OFF). Broken files carry one defect each."""
import base64
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
QUAD = (0, 3, 2, 1)                   # the base, outward (-z)
STRIPS = [(0, 1, 4, 2), (2, 3, 4, 0)]  # (0,1,4) (4,1,2) and (2,3,4) (4,3,0): the four sides, outward
SIDES = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]


def write(name, data):
    with open(os.path.join(HERE, name), "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)


def signed_volume(faces):
    """Divergence theorem over fan triangles: 1/3 for the pyramid when every face points out."""
    total = 0.0
    for f in faces:
        for k in range(1, len(f) - 1):
            a, b, c = (POINTS[f[0]], POINTS[f[k]], POINTS[f[k + 1]])
            total += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                      + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
    return total


def strip_triangles(strip):
    return [(strip[k], strip[k + 1], strip[k + 2]) if k % 2 == 0 else (strip[k + 1], strip[k], strip[k + 2])
            for k in range(len(strip) - 2)]


assert abs(signed_volume([QUAD] + SIDES) - 1 / 3) < 1e-12
assert abs(signed_volume([QUAD] + [t for s in STRIPS for t in strip_triangles(s)]) - 1 / 3) < 1e-12


def off(keyword="OFF", vertex_extra=lambda i: "", face_extra=lambda i: "", counts_on_keyword=False):
    faces = [QUAD] + SIDES
    lines = ["# a square pyramid, volume 1/3", ""]
    counts = f"{len(POINTS)} {len(faces)} 8"
    lines += [f"{keyword} {counts}" if counts_on_keyword else keyword]
    if not counts_on_keyword:
        lines += ["# vertices faces edges", counts]
    lines += [" ".join(map(str, p)) + vertex_extra(i) for i, p in enumerate(POINTS)]
    lines += ["  # faces: the base first"]
    lines += [f"{len(f)} " + " ".join(map(str, f)) + face_extra(i) for i, f in enumerate(faces)]
    return "\n".join(lines) + "\n"


def legacy_ascii():
    lines = ["# vtk DataFile Version 4.2", "square pyramid", "ASCII", "DATASET POLYDATA",
             f"POINTS {len(POINTS)} float"]
    lines += [" ".join(map(str, p)) for p in POINTS]
    lines += ["METADATA", "INFORMATION 0", ""]
    lines += ["VERTICES 1 2", "1 4"]
    lines += [f"POLYGONS 1 {len(QUAD) + 1}", f"{len(QUAD)} " + " ".join(map(str, QUAD))]
    lines += [f"TRIANGLE_STRIPS {len(STRIPS)} {sum(len(s) + 1 for s in STRIPS)}"]
    lines += [f"{len(s)} " + " ".join(map(str, s)) for s in STRIPS]
    lines += [f"POINT_DATA {len(POINTS)}", "NORMALS Normals float"] + ["0 0 1"] * len(POINTS)
    return "\n".join(lines) + "\n"


def legacy_binary():
    """BINARY, classic cell layout: big-endian floats and 4-byte ints after each header line."""
    out = b"# vtk DataFile Version 3.0\nsquare pyramid\nBINARY\nDATASET POLYDATA\n"
    out += f"POINTS {len(POINTS)} float\n".encode() + struct.pack(">15f", *[c for p in POINTS for c in p]) + b"\n"
    cells = [len(QUAD), *QUAD]
    out += f"POLYGONS 1 {len(cells)}\n".encode() + struct.pack(f">{len(cells)}i", *cells) + b"\n"
    cells = [v for s in STRIPS for v in (len(s), *s)]
    out += f"TRIANGLE_STRIPS {len(STRIPS)} {len(cells)}\n".encode() + struct.pack(f">{len(cells)}i", *cells) + b"\n"
    return out


def vtp(mode, header="UInt32", compress=False, block=None, strip_override=None, forge_points=0):
    """mode: ascii, binary (inline base64), raw or base64 (appended). block: zlib block size."""
    h = "<I" if header == "UInt32" else "<Q"
    appended = []  # (name, bytes) of appended arrays, in order
    coords = [c for p in POINTS for c in p]
    strips = strip_override or STRIPS

    def payload(data):
        if not compress:
            return [struct.pack(h, len(data)), data]
        size = block or max(len(data), 1)
        blocks = [data[i:i + size] for i in range(0, len(data), size)] or [b""]
        packed = [zlib.compress(b) for b in blocks]
        last = len(blocks[-1]) if len(blocks[-1]) != size else 0
        head = struct.pack(h[0] + h[1] * (3 + len(packed)), len(blocks), size, last, *map(len, packed))
        if forge_points and len(data) == 8 * len(coords):  # the points: a header that lies
            head = struct.pack(h[0] + h[1] * 4, 1, 24 * forge_points, 0, len(packed[0]))
        return [head, b"".join(packed)]

    def array(type_name, code, values, attrs):
        base = f'type="{type_name}" {attrs}'
        if mode == "ascii":
            return f'<DataArray {base} format="ascii">{" ".join(map(str, values))}</DataArray>'
        parts = payload(struct.pack("<" + code * len(values), *values))
        if mode == "binary":
            text = "".join(base64.b64encode(p).decode() for p in parts)
            return f'<DataArray {base} format="binary">\n{text}\n</DataArray>'
        offset = sum(len(b) for b in appended)
        encoded = b"".join(base64.b64encode(p) for p in parts) if mode == "base64" else b"".join(parts)
        appended.append(encoded)
        return f'<DataArray {base} format="appended" offset="{offset}"/>'

    strip_conn = [v for s in strips for v in s]
    strip_offsets = [sum(len(s) for s in strips[:k + 1]) for k in range(len(strips))]
    comp = ' compressor="vtkZLibDataCompressor"' if compress else ""
    text = f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="{header}"{comp}>
  <PolyData>
    <Piece NumberOfPoints="{forge_points or len(POINTS)}" NumberOfVerts="0" NumberOfLines="0" NumberOfStrips="{len(strips)}" NumberOfPolys="1">
      <PointData Normals="Normals">
        {array("Float32", "f", [0.0, 0.0, 1.0] * len(POINTS), 'Name="Normals" NumberOfComponents="3"')}
      </PointData>
      <Points>
        {array("Float64", "d", coords, 'Name="Points" NumberOfComponents="3"')}
      </Points>
      <Strips>
        {array("Int64", "q", strip_conn, 'Name="connectivity"')}
        {array("Int64", "q", strip_offsets, 'Name="offsets"')}
      </Strips>
      <Polys>
        {array("Int32", "i", list(QUAD), 'Name="connectivity"')}
        {array("Int32", "i", [len(QUAD)], 'Name="offsets"')}
      </Polys>
    </Piece>
  </PolyData>
"""
    if mode in ("raw", "base64"):
        return text.encode() + f'  <AppendedData encoding="{mode}">\n   _'.encode() + b"".join(appended) + \
            b"\n  </AppendedData>\n</VTKFile>\n"
    return text + "</VTKFile>\n"


def main():
    write("pyramid.off", off(face_extra=lambda i: "  # base" if i == 0 else ""))
    write("pyramid_coff.off", off("COFF", vertex_extra=lambda i: f" 255 {40 * i} 0 255",
                                  face_extra=lambda i: " 0.5 0.5 0.5 1", counts_on_keyword=True))
    write("pyramid_noff.off", off("NOFF", vertex_extra=lambda i: " 0 0 1"))
    write("pyramid_cnoff.off", off("CNOFF", vertex_extra=lambda i: " 0 0 1 0.1 0.2 0.3 1"))
    write("pyramid_fused.off", off("OFF", counts_on_keyword=True).replace("OFF ", "OFF", 1))
    write("pyramid_bad_colours.off", off("COFF", vertex_extra=lambda i: " red green blue" if i == 2 else " 1 1 1 1"))
    write("pyramid_ascii.vtk", legacy_ascii())
    write("pyramid_binary.vtk", legacy_binary())
    write("pyramid_ascii.vtp", vtp("ascii"))
    write("pyramid_binary.vtp", vtp("binary"))
    write("pyramid_zlib_blocks.vtp", vtp("binary", compress=True, block=16))
    write("pyramid_appended_raw64.vtp", vtp("raw", header="UInt64", compress=True))
    write("pyramid_appended_base64.vtp", vtp("base64", compress=True, block=32))
    # Leniency: attributes a simulation does not use, broken; each file loads with one warning.
    write("uv_indices_without_vt.obj", "# faces name vt and vn that the file does not have\n"
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl skin\ng tetra\n"
          "f 1/1/1 3/2/1 2/3/1\nf 1/1/2 2/2/2 4/3/2\nf 1/1/3 4/2/3 3/3/3\nf 2/1/4 3/2/4 4/3/4\n")
    write("nan_normals.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
          "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n"
          "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
          "0 0 0 nan nan nan 300\n1 0 0 1 0 0 255\n0 1 0 0 1 0 255\n0 0 1 0 0 1 255\n"
          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    # Broken: one defect each (tests/engine/mesh/test_volume_errors.cpp lists the errors).
    write("broken_off_index.off", off().replace("\n3 2 3 4\n", "\n3 2 3 5\n"))
    write("broken_off_count.off", off().replace("\n5 5 8\n", "\n5 500 8\n"))
    write("broken_off_number.off", off().replace("\n1 1 0\n", "\n1 1 zero\n"))
    write("broken_off_4off.off", off("4OFF"))
    write("broken_polydata_index.vtk", legacy_ascii().replace("\n4 0 3 2 1\n", "\n4 0 3 2 9\n"))
    write("broken_polydata_short.vtk", legacy_ascii().replace("\n4 0 1 4 2\n", "\n4 0 1 4\n"))
    write("broken_polydata_binary.vtk", legacy_binary()[:-30])
    write("broken_strip.vtp", vtp("ascii", strip_override=[(0, 1), (2, 3, 4, 0)]))
    # The points' header promises 10^9 bytes from a few compressed bytes, consistently with the
    # point count: refused before anything is allocated.
    write("broken_zlib_size.vtp", vtp("binary", compress=True, forge_points=41666666))
    good = vtp("raw")
    points = good.index(b'Name="Points"')
    write("broken_appended_offset.vtp", good[:points] + good[points:].replace(b'offset="', b'offset="9999', 1))


if __name__ == "__main__":
    main()
