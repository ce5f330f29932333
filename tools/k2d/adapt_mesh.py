"""The shape of the meshes gmsh makes for tools/adapt.py (docs/adaptivity.md, "Mesh quality").

    from k2d import adapt_mesh as am
    am.max_angles("step.msh")          # the largest interior angle of every 2-D element [deg]
    am.quality("step.msh")             # {"elements", "quads", "over_150", "max_angle", ...}

gmsh's recombination of a steeply graded triangulation can leave quadrilaterals with an interior
angle near 180 degrees; the error concentrates in them and the recovery estimate under-rates it
(an effectivity of 0.61 on a Hertz model).  The remeshing route measures every mesh it makes
with these functions and reports the worst angle in its table.
"""
import math

import numpy as np

# gmsh element types and the number of corner nodes: 3-node triangle, 4-node quadrilateral,
# 6-node triangle, 9- and 8-node quadrilaterals (corners first in gmsh's node order)
CORNERS = {2: 3, 3: 4, 9: 3, 10: 4, 16: 4}


def read_msh2d(path):
    """(xy of the nodes by tag: dict, [(gmsh type, corner tags)] of the 2-D elements) of a .msh
    file (format 4.1, ASCII)."""
    xy, elems = {}, []
    with open(path) as f:
        for line in f:
            tag = line.strip()
            if tag == "$Nodes":
                nblocks = int(f.readline().split()[0])
                for _ in range(nblocks):
                    _dim, _ent, _param, n = (int(v) for v in f.readline().split())
                    tags = [int(f.readline()) for _ in range(n)]
                    for t in tags:
                        c = f.readline().split()
                        xy[t] = (float(c[0]), float(c[1]))
            elif tag == "$Elements":
                nblocks = int(f.readline().split()[0])
                for _ in range(nblocks):
                    dim, _ent, ety, n = (int(v) for v in f.readline().split())
                    for _ in range(n):
                        v = f.readline().split()
                        if dim == 2 and ety in CORNERS:
                            elems.append((ety, [int(t) for t in v[1:1 + CORNERS[ety]]]))
    return xy, elems


def corner_angles(P):
    """The interior angles [deg] of the polygon with the corners P (k x 2, either orientation)."""
    P = np.asarray(P, float)
    k = len(P)
    out = np.empty(k)
    area2 = sum(P[i, 0] * P[(i + 1) % k, 1] - P[(i + 1) % k, 0] * P[i, 1] for i in range(k))
    sgn = 1.0 if area2 >= 0.0 else -1.0
    for i in range(k):
        a = P[i - 1] - P[i]
        b = P[(i + 1) % k] - P[i]
        cross = sgn * (b[0] * a[1] - b[1] * a[0])      # > 0 for a convex corner
        ang = math.degrees(math.atan2(cross, float(a @ b)))
        out[i] = ang if ang >= 0.0 else 360.0 + ang        # a reflex corner beyond 180
    return out


def polygon_max_angles(P):
    """The largest interior angle [deg] of each of the polygons P (m x k x 2, k corners in
    order, either orientation; a reflex corner counts beyond 180)."""
    P = np.asarray(P, float)
    prev, nxt = np.roll(P, 1, axis=1), np.roll(P, -1, axis=1)
    area2 = np.sum(P[:, :, 0] * nxt[:, :, 1] - nxt[:, :, 0] * P[:, :, 1], axis=1)
    sgn = np.where(area2 >= 0.0, 1.0, -1.0)[:, None]
    a, b = prev - P, nxt - P
    cross = sgn * (b[:, :, 0] * a[:, :, 1] - b[:, :, 1] * a[:, :, 0])
    ang = np.degrees(np.arctan2(cross, np.sum(a * b, axis=2)))
    return np.where(ang >= 0.0, ang, 360.0 + ang).max(axis=1)


