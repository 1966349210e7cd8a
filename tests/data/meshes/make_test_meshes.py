#!/usr/bin/env python3
"""Writes the small hand-made meshes of this folder (standard library only). Run from anywhere:
   python3 tests/data/meshes/make_test_meshes.py
All of them are a unit cube [0,1]^3 cut into 6 tets, or small broken variants of it."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# Unit cube corners: index = x + 2y + 4z; one unused point (index 8) to test its removal.
POINTS = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)] + [(5, 5, 5)]
# Six tets around the 0-7 diagonal; the second is inverted on purpose (finalize re-orients it).
TETS = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 7, 3), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 7, 6)]
TRIS = [(0, 1, 3)]  # a boundary triangle that a tet reader must skip


def write(name, text, mode="w"):
    with open(os.path.join(HERE, name), mode) as f:
        f.write(text)


def legacy_vtk():
    lines = ["# vtk DataFile Version 3.0", "unit cube, 6 tets and 1 triangle", "ASCII",
             "DATASET UNSTRUCTURED_GRID", f"POINTS {len(POINTS)} double"]
    lines += [" ".join(map(str, p)) for p in POINTS]
    cells = [(4,) + t for t in TETS] + [(3,) + t for t in TRIS]
    lines.append(f"CELLS {len(cells)} {sum(len(c) for c in cells)}")
    lines += [" ".join(map(str, c)) for c in cells]
    lines.append(f"CELL_TYPES {len(cells)}")
    lines += ["10"] * len(TETS) + ["5"] * len(TRIS)
    return "\n".join(lines) + "\n"


def vtu(fmt, header="UInt32", compress=False, byte_order="LittleEndian"):
    conn = [i for t in TETS for i in t] + [i for t in TRIS for i in t]
    offsets = [4 * (k + 1) for k in range(len(TETS))] + [4 * len(TETS) + 3]
    types = [10] * len(TETS) + [5]
    coords = [c for p in POINTS for c in p]
    end = "<" if byte_order == "LittleEndian" else ">"
    hchar = "I" if header == "UInt32" else "Q"

    def array(type_name, code, values, extra=""):
        attrs = f'type="{type_name}" {extra} format="{fmt}"'
        if fmt == "ascii":
            return f"<DataArray {attrs}>\n {' '.join(map(str, values))}\n</DataArray>"
        data = struct.pack(end + code * len(values), *values)
        if compress:
            block = zlib.compress(data)
            head = struct.pack(end + hchar * 4, 1, len(data), len(data), len(block))
            text = base64.b64encode(head).decode() + base64.b64encode(block).decode()
        else:
            text = base64.b64encode(struct.pack(end + hchar, len(data))).decode() + base64.b64encode(data).decode()
        return f"<DataArray {attrs}>\n{text}\n</DataArray>"

    comp = ' compressor="vtkZLibDataCompressor"' if compress else ""
    return f"""<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="{byte_order}" header_type="{header}"{comp}>
