"""Uniform refinement of a card deck (ELEMENTS and NODES blocks): every element split into four.

    from k2d.refine import read_card_deck, refine_deck, RefineError
    deck = read_card_deck("case.dat")        # the cards, by block (RefineError if unsupported)
    text = refine_deck(deck)                 # the deck with every element split into four
    deck.materials                           # {mat: (E, nu, thick)}; deck.ntype, deck.nnode

The split (docs/adaptivity.md):

* T3 -> 4 T3 (the edges' midpoints); Q4 -> 4 Q4 (midpoints and the centre of the bilinear map);
  Q8 / Q9 -> 4 Q8 / Q9 whose nodes sit at the parent's isoparametric points xi, eta in
  {-1, -1/2, 0, 1/2, 1}, so curved (quadratic) edges stay on the parent's curve.
* Old nodes keep their numbers, new nodes follow (NPOIN + 1, ...); element k becomes elements
  4k - 3 .. 4k.  A node shared by two elements is created once (keyed by the edge's corner nodes
  and its position along the edge), never shared between bodies that only touch.
* A new node on a *boundary* edge (an edge of one element only) is restrained in a direction
  when both its neighbours along the edge are, with the same load case; a prescribed value is
  interpolated linearly between them.  It joins a contact SURFACE when both neighbours are on it.
* POINT loads stay on their nodes; an EDGE load is split into the two child edges, its values
  interpolated with the edge's shape functions; BODY loads, materials, options, the contact
  laws and the load history are copied.
* TIES are copied; a new node on a boundary edge between two nodes tied to the same node in a
  direction is tied to it in that direction too (a rigid plate's face stays rigid).
* Not supported (RefineError names it): a MESH block (refine the .geo instead), contact
  PAIRS cards (their areas and gaps belong to the coarse mesh), more than 99999 nodes or
  elements (I5 fields).
"""
from .deck import f10

KEYWORDS = ("TITLE", "CONTROL", "OPTIONS", "MESH", "ELEMENTS", "NODES", "RESTRAINTS", "TIES",
            "MATERIALS", "LOADS", "CONTACT", "INCREMENTS", "END")
I5 = "%5d"


class RefineError(Exception):
    """A deck this module cannot refine, or a card it cannot read; the message names file and line."""


def _field(line, a, b):
    return line[a - 1:b].strip()


def _number(line, a, b, where, name, default, convert, what):
    """The field in columns a-b converted by `convert` ('what' names it in the message)."""
    s = _field(line, a, b)
    if not s:
        if default is None:
            raise RefineError("%s: field %s (columns %d-%d) is blank" % (where, name, a, b))
        return default
    try:
        return convert(s)
    except ValueError:
        raise RefineError("%s: field %s (columns %d-%d): expected %s, found %r" % (where, name, a, b, what, s))


def _int(line, a, b, where, name, default=None):
    return _number(line, a, b, where, name, default, int, "an integer")


def _real(line, a, b, where, name, default=None):
    return _number(line, a, b, where, name, default,
                   lambda s: float(s.replace("D", "e").replace("d", "e")), "a real")


class CardDeck:
    """The cards of a deck with ELEMENTS and NODES blocks, as far as refinement needs them."""

    def __init__(self, path):
        self.path = path
        self.header = []          # comment lines before TITLE
        self.title = ""
        self.control = ""         # the CONTROL data card
        self.ntype = self.nnode = 0
        self.options = []         # raw cards of OPTIONS
        self.elements = {}        # k -> (mat, [nodes])
        self.nodes = {}           # k -> (x, y)
        self.restraints = {}      # node -> [code "xy", ux, uy, case]
        self.ties = []            # (code "xy", [first node, nodes tied to it])
        self.materials = {}       # mat -> (E, nu, thick)
        self.material_cards = []
        self.point = []           # raw POINT cards
        self.edge = []            # (elem, [nodes], [pn...], [pt...], case)
        self.body = []            # raw BODY cards
        self.contact = []         # ("card", raw) or ("surface", raw keyword card, [nodes]) or ("data", raw)
        self.increments = []      # raw cards
        self.has_mesh = False


