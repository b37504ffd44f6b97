#!/usr/bin/env python3
"""Writes the small base meshes in assets/. Run from the repository root; the outputs are
committed, so the build never needs Python. Counts are documented in assets/README.md."""
import math, os

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets")

def fmt(x):
    r = repr(float(x))
    return r[:-2] if r.endswith(".0") else r

def y_up(v):
    """The shapes below are built Z-up; surface OBJ files are written Y-up, as OBJ viewers expect
    (a rotation about x, so orientation is kept)."""
    x, y, z = v
    return (x, z, -y if y != 0 else 0.0)

def write(name, comment, verts, faces, extra=""):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("# %s\n# Written by Sublift's scripts/make_assets.py (public domain, CC0).\n" % comment)
        for v in verts:
            f.write("v %s\n" % " ".join(fmt(c) for c in y_up(v)))
        for face in faces:
            f.write("f %s\n" % " ".join(str(i + 1) for i in face))
        f.write(extra)

def torus(n, m, R=1.0, r=0.4):
    verts = []
    for i in range(n):
        for j in range(m):
            u, v = 2 * math.pi * i / n, 2 * math.pi * j / m
            verts.append(((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v)))
    idx = lambda i, j: (i % n) * m + (j % m)
    faces = [(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)) for i in range(n) for j in range(m)]
    return verts, faces

cube_v = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
cube_f = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
write("cube.obj", "Cube: 8 vertices of valence 3 (extraordinary for quads), 6 quads", cube_v, cube_f)

v, f = torus(12, 8)
write("torus_quad.obj", "Regular quad torus 12 x 8: every vertex valence 4, genus 1", v, f)

v, f = torus(24, 12)
write("sample.obj", "Sample opened by 'sublift' with no file: regular quad torus 24 x 12", v, f)

pyr_v = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 0, 1.4)]
pyr_f = [(0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
write("pyramid.obj", "Square pyramid: one quad, four triangles, apex of valence 4", pyr_v, pyr_f)

# Pentagonal prism with a pentagonal pyramid on top: faces of 3, 4 and 5 sides; the apex has
# valence 5 and the bottom pentagon's corners valence 3 (extraordinary for both schemes).
mv = [(math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5), 0.0) for k in range(5)]
mv += [(math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5), 1.0) for k in range(5)]
mv += [(0.0, 0.0, 1.8)]
mf = [tuple(reversed(range(5)))]
mf += [(k, (k + 1) % 5, 5 + (k + 1) % 5, 5 + k) for k in range(5)]
mf += [(5 + k, 5 + (k + 1) % 5, 10) for k in range(5)]
write("mixed_polygons.obj", "Mixed triangles/quads/pentagon with extraordinary vertices (closed)", mv, mf)

gv = [(x - 2.0, y - 2.0, 0.15 * math.sin(x) * math.cos(y)) for y in range(5) for x in range(5)]
gf = [(y * 5 + x, y * 5 + x + 1, (y + 1) * 5 + x + 1, (y + 1) * 5 + x) for y in range(4) for x in range(4)]
write("quad_grid_boundary.obj", "Open 4 x 4 quad grid: one boundary loop of 16 edges, 4 corners", gv, gf)

# Flat stars of n kite quads around one vertex of valence n (3 and 5): the basis gallery's
# extraordinary vertices, on a plane so the height field shows the function and not the shape.
def star(n):
    rq = 1.0 / math.cos(math.pi / n)  # kite tips on the lines through the spoke ends
    sv = [(0.0, 0.0, 0.0)]
    for k in range(n):
        a = 2 * math.pi * k / n
        b = a + math.pi / n
        sv += [(math.cos(a), math.sin(a), 0.0), (rq * math.cos(b), rq * math.sin(b), 0.0)]
    sf = [(0, 1 + 2 * k, 2 + 2 * k, 1 + (2 * k + 2) % (2 * n)) for k in range(n)]
    return sv, sf

for n in (3, 5):
    sv, sf = star(n)
    write("star%d_flat.obj" % n, "Flat star of %d kite quads around a valence-%d vertex, the first" % (n, n), sv, sf)

# A flat 6 x 6 quad grid with its middle column (x = 0, vertices 3, 10, ..., 45) tagged as a
# crease: the gallery's crease function over a plane; vertex 24 is the centre.
cv = [(x - 3.0, y - 3.0, 0.0) for y in range(7) for x in range(7)]
cf = [(y * 7 + x, y * 7 + x + 1, (y + 1) * 7 + x + 1, (y + 1) * 7 + x) for y in range(6) for x in range(6)]
ctags = "".join("t crease 2/1/0 %d %d 10\n" % (3 + 7 * k, 10 + 7 * k) for k in range(6))
write("crease_grid_flat.obj", "Flat 6 x 6 quad grid, middle column tagged as a crease (t crease)", cv, cf, ctags)
# The same grid with a crease from the boundary to the centre vertex (24), where it ends inside
# the surface (a dart): the sqrt(2) lifting next to a curve end (001 sec. 4).
dtags = "".join("t crease 2/1/0 %d %d 10\n" % (3 + 7 * k, 10 + 7 * k) for k in range(3))
write("crease_dart_flat.obj", "Flat 6 x 6 quad grid, a crease from the boundary ending at the centre vertex (t crease)", cv, cf, dtags)

