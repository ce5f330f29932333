"""Write Kontakt2D decks for structured multi-block meshes.

A small library used by the scripts that generate the example and test decks
(docs/deck-format.md is the format).  Each body is a set of rectangular blocks
on grid lines; nodes are shared inside a body, never between bodies, so two
bodies that touch get coincident node pairs for the contact surfaces.

    from k2d.deck import Deck
    d = Deck("title", ntype=1, nnode=4)
    a = d.block("A", xs=[0, 5, 10], ys=[0, 5, 10], mat=1)
    ...
    d.write("case.dat")
"""
import math

__all__ = ["BLOCKS", "SOLVERS", "keyword", "f10", "fine_then_graded", "graded", "Deck", "circle_y"]

FMT_I = "%5d"
# the deck's blocks, in their order (src/io/deck_blocks.f90, docs/deck-format.md)
BLOCKS = ("TITLE", "CONTROL", "OPTIONS", "MESH", "ELEMENTS", "NODES", "RESTRAINTS", "TIES", "MATERIALS",
          "LOADS", "CONTACT", "INCREMENTS", "END")
# CONTROL's SOLVER field (columns 36-45; blank: AUTO) and the command line's -s, in lower case there
SOLVERS = ("SKYLINE", "UMFPACK", "MUMPS", "DENSE", "AUTO")


def keyword(line):
    """The keyword of a card: its first ten columns, upper case, without a comment."""
    return line[:10].split("#")[0].strip().upper()


def f10(x):
    """A real in a 10-column field, as precise as fits."""
    if x == 0:
        return "%10s" % "0.0"
    for fmt in ("%10.6f", "%10.5f", "%10.4f", "%10.3f"):
        s = fmt % x
        if len(s) <= 10 and abs(float(s) - x) <= 1e-9 * max(1.0, abs(x)):
            return s
    s = "%10.4e" % x
    if len(s) <= 10 and abs(float(s) - x) <= 1e-12 * abs(x):
        return s
    # not exact in 10 columns: the most precise fixed or exponent form that fits
    best = None
    for s in ["%.*f" % (k, x) for k in range(8, -1, -1)] + ["%.*e" % (k, x) for k in range(5, 0, -1)]:
        if len(s) <= 10 and (best is None or abs(float(s) - x) < abs(float(best) - x)):
            best = s
    return "%10s" % best


def fine_then_graded(a, b, h, s1, q):
    """Grid lines from a to b: uniform cells of size about h up to a + s1, then
    cells growing geometrically by about q per cell up to b (the number of
    growing cells is chosen so that the first one is about h)."""
    n1 = max(1, int(round(s1 / h)))
    x1 = a + n1 * h
    lines = [a + (x1 - a) * k / n1 for k in range(n1 + 1)]
    if b - x1 <= h * 1e-9:
        lines[-1] = b
        return lines
    # n growing cells of ratio q starting near h: h (q^n - 1)/(q - 1) = b - x1
    n2 = max(1, int(round(math.log(1.0 + (b - x1) * (q - 1.0) / h) / math.log(q))))
    # exact end: solve h q^0 + ... with the ratio fixed, scale the cells
    cells = [q ** k for k in range(n2)]
    scale = (b - x1) / sum(cells)
    x = x1
    for c in cells[:-1]:
        x += c * scale
        lines.append(x)
    lines.append(b)
    return lines


def graded(a, b, n, ratio=1.0):
    """n cells from a to b, last cell / first cell = ratio."""
    if n == 1 or abs(ratio - 1.0) < 1e-12:
        return [a + (b - a) * k / n for k in range(n + 1)]
    q = ratio ** (1.0 / (n - 1))
    s = [(q ** k - 1.0) / (q ** n - 1.0) for k in range(n + 1)]
    return [a + (b - a) * t for t in s]