def read_card_deck(path):
    """Read the deck at `path` (docs/deck-format.md) into a CardDeck; RefineError for a deck the
    splitter does not support, naming the file, the line and what is unsupported."""
    d = CardDeck(path)
    block, sub, control_where = None, None, path
    expect_title = False
    surface = None
    with open(path) as f:
        lines = f.read().splitlines()
    for ln, raw in enumerate(lines, 1):
        where = "%s:%d" % (path, ln)
        if expect_title:
            d.title = raw
            expect_title = False
            continue
        line = raw.split("#", 1)[0].rstrip()
        if not line.strip():
            if block is None and raw.strip().startswith("#"):
                d.header.append(raw)
            continue
        word = line.split()[0].upper()
        is_kw = line.lstrip()[0].isalpha()
        if is_kw and word in KEYWORDS and (block != "CONTACT" or word in ("INCREMENTS", "END")):
            block, sub, surface = word, None, None
            if word == "TITLE":
                expect_title = True
            elif word == "MESH":
                raise RefineError("%s: the deck has a MESH block: refine its .geo (tools/adapt.py does, "
                                  "with gmsh) rather than the cards" % where)
            elif word == "END":
                break
            continue
        if block == "CONTROL":
            d.control = line
            d.ntype = _int(line, 16, 20, where, "NTYPE")
            d.nnode = _int(line, 21, 25, where, "NNODE", 0)
            control_where = where
        elif block == "OPTIONS":
            d.options.append(line)
        elif block == "ELEMENTS":
            if d.nnode not in (3, 4, 8, 9):
                raise RefineError("%s: NNODE = %d: expected 3, 4, 8 or 9" % (control_where, d.nnode))
            k = _int(line, 1, 5, where, "IELEM")
            mat = _int(line, 6, 10, where, "MATNO")
            c = [_int(line, 11 + 5 * i, 15 + 5 * i, where, "NODE%d" % (i + 1)) for i in range(d.nnode)]
            d.elements[k] = (mat, c)
        elif block == "NODES":
            k = _int(line, 1, 5, where, "IPOIN")
            d.nodes[k] = (_real(line, 6, 15, where, "X"), _real(line, 16, 25, where, "Y"))
        elif block == "RESTRAINTS":
            if word == "GROUP":
                raise RefineError("%s: GROUP restraints belong to a MESH deck" % where)
            k = _int(line, 1, 5, where, "NODE")
            code = _field(line, 6, 10).zfill(2)
            d.restraints[k] = [code, _real(line, 11, 20, where, "UX", 0.0), _real(line, 21, 30, where, "UY", 0.0),
                               _int(line, 31, 35, where, "CASE", 1)]
        elif block == "TIES":
            code = _field(line, 1, 5).zfill(2)
            ids = [_int(line, 6 + 5 * i, 10 + 5 * i, where, "N%d" % (i + 1)) for i in range(15)
                   if _field(line, 6 + 5 * i, 10 + 5 * i)]
            if code not in ("10", "01", "11") or len(ids) < 2:
                raise RefineError("%s: a TIES card needs CODE 10, 01 or 11 and at least two nodes" % where)
            d.ties.append((code, ids))
        elif block == "MATERIALS":
            m = _int(line, 1, 5, where, "MATNO")
            d.materials[m] = (_real(line, 6, 15, where, "E"), _real(line, 16, 25, where, "NU"),
                              _real(line, 26, 35, where, "THICK", 1.0))
            d.material_cards.append(line)
        elif block == "LOADS":
            if is_kw and word in ("POINT", "EDGE", "BODY"):
                sub = word
                continue
            if word == "GROUP":
                raise RefineError("%s: GROUP loads belong to a MESH deck" % where)
            if sub == "POINT":
                d.point.append(line)
            elif sub == "BODY":
                d.body.append(line)
            elif sub == "EDGE":
                e = _int(line, 1, 5, where, "IELEM")
                n3 = _field(line, 16, 20)
                nn = 3 if n3 else 2
                ids = [_int(line, 6 + 5 * i, 10 + 5 * i, where, "N%d" % (i + 1)) for i in range(nn)]
                pn = [_real(line, 21 + 10 * i, 30 + 10 * i, where, "PN%d" % (i + 1), 0.0) for i in range(nn)]
                pt = [_real(line, 51 + 10 * i, 60 + 10 * i, where, "PT%d" % (i + 1), 0.0) for i in range(nn)]
                d.edge.append((e, ids, pn, pt, _int(line, 81, 85, where, "CASE", 1), where))
            else:
                raise RefineError("%s: a LOADS card before POINT, EDGE or BODY" % where)
        elif block == "CONTACT":
            if is_kw:
                surface = None
                if word == "PAIRS":
                    raise RefineError("%s: contact PAIRS cards are not supported by the uniform refinement "
                                      "(their gaps and areas belong to the coarse mesh); give SURFACE A and B" % where)
                if word == "SURFACE" and not _field(line, 21, 60):
                    surface = ("surface", line, [])
                    d.contact.append(surface)
                else:
                    d.contact.append(("card", line))
            elif surface is not None:
                for i in range(16):
                    s = _field(line, 1 + 5 * i, 5 + 5 * i)
                    if s:
                        surface[2].append(_int(line, 1 + 5 * i, 5 + 5 * i, where, "node"))
            else:
                d.contact.append(("data", line))      # the vertices of a RIGID POLYLINE
        elif block == "INCREMENTS":
            d.increments.append(line)
    if not d.elements or not d.nodes:
        raise RefineError("%s: no ELEMENTS and NODES blocks (a card deck is needed)" % path)
    return d


