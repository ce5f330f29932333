"""The block on a rigid base: the model of the contact patch tests (SPEC §7, V1-V4) and of
the stability decks built on them (tests/decks/contact, tests/decks/stability).

    from k2d.patch import block_on_base, surfaces
    d = block_on_base("title", ntype=1, nnode=4)          # a k2d.deck.Deck
    d.contact = [...] + surfaces(d)                       # SURFACE A / SURFACE B cards
"""
from .deck import Deck

__all__ = ["block_on_base", "surfaces"]


def block_on_base(title, ntype=1, nnode=4, xs=None, nya=4, W=10.0, H=10.0, E=1000.0, nu=0.0,
                  fix_x_line=True):
    """Body A: block [0,W]x[0,H]; body B: layer [0,W]x[-1,0], every node fixed (rigid base)."""
    d = Deck(title, ntype=ntype, nnode=nnode)
    xs = xs or [W * i / 4 for i in range(5)]
    d.block("A", xs, [H * j / nya for j in range(nya + 1)], 1)
    d.block("B", xs, [-1.0, 0.0], 2)
    d.material(1, E, nu, 1.0)
    d.material(2, E, nu, 1.0)
    for n in d.nodes_where("B", lambda x, y: True):
        d.fix(n, "11")
    if fix_x_line and ntype != 3:
        for n in d.nodes_where("A", lambda x, y: abs(x) < 1e-12):
            d.fix(n, "10")
    return d


def surfaces(d):
    """SURFACE A and SURFACE B cards: the nodes of A and of B on y = 0."""
    sa = d.nodes_where("A", lambda x, y: abs(y) < 1e-12)
    sb = d.nodes_where("B", lambda x, y: abs(y) < 1e-12)
    return ["SURFACE   A"] + d.node_list_cards(sa) + ["SURFACE   B"] + d.node_list_cards(sb)