# A box in four rings (z = 0, 1/3, 2/3, 1); the ring at z = 1/3 is tagged as a crease loop in
# OpenSubdiv's syntax (0-based vertex indices, infinite-ish sharpness 10).
zs = (0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0)
corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
bv = [(x, y, z * 2 - 1) for z in zs for (x, y) in corners]
bf = [(3, 2, 1, 0), (12, 13, 14, 15)]
bf += [(r * 4 + k, r * 4 + (k + 1) % 4, (r + 1) * 4 + (k + 1) % 4, (r + 1) * 4 + k) for r in range(3) for k in range(4)]
tags = "".join("t crease 2/1/0 %d %d 10\n" % (4 + k, 4 + (k + 1) % 4) for k in range(4))
write("crease_loop.obj", "Box with a tagged crease loop (t crease) around the ring at height -1/3", bv, bf, tags)

# Triangle meshes for the schemes of paper 004 (linear-tri, butterfly, loop).
ov = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
of = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
write("octahedron.obj", "Octahedron: 6 vertices of valence 4 (extraordinary for triangles), 8 triangles", ov, of)
# An open 5 x 4 grid of squares cut into triangles along alternating diagonals, a bump in z,
# the inner row y = 2 tagged as a crease from boundary to boundary.
tv = [(i, j, 0.25 * math.sin(1.3 * i) * math.cos(0.9 * j)) for j in range(5) for i in range(6)]
tf = []
for j in range(4):
    for i in range(5):
        a0, a1, a2, a3 = i + 6 * j, i + 1 + 6 * j, i + 1 + 6 * (j + 1), i + 6 * (j + 1)
        tf += [(a0, a1, a2), (a0, a2, a3)] if (i + j) % 2 == 0 else [(a0, a1, a3), (a1, a2, a3)]
ttags = "".join("t crease 2/1/0 %d %d 10\n" % (12 + i, 13 + i) for i in range(5))
write("tri_crease_grid.obj", "Open 5 x 4 grid of triangles (alternating diagonals), the row y = 2 tagged as a crease", tv, tf, ttags)

# ---- Curves and lattices (formats: docs/file_formats.md) ----

# Curves: an open polyline (a quarter helix) and a closed one (an octagon), OBJ 'l' lines.
# Kept in assets/curves/: tools that iterate over assets/*.obj expect surfaces there.
os.makedirs(os.path.join(HERE, "curves"), exist_ok=True)
with open(os.path.join(HERE, "curves", "curve.obj"), "w") as f:
    f.write("# Two polylines: an open helix arc (6 vertices) and a closed octagon (8 vertices).\n"
            "# Written by Sublift's scripts/make_assets.py (public domain, CC0).\n")
    for k in range(6):
        t = 0.5 * math.pi * k / 5
        f.write("v %s %s %s\n" % (fmt(2 * math.cos(t)), fmt(2 * math.sin(t)), fmt(0.3 * k)))
    for k in range(8):
        t = 2 * math.pi * k / 8
        f.write("v %s %s 0\n" % (fmt(math.cos(t)), fmt(math.sin(t))))
    f.write("l 1 2 3 4 5 6\n")
    f.write("l %s 7\n" % " ".join(str(7 + k) for k in range(8)))

def write_lattice(name, comment, verts, cells, extra=""):
    """cells: ('hex'|'wedge'|'pyramid'|'tet', [ids]) in VTK vertex order (0-based)."""
    with open(os.path.join(HERE, name), "w") as f:
        f.write("sublift-lattice 1\n# %s\n# Written by Sublift's scripts/make_assets.py (public domain, CC0).\n" % comment)
        for v in verts:
            f.write("v %s\n" % " ".join(fmt(c) for c in v))
        for kind, ids in cells:
            f.write("%s %s\n" % (kind, " ".join(str(i) for i in ids)))
        f.write(extra)

def hex_block(nx, ny, nz, scale=1.0):
    idx = lambda i, j, k: (k * (ny + 1) + j) * (nx + 1) + i
    verts = [((i - nx / 2) * scale, (j - ny / 2) * scale, (k - nz / 2) * scale)
             for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)]
    cells = [("hex", [idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                      idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)])
             for k in range(nz) for j in range(ny) for i in range(nx)]
    return verts, cells, idx