# ------------------------------------------------------------------------------ shape functions
def _shape(nnode, xi, eta):
    if nnode == 4:
        return [0.25 * (1 - xi) * (1 - eta), 0.25 * (1 + xi) * (1 - eta),
                0.25 * (1 + xi) * (1 + eta), 0.25 * (1 - xi) * (1 + eta)]
    if nnode == 8:
        c = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
        n = [0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1) for a, b in c]
        n += [0.5 * (1 - xi * xi) * (1 - eta), 0.5 * (1 + xi) * (1 - eta * eta),
              0.5 * (1 - xi * xi) * (1 + eta), 0.5 * (1 - xi) * (1 - eta * eta)]
        return n
    # Q9: products of the 1-D quadratic Lagrange functions
    def lag1d(s):
        return (0.5 * s * (s - 1), 1 - s * s, 0.5 * s * (s + 1))
    lx, ly = lag1d(xi), lag1d(eta)
    ij = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)]
    return [lx[i] * ly[j] for i, j in ij]


def _edge_values(vals, t):
    """A value along an edge at t in [0, 1] from its node values (2 linear, 3 quadratic)."""
    if len(vals) == 2:
        return (1 - t) * vals[0] + t * vals[1]
    s = 2 * t - 1
    return 0.5 * s * (s - 1) * vals[0] + (1 - s * s) * vals[1] + 0.5 * s * (s + 1) * vals[2]


def refine(deck):
    """Split every element of the CardDeck into four; returns (nodes, elements, refined edges),
    nodes {k: (x, y)}, elements [(mat, nodes)] (element k -> 4k-3..4k), refined edges
    {(a, b): [nodes from corner a to corner b]} for every parent edge in both directions."""
    nodes = dict(deck.nodes)
    nnode = deck.nnode
    quad = nnode in (8, 9)
    n = 5 if quad else 3                    # lattice points per direction
    nxt = [max(nodes) + 1]
    keyed = {}

    def new_node(key, xy):
        if key not in keyed:
            keyed[key] = nxt[0]
            nodes[nxt[0]] = xy
            nxt[0] += 1
        return keyed[key]

    def edge_point(a, b, k, mid, xy):
        """Point k (0..n-1) of the lattice along the parent edge from corner a to corner b."""
        if k == 0:
            return a
        if k == n - 1:
            return b
        if mid is not None and 2 * k == n - 1:
            return mid
        lo, hi, kk = (a, b, k) if a < b else (b, a, n - 1 - k)
        return new_node(("E", lo, hi, kk), xy)

    elements, edges = [], {}
    for e in sorted(deck.elements):
        mat, c = deck.elements[e]
        xy = [nodes[i] for i in c]
        if nnode == 3:
            m = []
            for k in range(3):
                a, b = c[k], c[(k + 1) % 3]
                p = (0.5 * (xy[k][0] + xy[(k + 1) % 3][0]), 0.5 * (xy[k][1] + xy[(k + 1) % 3][1]))
                m.append(edge_point(a, b, 1, None, p))
                edges[(a, b)] = [a, m[-1], b]
                edges[(b, a)] = [b, m[-1], a]
            elements += [(mat, [c[0], m[0], m[2]]), (mat, [m[0], c[1], m[1]]),
                         (mat, [m[2], m[1], c[2]]), (mat, [m[0], m[1], m[2]])]
            continue
        grid = {}
        for j in range(n):
            for i in range(n):
                xi, eta = -1 + 2.0 * i / (n - 1), -1 + 2.0 * j / (n - 1)
                N = _shape(nnode, xi, eta)
                p = (sum(N[k] * xy[k][0] for k in range(nnode)), sum(N[k] * xy[k][1] for k in range(nnode)))
                if j == 0:
                    grid[i, j] = edge_point(c[0], c[1], i, c[4] if quad else None, p)
                elif i == n - 1:
                    grid[i, j] = edge_point(c[1], c[2], j, c[5] if quad else None, p)
                elif j == n - 1:
                    grid[i, j] = edge_point(c[2], c[3], n - 1 - i, c[6] if quad else None, p)
                elif i == 0:
                    grid[i, j] = edge_point(c[3], c[0], n - 1 - j, c[7] if quad else None, p)
                elif nnode == 9 and i == j == 2:
                    grid[i, j] = c[8]
                else:
                    grid[i, j] = (("I", e, i, j), p)      # created only if a child uses it (not Q8's centres)
        for key in list(grid):
            if isinstance(grid[key], tuple) and not (nnode == 8 and key[0] % 2 == 1 and key[1] % 2 == 1):
                grid[key] = new_node(*grid[key])
        s = 2 if quad else 1
        for b in range(2):
            for a in range(2):
                i0, j0 = s * a, s * b
                ch = [grid[i0, j0], grid[i0 + s, j0], grid[i0 + s, j0 + s], grid[i0, j0 + s]]
                if quad:
                    ch += [grid[i0 + 1, j0], grid[i0 + 2, j0 + 1], grid[i0 + 1, j0 + 2], grid[i0, j0 + 1]]
                    if nnode == 9:
                        ch.append(grid[i0 + 1, j0 + 1])
                elements.append((mat, ch))
        sides = [[grid[i, 0] for i in range(n)], [grid[n - 1, j] for j in range(n)],
                 [grid[i, n - 1] for i in range(n - 1, -1, -1)], [grid[0, j] for j in range(n - 1, -1, -1)]]
        for side in sides:
            edges[(side[0], side[-1])] = side
            edges[(side[-1], side[0])] = side[::-1]
    return nodes, elements, edges


