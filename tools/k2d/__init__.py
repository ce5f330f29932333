"""Kontakt2D's Python package: the tools' library; the scripts in tools/ are thin command
lines on it (docs/DEVELOPERS.md, "The Python package tools/k2d").

    results          the one reader of the result file (docs/results-format.md)
    deck, patch      the deck writer; the block on a rigid base of the patch tests
    examples         the decks of the paper's examples and their variants
    published        the paper's Tables 1 and 2
    build, batch     find or build the program, run a deck; many decks in parallel, measured runs
    tables, analysis CSV and Markdown tables; contact pairs along the surface, contact radius
    checks           the expected values of a good deck (<deck>.check)
    paper, study, increment_study, plot   the work of the scripts of the same purpose
    history          the figures of a run's history (approach, load stages, width, slip zone)
    history_plot     the history plots and the stage table (tools/plot_history.py, tools/run.sh)
    compare          a deck against a varied card, or two decks: runs and report (tools/compare.py)
    adapt, refine    refinement to a requested accuracy; a card deck split uniformly (tools/adapt.py)

Scripts in tools/ put the tools directory on sys.path and import from here,
e.g. ``from k2d.results import Result``; ctest sets PYTHONPATH for the test checkers.
"""