<UnstructuredGrid>
<Piece NumberOfPoints="{len(POINTS)}" NumberOfCells="{len(types)}">
<Points>
{array("Float64", "d", coords, 'NumberOfComponents="3"')}
</Points>
<Cells>
{array("Int64", "q", conn, 'Name="connectivity"')}
{array("Int32", "i", offsets, 'Name="offsets"')}
{array("UInt8", "B", types, 'Name="types"')}
</Cells>
</Piece>
</UnstructuredGrid>
</VTKFile>
"""


def msh22(points=POINTS, tets=TETS, node_count=None, extra_elements=()):
    node_count = len(points) if node_count is None else node_count
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(node_count)]
    lines += [f"{i + 1} {p[0]} {p[1]} {p[2]}" for i, p in enumerate(points)]
    lines += ["$EndNodes", "$Elements", str(len(tets) + len(extra_elements))]
    lines += [f"{k + 1} 4 2 0 1 " + " ".join(str(i + 1) for i in t) for k, t in enumerate(tets)]
    lines += [f"{len(tets) + k + 1} {e}" for k, e in enumerate(extra_elements)]
    lines += ["$EndElements"]
    return "\n".join(lines) + "\n"


def surfaces():
    # A closed tetrahedron in ASCII PLY, plus one degenerate face (a repeated vertex).
    verts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3), (1, 1, 2)]
    ply = ["ply", "format ascii 1.0", f"element vertex {len(verts)}", "property float x", "property float y",
           "property float z", f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
    ply += [" ".join(map(str, v)) for v in verts] + [f"3 {' '.join(map(str, f))}" for f in faces]
    write("tetra.ply", "\n".join(ply) + "\n")
    # The same tetrahedron as glTF 2.0 with an embedded buffer, under a node that moves it by +2 in x.
    positions = struct.pack("<12f", *[c for v in verts for c in v])
    indices = struct.pack("<12H", *[i for f in faces[:4] for i in f])
    buffer = positions + indices
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [2, 0, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions), "target": 34962},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    }
    write("tetra.gltf", json.dumps(gltf, indent=1) + "\n")
    # And as binary glTF (.glb): the buffer moves into the BIN chunk; the node moves it by +2 in y.
    del gltf["buffers"][0]["uri"]
    gltf["nodes"][0]["translation"] = [0, 2, 0]
    payload = json.dumps(gltf).encode()
    payload += b" " * (-len(payload) % 4)
    binary = buffer + b"\0" * (-len(buffer) % 4)
    glb = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(payload) + 8 + len(binary))
    glb += struct.pack("<I4s", len(payload), b"JSON") + payload + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    write("tetra.glb", glb, "wb")
    # Two OBJ objects that repeat the positions they share: welding must join them into one closed surface.
    obj = ["o first", "v 0 0 0", "v 1 0 0", "v 0 1 0", "v 0 0 1", "f 1 3 2", "f 1 2 4",
           "o second", "v 0 0 0", "v 0 1 0", "v 0 0 1", "v 1 0 0", "f 5 7 6", "f 8 6 7"]
    write("two_parts.obj", "\n".join(obj) + "\n")


def broken():
    write("broken_node_count.msh", msh22(node_count=len(POINTS) + 2))
    write("broken_element_count.msh", msh22().replace("$Elements\n6", "$Elements\n9"))
    bad_index = [t for t in TETS]
    bad_index[2] = (0, 2, 7, 41)
    write("broken_index.msh", msh22(tets=bad_index))
    nan_points = list(POINTS)
    nan_points[3] = (1, "nan", 0)
    write("broken_nan.msh", msh22(points=nan_points))
    write("broken_inf.vtk", legacy_vtk().replace("1 0 1\n", "1 0 inf\n", 1))
    flat = list(TETS) + [(0, 1, 2, 3)]  # four corners of the bottom face: zero volume
    write("broken_flat_tet.msh", msh22(tets=flat))
    write("broken_no_tets.msh", msh22(tets=[], extra_elements=["2 2 0 1 1 2 4"]))
    write("broken_short_line.msh", msh22().replace("\n1 4 2 0 1 1 2 4 8\n", "\n1 4 2 0 1 1 2 4\n8\n", 1))
    write("broken_unknown.dat", "solid nothing\nthis is not a mesh\n")
    write("broken_empty.msh", "")
    write("broken_cell_index.vtk", legacy_vtk().replace("4 0 4 7 6", "4 0 4 7 60"))
    write("broken_cell_type.vtk", legacy_vtk().replace("\n10\n10\n", "\n10\n12\n", 1))
    write("broken_types.vtu", vtu("ascii").replace(" 10 10 10 10 10 10 5\n", " 10 10 10 10 10 10\n"))
    write("broken_base64.vtu", vtu("binary").replace("AAAA", "A*AA", 1))
    write("broken_header.vtu", vtu("binary").replace('header_type="UInt32"', 'header_type="UInt64"'))
    write("broken_mesh_format.msh", msh22().replace("2.2 0 8", "3.0 0 8"))
    write("broken_surface.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n")


def main():
    write("cube_legacy.vtk", legacy_vtk())
    write("cube_ascii.vtu", vtu("ascii"))
    write("cube_binary32.vtu", vtu("binary", "UInt32"))
    write("cube_binary64_be.vtu", vtu("binary", "UInt64", byte_order="BigEndian"))
    write("cube_zlib.vtu", vtu("binary", "UInt32", compress=True))
    write("cube_v22.msh", msh22())
    surfaces()
    broken()


if __name__ == "__main__":
    main()