def boundary_edges(deck):
    """(a, b) corner pairs of the edges that belong to one element only (either direction)."""
    count = {}
    nc = 3 if deck.nnode == 3 else 4
    for mat, c in deck.elements.values():
        for k in range(nc):
            key = frozenset((c[k], c[(k + 1) % nc]))
            count[key] = count.get(key, 0) + 1
    return {tuple(k) for k, v in count.items() if v == 1}


def refine_deck(deck, note=""):
    """The text of the deck with every element split into four (module docstring)."""
    nodes, elements, edges = refine(deck)
    if len(nodes) > 99999 or len(elements) > 99999:
        raise RefineError("%s: the refined mesh has %d nodes and %d elements: more than the I5 fields of a "
                          "card deck hold (99999)" % (deck.path, len(nodes), len(elements)))
    bnd = boundary_edges(deck)
    # new nodes on boundary edges: (node, left neighbour, right neighbour, t between them)
    on_bnd = []
    for a, b in bnd:
        side = edges[(a, b)]
        for k, nd in enumerate(side):
            if nd not in deck.nodes:
                left, right = side[k - 1], side[k + 1]
                on_bnd.append((nd, left, right))
    fixes = {k: list(v) for k, v in deck.restraints.items()}
    for nd, left, right in on_bnd:
        fl, fr = deck.restraints.get(left), deck.restraints.get(right)
        if not fl or not fr or fl[3] != fr[3]:
            continue
        code = "".join("1" if fl[0][i] == "1" and fr[0][i] == "1" else "0" for i in range(2))
        if code == "00":
            continue
        ux = 0.5 * (fl[1] + fr[1]) if code[0] == "1" else 0.0
        uy = 0.5 * (fl[2] + fr[2]) if code[1] == "1" else 0.0
        fixes[nd] = [code, ux, uy, fl[3]]
    # ties: the group (first node) of every tied node in each direction; a new node between two
    # nodes of one group in a direction joins it there (a rigid plate's face stays rigid)
    group = [{}, {}]
    for code, ids in deck.ties:
        for i in range(2):
            if code[i] == "1":
                for n in ids:
                    group[i][n] = ids[0]
    new_ties = {}
    for nd, left, right in on_bnd:
        for i in range(2):
            g = group[i].get(left)
            if g is not None and g == group[i].get(right) and fixes.get(nd, ["00"])[0][i] != "1":
                new_ties.setdefault(g, [set(), set()])[i].add(nd)
    tie_cards = ["%5s" % code + "".join(I5 % n for n in ids) for code, ids in deck.ties]
    for g in sorted(new_ties):
        both = sorted(new_ties[g][0] & new_ties[g][1])
        for code, lst in (("11", both), ("10", sorted(new_ties[g][0] - set(both))),
                          ("01", sorted(new_ties[g][1] - set(both)))):
            for k in range(0, len(lst), 14):
                tie_cards.append("%5s" % code + I5 % g + "".join(I5 % n for n in lst[k:k + 14]))
    # the cards
    L = list(deck.header)
    if note:
        L.append("# " + note)
    L += ["TITLE", deck.title, "CONTROL", "#NPOI NELE NVFI NTYP NNOD NMAT NGAU SOLVER",
          I5 % len(nodes) + I5 % len(elements) + I5 % len(fixes) + deck.control[15:]]
    if deck.options:
        L += ["OPTIONS"] + deck.options
    L.append("ELEMENTS")
    for k, (mat, c) in enumerate(elements, 1):
        L.append(I5 % k + I5 % mat + "".join(I5 % i for i in c))
    L.append("NODES")
    for k in sorted(nodes):
        L.append(I5 % k + f10(nodes[k][0]) + f10(nodes[k][1]))
    L.append("RESTRAINTS")
    for k in sorted(fixes):
        code, ux, uy, case = fixes[k]
        L.append((I5 % k + "%5s" % code + f10(ux) + f10(uy) + I5 % case).rstrip())
    if tie_cards:
        L += ["TIES"] + tie_cards
    L.append("MATERIALS")
    L += deck.material_cards
    if deck.point or deck.edge or deck.body:
        L.append("LOADS")
        if deck.point:
            L += ["POINT"] + deck.point
        if deck.body:
            L += ["BODY"] + deck.body
        if deck.edge:
            L.append("EDGE")
            for e, ids, pn, pt, case, where in deck.edge:
                L += _split_edge_load(deck, e, ids, pn, pt, case, where, edges, elements)
    if deck.contact:
        L.append("CONTACT")
        for item in deck.contact:
            if item[0] == "surface":
                members = set(item[2])
                extra = [nd for nd, left, right in on_bnd if left in members and right in members]
                lst = list(item[2]) + sorted(set(extra))
                L.append(item[1])
                L += ["".join(I5 % v for v in lst[i:i + 16]) for i in range(0, len(lst), 16)]
            else:
                L.append(item[1])
    if deck.increments:
        L += ["INCREMENTS"] + deck.increments
    L.append("END")
    return "\n".join(L) + "\n"