v, c, _ = hex_block(1, 1, 1, 2.0)
write_lattice("cube_cell.lattice", "A single hexahedral cell (the cube [-1, 1]^3)", v, c)

v, c, _ = hex_block(4, 4, 4, 0.5)
write_lattice("hex_block_4.lattice", "A 4 x 4 x 4 block of hexahedra (regular inside)", v, c)

write_lattice("pyramid_cell.lattice", "A single square pyramid cell (4 triangles and a quad)",
              [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 0, 1.4)], [("pyramid", [0, 1, 2, 3, 4])])

# Prism ring: 8 wedges around the z axis; the axis edge is shared by all 8 cells.
pv = [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)]
for z in (0.0, 1.0):
    for k in range(8):
        t = 2 * math.pi * k / 8
        pv.append((math.cos(t), math.sin(t), z))
pc = [("wedge", [0, 2 + k, 2 + (k + 1) % 8, 1, 10 + k, 10 + (k + 1) % 8]) for k in range(8)]
write_lattice("prism_ring.lattice", "Prism ring: 8 wedge cells around the z axis (an edge of valence 8)", pv, pc)

# Swept quad mesh: a quad annulus (12 around x 2 radial) swept along z in two layers of hexahedra.
n_around, n_radial, n_layers = 12, 2, 2
sid = lambda a, r, l: (l * (n_radial + 1) + r) * n_around + a % n_around
sv = []
for l in range(n_layers + 1):
    for r in range(n_radial + 1):
        for a in range(n_around):
            t = 2 * math.pi * a / n_around
            sv.append(((1 + 0.5 * r) * math.cos(t), (1 + 0.5 * r) * math.sin(t), 0.5 * l))
sc = [("hex", [sid(a, r, l), sid(a, r + 1, l), sid(a + 1, r + 1, l), sid(a + 1, r, l),
               sid(a, r, l + 1), sid(a, r + 1, l + 1), sid(a + 1, r + 1, l + 1), sid(a + 1, r, l + 1)])
      for l in range(n_layers) for r in range(n_radial) for a in range(n_around)]
write_lattice("swept_quads.lattice", "Quad annulus (12 x 2 quads) swept into two layers of hexahedra", sv, sc)

# Inner feature surface: a 3 x 3 x 4 block whose middle layer z = 0 is tagged as a surface.
v, c, idx = hex_block(3, 3, 4, 0.5)
tags = "".join("feature_face %d %d %d %d\n" % (idx(i, j, 2), idx(i + 1, j, 2), idx(i + 1, j + 1, 2), idx(i, j + 1, 2))
               for j in range(3) for i in range(3))
write_lattice("feature_surface.lattice", "3 x 3 x 4 hexahedra with an inner feature surface (9 feature_face tags at z = 0)",
              v, c, tags)

# ---- FFD sample lattices (issue 6), in assets/ffd/ ----
# In a folder of their own, so that tools iterating over assets/*.lattice keep their set. Built
# Z-up like the others, written Y-up like the OBJ files (and glTF models, and the modeler's
# view), so that "top" is +y and torus_ring fits assets/torus_quad.obj as written. Every
# standard cell is written positively oriented (hex: 0-1 x 0-3 toward 4; wedge: 0-1 x 0-2 toward
# 3; pyramid: 0-1 x 0-3 toward the apex); oriented() flips any cell built the other way.
os.makedirs(os.path.join(HERE, "ffd"), exist_ok=True)

def oriented(verts, cells):
    def det(o, a, b, c):
        p = [[verts[i][k] - verts[o][k] for k in range(3)] for i in (a, b, c)]
        return (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0])
                + p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]))
    out = []
    for kind, ids in cells:
        if kind == "hex" and det(ids[0], ids[1], ids[3], ids[4]) < 0:
            ids = ids[4:] + ids[:4]
        elif kind == "wedge" and det(ids[0], ids[1], ids[2], ids[3]) < 0:
            ids = ids[3:] + ids[:3]
        elif kind == "pyramid" and det(ids[0], ids[1], ids[3], ids[4]) < 0:
            ids = [ids[0], ids[3], ids[2], ids[1], ids[4]]
        out.append((kind, ids))
    return out

def write_ffd_lattice(name, comment, verts, cells, extra=""):
    verts = [y_up(p) for p in verts]
    write_lattice("ffd/" + name, comment, verts, oriented(verts, cells), extra)