def max_angles(path):
    """(largest interior angle of every 2-D element [deg], corner counts) of a .msh file."""
    xy, elems = read_msh2d(path)
    ang = np.zeros(len(elems))
    nc = np.array([len(c) for _ety, c in elems], dtype=int)
    for k in (3, 4):
        sel = np.where(nc == k)[0]
        if len(sel):
            ang[sel] = polygon_max_angles([[xy[t] for t in elems[i][1]] for i in sel])
    return ang, nc


# an interior angle of a quadrilateral beyond this [deg] marks a badly shaped element
ANGLE_LIMIT = 150.0


def quality(path, limit=ANGLE_LIMIT):
    """Summary of a mesh's shape: element and quadrilateral counts, the quadrilaterals with an
    interior angle above `limit` degrees, the largest angle of a quadrilateral and of a triangle."""
    ang, nc = max_angles(path)
    q = nc == 4
    return {"elements": int(len(ang)), "quads": int(np.count_nonzero(q)),
            "over_limit": int(np.count_nonzero(ang[q] > limit)),
            "max_angle_quad": float(ang[q].max()) if q.any() else float("nan"),
            "max_angle_tri": float(ang[~q].max()) if (~q).any() else float("nan")}


# the ghost cells of the size view reach this share of each boundary edge's length outwards
GHOST_DEPTH = 0.25


def boundary_ghosts(xy, cells, nodal, depth=GHOST_DEPTH):
    """Ghost quadrilaterals along the boundary of a mesh of corner cells: the size view gmsh
    meshes the next mesh from is the old mesh's corners, whose boundary edges are the chords of a
    curved boundary; the curve bulges past them (by h^2 / (8 R) for an edge h on a radius R), and
    there gmsh's PostView field finds no element and takes no size at all (its largest size:
    the 1-D mesh of a Hertz cylinder's arc then skipped 10 mm between two nodes, a chord in
    place of the arc, with badly shaped elements along it).  Each boundary edge a-b (an edge of
    one cell) gets the quadrilateral a, b, b + d n, a + d n, n its outward normal, d = `depth`
    times its length (covers the bulge for R > h / (8 depth)), with the sizes of a and b.
    Returns [(corner coordinates 4 x 2, sizes 4)].  `cells` lists the corner indices (0-based)
    of each cell, counter-clockwise or clockwise."""
    count, owner = {}, {}
    for ci, c in enumerate(cells):
        k = len(c)
        for i in range(k):
            a, b = int(c[i]), int(c[(i + 1) % k])
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
            owner[key] = (ci, a, b)
    out = []
    for key, n in count.items():
        if n != 1:
            continue
        ci, a, b = owner[key]
        c = np.asarray(cells[ci])
        centre = xy[c].mean(axis=0)
        t = xy[b] - xy[a]
        length = float(np.hypot(t[0], t[1]))
        if length == 0.0:
            continue
        normal = np.array([t[1], -t[0]]) / length
        if normal @ (0.5 * (xy[a] + xy[b]) - centre) < 0.0:
            normal = -normal
        d = depth * length * normal
        out.append((np.array([xy[a], xy[b], xy[b] + d, xy[a] + d]),
                    np.array([nodal[a], nodal[b], nodal[b], nodal[a]])))
    return out


def _components(ncells, cells):
    """Component index of every cell: cells that share a node are in one component (a body)."""
    parent = {}

    def find(a):
        while parent.setdefault(a, a) != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a
    for c in cells:
        r0 = find(int(c[0]))
        for v in c[1:]:
            r1 = find(int(v))
            if r1 != r0:
                parent[r1] = r0
    roots = {}
    return np.array([roots.setdefault(find(int(c[0])), len(roots)) for c in cells], dtype=int)