class Deck:
    def __init__(self, title, ntype, nnode, solver="SKYLINE"):
        self.title = title
        self.ntype = ntype
        self.nnode = nnode
        self.solver = solver
        self.nodes = []          # (x, y, body)
        self.index = {}          # (body, x, y) -> node number
        self.elements = []       # (mat, [nodes], body)
        self.materials = {}      # mat -> (E, nu, thick)
        self.fixes = {}          # node -> [code, ux, uy, case]
        self.ties = []           # (code, [nodes])
        self.edge_loads = []     # card strings
        self.point_loads = []
        self.contact = []        # raw lines of the CONTACT block
        self.increments = []     # (nstep, [factors])
        self.options = []
        self.comments = []

    # ---------------------------------------------------------------- mesh
    def node(self, body, x, y):
        key = (body, round(x, 9), round(y, 9))
        if key not in self.index:
            self.nodes.append((x, y, body))
            self.index[key] = len(self.nodes)
        return self.index[key]

    def find(self, body, x, y):
        return self.index.get((body, round(x, 9), round(y, 9)))

    def reference_node(self, x, y, body="RIGID"):
        """A node of no element: the reference node of a rigid body."""
        self.nodes.append((x, y, body))
        self.index[(body + "#%d" % len(self.nodes), round(x, 9), round(y, 9))] = len(self.nodes)
        return len(self.nodes)

    def profile(self, links=()):
        """Skyline profile (stored entries, both dofs per node) of the node numbering."""
        low = list(range(len(self.nodes) + 1))
        for mat, c, b in self.elements:
            m = min(c)
            for i in c:
                low[i] = min(low[i], m)
        for i, j in links:
            low[max(i, j)] = min(low[max(i, j)], min(i, j))
        return sum(2 * (i - low[i]) + 2 for i in range(1, len(self.nodes) + 1))

    def block(self, body, xs, ys, mat, mapping=None):
        """Elements on the grid xs x ys (lists of grid lines); mapping(x, y) -> (x', y')
        may curve the block (the grid is in parameter space then)."""
        quad = self.nnode >= 8
        mp = mapping or (lambda x, y: (x, y))

        def nd(x, y):
            X, Y = mp(x, y)
            return self.node(body, X, Y)

        for j in range(len(ys) - 1):
            for i in range(len(xs) - 1):
                xa, xb, ya, yb = xs[i], xs[i + 1], ys[j], ys[j + 1]
                c = [nd(xa, ya), nd(xb, ya), nd(xb, yb), nd(xa, yb)]
                if quad:
                    xm, ym = 0.5 * (xa + xb), 0.5 * (ya + yb)
                    c += [nd(xm, ya), nd(xb, ym), nd(xm, yb), nd(xa, ym)]
                    if self.nnode == 9:
                        c.append(nd(xm, ym))
                if mapping is not None and self._signed_area(c[:4]) < 0.0:
                    # the mapping mirrors the block: number the corners anticlockwise again
                    c = self._reverse(c)
                if quad:
                    self.elements.append((mat, c, body))
                elif self.nnode == 3:
                    self.elements.append((mat, [c[0], c[1], c[2]], body))
                    self.elements.append((mat, [c[0], c[2], c[3]], body))
                else:
                    self.elements.append((mat, c, body))

    def _signed_area(self, corners):
        pts = [self.nodes[k - 1][:2] for k in corners]
        return 0.5 * sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1]
                         for i in range(len(pts)))

    @staticmethod
    def _reverse(c):
        """The same quadrilateral numbered the other way round (corners 1 4 3 2, midsides 8 7 6 5)."""
        out = [c[0], c[3], c[2], c[1]]
        if len(c) >= 8:
            out += [c[7], c[6], c[5], c[4]]
        if len(c) == 9:
            out.append(c[8])
        return out

    def renumber(self, links=()):
        """Renumber the nodes by reverse Cuthill-McKee over the element graph plus `links`
        (pairs of nodes coupled otherwise, e.g. contact pairs), so that the skyline
        solver's profile is small.  Call it after the mesh is complete and before any
        node number is used (restraints, loads, surfaces)."""
        if self.fixes or self.ties or self.edge_loads or self.point_loads or self.contact:
            raise RuntimeError("renumber() must come before restraints, loads and contact cards")
        n = len(self.nodes)
        adj = [set() for _ in range(n + 1)]
        for mat, c, b in self.elements:
            for a in c:
                adj[a].update(c)
        for a, b in links:
            adj[a].add(b)
            adj[b].add(a)
        for k in range(1, n + 1):
            adj[k].discard(k)
        deg = [len(a) for a in adj]
        seen = [False] * (n + 1)
        order = []
        while len(order) < n:
            # start each component at a node of least degree (a pseudo-peripheral guess)
            start = min((k for k in range(1, n + 1) if not seen[k]), key=lambda k: deg[k])
            for _ in range(3):     # a few sweeps towards a peripheral node
                level = {start: 0}
                frontier = [start]
                while frontier:
                    nxt = []
                    for a in frontier:
                        for b in adj[a]:
                            if b not in level and not seen[b]:
                                level[b] = level[a] + 1
                                nxt.append(b)
                    frontier = nxt
                far = max(level.values())
                cand = min((k for k, lv in level.items() if lv == far), key=lambda k: deg[k])
                if cand == start:
                    break
                start = cand
            seen[start] = True
            queue = [start]
            head = 0
            while head < len(queue):
                a = queue[head]
                head += 1
                for b in sorted((b for b in adj[a] if not seen[b]), key=lambda k: deg[k]):
                    seen[b] = True
                    queue.append(b)
            order += queue
        order.reverse()
        new = {old: k for k, old in enumerate(order, 1)}
        self.nodes = [self.nodes[old - 1] for old in order]
        self.index = {key: new[v] for key, v in self.index.items()}
        self.elements = [(mat, [new[a] for a in c], b) for mat, c, b in self.elements]
        return new

    def grade_towards(self, centre, radius, factor):
        """Move the nodes within `radius` of `centre` towards it, so that the elements there
        shrink smoothly to `factor` times their size at the centre (0 < factor <= 1) and keep
        their size at the radius: r -> radius * psi(r / radius), psi(t) = f t + 2 (1 - f) t^2
        - (1 - f) t^3, with psi(0) = 0, psi'(0) = f, psi(1) = 1, psi'(1) = 1, psi' > 0.

        The map is radial, so straight lines through the centre stay straight (a contact
        line and a body edge meeting at a corner keep their nodes on them), coincident
        nodes of two bodies stay coincident, and nodes beyond the radius do not move.
        Call it after the mesh is complete; restraints, loads and surfaces refer to node
        numbers and are not affected."""
        if not 0.0 < factor <= 1.0:
            raise ValueError("grade_towards: factor must lie in (0, 1]")
        cx, cy = centre
        moved = []
        for x, y, b in self.nodes:
            r = math.hypot(x - cx, y - cy)
            if 0.0 < r < radius:
                t = r / radius
                s = factor + 2.0 * (1.0 - factor) * t - (1.0 - factor) * t * t    # psi(t) / t
                x, y = cx + (x - cx) * s, cy + (y - cy) * s
            moved.append((x, y, b))
        self.nodes = moved
        # the coordinate index follows the nodes (reference nodes keep their own keys)
        self.index = {(key if "#" in key[0] else
                       (key[0], round(self.nodes[k - 1][0], 9), round(self.nodes[k - 1][1], 9))): k
                      for key, k in self.index.items()}

    def nodes_where(self, body, pred):
        """Node numbers of `body` whose coordinates satisfy pred(x, y), sorted by x then y."""
        sel = [(x, y, k) for k, (x, y, b) in enumerate(self.nodes, 1) if b == body and pred(x, y)]
        return [k for x, y, k in sorted(sel)]

    def edges_where(self, body, pred):
        """Element edges of `body` whose nodes all satisfy pred: (elem, [nodes along the edge])."""
        out = []
        for e, (mat, c, b) in enumerate(self.elements, 1):
            if b != body:
                continue
            nc = 3 if self.nnode == 3 else 4
            for k in range(nc):
                a, bb = c[k], c[(k + 1) % nc]
                ids = [a, bb] if self.nnode < 8 else [a, c[nc + k], bb]
                if all(pred(*self.nodes[i - 1][:2]) for i in ids):
                    out.append((e, ids))
        return out

    # ---------------------------------------------------------------- data
    def material(self, mat, E, nu, thick=1.0):
        self.materials[mat] = (E, nu, thick)

    def fix(self, node, code, ux=None, uy=None, case=None):
        old = self.fixes.get(node)
        if old:
            c = "%d%d" % (int(old[0][0]) | int(code[0]), int(old[0][1]) | int(code[1]))
            self.fixes[node] = [c, ux if ux is not None else old[1], uy if uy is not None else old[2], case or old[3]]
        else:
            self.fixes[node] = [code, ux, uy, case]

    def edge_pressure(self, body, pred, pn, pt=0.0, case=None):
        """Uniform pressure pn (compressive) and traction pt on the edges selected."""
        for e, ids in self.edges_where(body, pred):
            s = FMT_I % e + "".join(FMT_I % i for i in ids) + (" " * 5 if len(ids) == 2 else "")
            pad = [None] if len(ids) == 2 else []
            vals = [pn] * len(ids) + pad + [pt] * len(ids) + pad
            s += "".join(" " * 10 if v is None else f10(v) for v in vals)
            if case:
                s += FMT_I % case
            self.edge_loads.append(s)

    def point_load(self, node, fx, fy, case=None):
        self.point_loads.append(FMT_I % node + f10(fx) + f10(fy) + (FMT_I % case if case else ""))

    def tie(self, code, nodes):
        for k in range(0, len(nodes) - 1, 14):
            chunk = [nodes[0]] + nodes[1 + k:1 + k + 14]
            self.ties.append("%5s" % code + "".join(FMT_I % n for n in chunk))

    def node_list_cards(self, nodes):
        return ["".join(FMT_I % n for n in nodes[i:i + 16]) for i in range(0, len(nodes), 16)]

    # ---------------------------------------------------------------- output
    def write(self, path):
        L = []
        for c in self.comments:
            L.append("# " + c)
        L += ["TITLE", self.title, "CONTROL",
              "#NPOI NELE NVFI NTYP NNOD NMAT NGAU SOLVER",
              "%5d%5d%5d%5d%5d%5d%5d%10s" % (len(self.nodes), len(self.elements), len(self.fixes), self.ntype,
                                            self.nnode, len(self.materials), 0, self.solver)]
        if self.options:
            L += ["OPTIONS"] + self.options
        L.append("ELEMENTS")
        for k, (mat, c, b) in enumerate(self.elements, 1):
            L.append(FMT_I % k + FMT_I % mat + "".join(FMT_I % n for n in c) + "   # body " + b)
        L.append("NODES")
        for k, (x, y, b) in enumerate(self.nodes, 1):
            L.append(FMT_I % k + f10(x) + f10(y))
        L.append("RESTRAINTS")
        for n in sorted(self.fixes):
            code, ux, uy, case = self.fixes[n]
            s = FMT_I % n + "%5s" % code
            if ux is not None or uy is not None or case:
                s += (f10(ux) if ux is not None else " " * 10) + (f10(uy) if uy is not None else " " * 10)
            if case:
                s += FMT_I % case
            L.append(s.rstrip())
        if self.ties:
            L += ["TIES"] + self.ties
        L.append("MATERIALS")
        for m in sorted(self.materials):
            E, nu, t = self.materials[m]
            L.append(FMT_I % m + f10(E) + f10(nu) + f10(t))
        if self.point_loads or self.edge_loads:
            L.append("LOADS")
            if self.point_loads:
                L += ["POINT"] + self.point_loads
            if self.edge_loads:
                L += ["EDGE"] + [s.rstrip() for s in self.edge_loads]
        if self.contact:
            L += ["CONTACT"] + self.contact
        if self.increments:
            L.append("INCREMENTS")
            for n, fs in self.increments:
                L.append((FMT_I % n + "".join(" " * 10 if f is None else f10(f) for f in fs)).rstrip())
        L.append("END")
        with open(path, "w") as f:
            f.write("\n".join(L) + "\n")


def circle_y(r, radius):
    """Height above the lowest point of a circle of the given radius at distance r from its axis."""
    return radius - math.sqrt(max(radius * radius - r * r, 0.0))
