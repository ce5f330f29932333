"""Kontakt2D's Python package: the deck writer and the tools built on it.

Scripts in tools/ put the tools directory on sys.path and import from here,
e.g. ``from k2d.deck import Deck``.
"""