# Bent tube: a SOLID round tube (an O-grid section: 2 x 2 hexahedra in the middle and a ring of 8
# around them, 17 vertices a section; its 4 O-grid corner edges have valence 3) swept along a
# quarter circle of radius 2 about the vertical axis (Y-up: from +x to -z), in 6 steps. Solid rather than a
# pipe wall, so a model anywhere inside the tube (a bent rod or cylinder along the arc, radius
# up to about 0.4 after cubic subdivision) is embedded.
bend_R, tube_r, core_a, steps = 2.0, 0.5, 0.22, 6
ring_ij = [(2, 1), (2, 2), (1, 2), (0, 2), (0, 1), (0, 0), (1, 0), (2, 0)]  # square border, ccw
section = [(core_a * (i - 1), core_a * (j - 1)) for j in range(3) for i in range(3)]
section += [(tube_r * math.cos(math.pi * k / 4), tube_r * math.sin(math.pi * k / 4)) for k in range(8)]
quads = [(j * 3 + i, j * 3 + i + 1, (j + 1) * 3 + i + 1, (j + 1) * 3 + i) for j in range(2) for i in range(2)]
quads += [(ring_ij[k][1] * 3 + ring_ij[k][0], 9 + k, 9 + (k + 1) % 8,
           ring_ij[(k + 1) % 8][1] * 3 + ring_ij[(k + 1) % 8][0]) for k in range(8)]
tv = []
for m in range(steps + 1):
    t = 0.5 * math.pi * m / steps
    tv += [((bend_R + s) * math.cos(t), (bend_R + s) * math.sin(t), h) for s, h in section]
n_sec = len(section)
tc = [("hex", [m * n_sec + q for q in quad] + [(m + 1) * n_sec + q for q in quad]) for m in range(steps) for quad in quads]
write_ffd_lattice("bent_tube.lattice", "Solid round tube (O-grid section, 12 hexahedra) bent along a quarter circle in 6 steps",
                  tv, tc)

# Pyramid cap: a 2 x 2 x 2 block of hexahedra ([-1, 1]^3) whose 4 top quads are capped by 4
# pyramids sharing one apex above the middle, so the lattice tapers to a point; the edge from
# the top centre to the apex is shared by the 4 pyramids. The apex is tagged as a corner: cubic
# levels would round it off (to height 1.6 at level 2); the corner keeps the point at every level.
v, c, idx = hex_block(2, 2, 2, 1.0)
apex = len(v)
v.append((0.0, 0.0, 2.2))
c += [("pyramid", [idx(i, j, 2), idx(i + 1, j, 2), idx(i + 1, j + 1, 2), idx(i, j + 1, 2), apex])
      for j in range(2) for i in range(2)]
write_ffd_lattice("pyramid_cap.lattice", "2 x 2 x 2 hexahedra capped by 4 pyramids meeting at one apex (a corner)",
                  v, c, "corner %d\n" % apex)

# Torus ring: 12 wedges around the axis of assets/torus_quad.obj (R = 1, r = 0.4; both written
# Y-up, so the axis is y in the files), closed (the last wedge reuses the first section). Each section is an
# equilateral triangle around the tube circle with inradius 0.62 (its inner side vertical, apex
# outward): cubic levels round the triangles off, and from two levels on an inradius below about
# 0.49 leaves torus vertices outside, so 0.62 keeps a margin at every depth.
ring_n, ring_in = 12, 0.62
tri = [(1.0 - ring_in, -math.sqrt(3) * ring_in), (1.0 + 2 * ring_in, 0.0), (1.0 - ring_in, math.sqrt(3) * ring_in)]
rv = []
for m in range(ring_n):
    u = 2 * math.pi * m / ring_n
    rv += [(rho * math.cos(u), rho * math.sin(u), z) for rho, z in tri]
rc = [("wedge", [3 * m, 3 * m + 1, 3 * m + 2] + [3 * ((m + 1) % ring_n) + k for k in range(3)]) for m in range(ring_n)]
write_ffd_lattice("torus_ring.lattice", "Closed ring of 12 wedges around assets/torus_quad.obj (axis y, as that file)",
                  rv, rc)

# Crease and feature face: a 4 x 4 x 3 block of hexahedra (edge 0.5) with a crease chain across
# the top face along x = 0 (5 vertices, 4 edges; boundary edges, so a fold line of the top) and
# an inner feature surface: the 2 x 2 faces of the horizontal plane 0.25 below the middle,
# around the vertical axis (Y-up: the top is y = 0.75, the surface at y = -0.25).
v, c, idx = hex_block(4, 4, 3, 0.5)
tags = "crease %s\n" % " ".join(str(idx(2, j, 3)) for j in range(5))
tags += "".join("feature_face %d %d %d %d\n" % (idx(i, j, 1), idx(i + 1, j, 1), idx(i + 1, j + 1, 1), idx(i, j + 1, 1))
                for j in (1, 2) for i in (1, 2))
write_ffd_lattice("crease_feature.lattice", "4 x 4 x 3 hexahedra, a crease across the top and a 2 x 2 inner feature surface",
                  v, c, tags)
