#!/usr/bin/python3
"""Writes the SOFA cantilever's tetrahedral mesh (tests/data/sofa_cantilever/beam_5x5x30.msh).

SOFA's validation scene examples/Validation/cantilever_beam (sofa-framework/sofa): a
RegularGridTopology from (-0.01, -0.01, 0) to (0.01, 0.01, 0.2) m with 5 x 5 x 30 nodes, each
hexahedron cut into 6 tetrahedra around its diagonal corner 0 - corner 6 by
Hexa2TetraTopologicalMapping with swapping="true": the hexahedron's corners are mirrored along x
in cells of even x index, along y in cells of odd y index and along z in cells of odd z index,
so the diagonals alternate from cell to cell. Corners are numbered as SOFA numbers them
(0 (x,y,z), 1 (x+1,y,z), 2 (x+1,y+1,z), 3 (x,y+1,z), then 4..7 the same at z+1); tets are
written positively oriented. Gmsh 2.2 ASCII. Usage: scripts/validation/sofa_cantilever_mesh.py
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NODES = (5, 5, 30)
LO, HI = (-0.01, -0.01, 0.0), (0.01, 0.01, 0.2)
# The six tets of a cell around the diagonal 0 - 6, as corner numbers.
SPLIT = ((0, 5, 1, 6), (0, 1, 3, 6), (1, 3, 6, 2), (6, 3, 0, 7), (6, 7, 0, 5), (7, 5, 4, 0))


def node(x, y, z):
    return x + NODES[0] * (y + NODES[1] * z)


def signed_volume(p, t):
    a, b, c, d = (p[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0]))


def main():
    points = []
    for z in range(NODES[2]):
        for y in range(NODES[1]):
            for x in range(NODES[0]):
                points.append(tuple(LO[a] + (HI[a] - LO[a]) * (x, y, z)[a] / (NODES[a] - 1) for a in range(3)))
    tets = []
    for z in range(NODES[2] - 1):
        for y in range(NODES[1] - 1):
            for x in range(NODES[0] - 1):
                c = [node(x, y, z), node(x + 1, y, z), node(x + 1, y + 1, z), node(x, y + 1, z),
                     node(x, y, z + 1), node(x + 1, y, z + 1), node(x + 1, y + 1, z + 1), node(x, y + 1, z + 1)]
                if x % 2 == 0:
                    c = [c[1], c[0], c[3], c[2], c[5], c[4], c[7], c[6]]
                if y % 2 == 1:
                    c = [c[3], c[2], c[1], c[0], c[7], c[6], c[5], c[4]]
                if z % 2 == 1:
                    c = c[4:] + c[:4]
                for t in SPLIT:
                    tet = [c[i] for i in t]
                    if signed_volume(points, tet) < 0:
                        tet[2], tet[3] = tet[3], tet[2]
                    tets.append(tet)
    out = os.path.join(ROOT, "tests", "data", "sofa_cantilever", "beam_5x5x30.msh")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(points))
        for i, p in enumerate(points):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, p[0], p[1], p[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % len(tets))
        for i, t in enumerate(tets):
            f.write("%d 4 2 1 1 %d %d %d %d\n" % (i + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1))
        f.write("$EndElements\n")


if __name__ == "__main__":
    main()