def msh_bodies(path):
    """The bodies of a .msh file (format 4.1, ASCII): [{"surfaces", "curves", "points": gmsh
    entity tags, "nodes": node count, "centre": mean of the nodes}], one per set of 2-D
    elements connected through shared nodes."""
    bound = {1: {}, 2: {}}
    block_cells, block_surface = [], []
    with open(path) as f:
        for line in f:
            tag = line.strip()
            if tag == "$Entities":
                npt, ncu, nsu, _nvo = (int(v) for v in f.readline().split())
                for _ in range(npt):
                    f.readline()
                for dim, n in ((1, ncu), (2, nsu)):
                    for _ in range(n):
                        v = f.readline().split()
                        nphys = int(v[7])
                        nb = int(v[8 + nphys])
                        bound[dim][int(v[0])] = [abs(int(t)) for t in v[9 + nphys:9 + nphys + nb]]
            elif tag == "$Elements":
                nblocks = int(f.readline().split()[0])
                for _ in range(nblocks):
                    dim, ent, ety, n = (int(v) for v in f.readline().split())
                    rows = [f.readline().split() for _ in range(n)]
                    if dim == 2 and ety in CORNERS:
                        for v in rows:
                            block_cells.append([int(t) for t in v[1:1 + CORNERS[ety]]])
                            block_surface.append(ent)
    xy, _ = read_msh2d(path)
    comp = _components(len(block_cells), block_cells)
    out = []
    for k in range(int(comp.max()) + 1 if len(comp) else 0):
        sel = np.where(comp == k)[0]
        surfaces = sorted({block_surface[i] for i in sel})
        curves = sorted({c for s in surfaces for c in bound[2].get(s, [])})
        points = sorted({p for c in curves for p in bound[1].get(c, [])})
        nodes = sorted({t for i in sel for t in block_cells[i]})
        out.append({"surfaces": surfaces, "curves": curves, "points": points, "nodes": len(nodes),
                    "centre": np.mean([xy[t] for t in nodes], axis=0)})
    return out


def match_bodies(xy, cells, bodies):
    """The body of `bodies` (msh_bodies of the mesh the result came from) of every cell of the
    result's mesh (xy, cells: corner indices), matched by the corner-node count and the centre
    of each connected set of cells; None when they do not match one to one."""
    comp = _components(len(cells), cells)
    ncomp = int(comp.max()) + 1 if len(comp) else 0
    if ncomp != len(bodies):
        return None
    size = float(np.ptp(xy, axis=0).max()) or 1.0
    which = {}
    for k in range(ncomp):
        nodes = np.unique(np.concatenate([cells[i] for i in np.where(comp == k)[0]]))
        centre = xy[nodes].mean(axis=0)
        cand = [b for b, body in enumerate(bodies) if body["nodes"] == len(nodes)
                and np.hypot(*(body["centre"] - centre)) <= 1e-6 * size]
        if len(cand) != 1 or cand[0] in which.values():
            return None
        which[k] = cand[0]
    return np.array([which[c] for c in comp], dtype=int)


# ------------------------------------------------------------------ a layer along contact curves
# A boundary layer of quadrilaterals along a curved contact (docs/adaptivity.md, "A layer along
# the contact"): gmsh's BoundaryLayer field builds a column of nodes normal to the curve at every
# node of its 1-D mesh, the first at the distance hWall, the next ones growing by LAYER_RATIO
# until LAYER_DEPTH times the smallest hWall; hWall is given at the curves' end points (the
# field's SizesList) and gmsh 4.8 interpolates it along a curve quadratically between them.
# Where the layer ends on a point whose next curve continues the layer's curve (a tangent or
# collinear continuation) gmsh takes that curve's nodes for the end column, which lies along
# the boundary and makes quadrilaterals near 180 degrees; the layer is therefore carried on
# along such continuations to a corner (a turn of at least LAYER_CORNER degrees).
LAYER_FIRST = 1.0       # the first layer's thickness over the size of the view at the point
LAYER_RATIO = 1.15      # growth of the layers' thickness
LAYER_DEPTH = 4.0       # the layer's depth over the smallest first thickness of its curves
LAYER_CORNER = 45.0     # a turn of the boundary [deg] that ends the layer