def _split_edge_load(deck, e, ids, pn, pt, case, where, edges, elements):
    """The cards of one EDGE load on the two child edges of the parent edge."""
    if e not in deck.elements:
        raise RefineError("%s: EDGE load on element %d, which the deck does not have" % where)
    a, b = ids[0], ids[-1]
    side = edges.get((a, b))
    if side is None or (len(ids) == 3 and side[len(side) // 2] != ids[1]):
        raise RefineError("%s: EDGE load nodes %s are no edge of element %d" % (where, ids, e))
    n = len(side)
    halves = [side[:n // 2 + 1], side[n // 2:]]
    ts = [[k / (n - 1) for k in range(n // 2 + 1)], [k / (n - 1) for k in range(n // 2, n)]]
    out = []
    for half, t in zip(halves, ts):
        child = None
        for k in range(4 * (e - 1), 4 * e):
            c = elements[k][1]
            nc = 3 if deck.nnode == 3 else 4
            corners = [(c[i], c[(i + 1) % nc]) for i in range(nc)]
            if (half[0], half[-1]) in corners or (half[-1], half[0]) in corners:
                child = k + 1
                break
        if child is None:
            raise RefineError("%s: no child of element %d holds the half edge %s" % (where, e, half))
        vn = [_edge_values(pn, s) for s in t]
        vt = [_edge_values(pt, s) for s in t]
        s = I5 % child + "".join(I5 % i for i in half) + (" " * 5 if len(half) == 2 else "")
        pad = [None] if len(half) == 2 else []
        s += "".join(" " * 10 if v is None else f10(v) for v in vn + pad + vt + pad)
        s += I5 % case
        out.append(s)
    return out


def refine_file(src, dst, note=""):
    """Refine the deck `src` into the file `dst`; returns the CardDeck read."""
    deck = read_card_deck(src)
    text = refine_deck(deck, note)
    with open(dst, "w") as f:
        f.write(text)
    return deck