def msh_topology(path):
    """The geometry of a .msh file (format 4.1, ASCII) the layer needs: {"points": {tag: xy},
    "curves": {tag: (begin point, end point)}, "curve_nodes": {tag: xy of the curve's inner
    nodes, k x 2}}."""
    points, curves, nodes = {}, {}, {}
    with open(path) as f:
        for line in f:
            tag = line.strip()
            if tag == "$Entities":
                npt, ncu, _nsu, _nvo = (int(v) for v in f.readline().split())
                for _ in range(npt):
                    v = f.readline().split()
                    points[int(v[0])] = np.array([float(v[1]), float(v[2])])
                for _ in range(ncu):
                    v = f.readline().split()
                    nphys = int(v[7])
                    nb = int(v[8 + nphys])
                    b = [abs(int(t)) for t in v[9 + nphys:9 + nphys + nb]]
                    curves[int(v[0])] = tuple(b)
            elif tag == "$Nodes":
                nblocks = int(f.readline().split()[0])
                for _ in range(nblocks):
                    dim, ent, _param, n = (int(v) for v in f.readline().split())
                    for _ in range(n):
                        f.readline()
                    xy = np.array([[float(c) for c in f.readline().split()[:2]] for _ in range(n)])
                    if dim == 1:
                        nodes[ent] = xy.reshape(-1, 2)
                break
    return {"points": points, "curves": curves, "curve_nodes": nodes}


def _leaving(topo, curve, point):
    """The unit direction in which `curve` leaves `point` (towards its nearest inner node, or its
    other end point when it has no inner node)."""
    p = topo["points"][point]
    inner = topo["curve_nodes"].get(curve)
    if inner is not None and len(inner):
        q = inner[int(np.argmin(np.hypot(*(inner - p).T)))]
    else:
        ends = [e for e in topo["curves"][curve] if e != point]
        q = topo["points"][ends[0]] if ends else p
    d = q - p
    n = float(np.hypot(d[0], d[1]))
    return d / n if n > 0.0 else d


def layer_chain(topo, seeds, body_curves, corner=LAYER_CORNER):
    """The curves of a layer: `seeds` (the contact curves) and, from each end of the chain they
    form, the body's next curve as long as it continues the last one within `corner` degrees
    (a turn below it: the layer's end column would lie along the boundary).  Returns (curves,
    their end points), sorted."""
    curves = set(seeds)
    body_curves = set(body_curves)
    grown = True
    while grown:
        grown = False
        count = {}
        for c in curves:
            for p in topo["curves"].get(c, ()):
                count[p] = count.get(p, 0) + 1
        for p, n in count.items():
            if n != 1:
                continue                                # inside the chain
            last = [c for c in curves if p in topo["curves"].get(c, ())][0]
            nxt = [c for c in body_curves - curves if p in topo["curves"].get(c, ())]
            if len(nxt) != 1:
                continue
            # the turn between the two curves at p: 0 for a straight continuation
            turn = 180.0 - math.degrees(math.acos(float(np.clip(_leaving(topo, last, p)
                                                                @ _leaving(topo, nxt[0], p), -1.0, 1.0))))
            if turn < corner:
                curves.add(nxt[0])
                grown = True
                break
    points = sorted({p for c in curves for p in topo["curves"].get(c, ())})
    return sorted(curves), points


def layer_lines(layers, first_field=99100):
    """The .geo lines of gmsh BoundaryLayer fields, one per layer {"curves", "sizes": {point:
    first thickness}, "depth"}, each made a boundary layer of the mesh."""
    lines = []
    for k, lay in enumerate(layers):
        f = first_field + k
        sizes = ", ".join("%d, %.8g" % (p, h) for p, h in sorted(lay["sizes"].items()))
        lines += ["Field[%d] = BoundaryLayer;" % f,
                  "Field[%d].CurvesList = {%s};" % (f, ", ".join(map(str, lay["curves"]))),
                  "Field[%d].SizesList = {%s};" % (f, sizes),
                  "Field[%d].Size = %.8g;" % (f, min(lay["sizes"].values())),
                  "Field[%d].Ratio = %.8g;" % (f, lay.get("ratio", LAYER_RATIO)),
                  "Field[%d].Thickness = %.8g;" % (f, lay["depth"]),
                  "Field[%d].Quads = 1;" % f,
                  "BoundaryLayer Field = %d;" % f]
    return lines
