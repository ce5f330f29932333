"""Kontakt2D's Python package: the tools' library; the scripts in tools/ are thin command
lines on it (docs/DEVELOPERS.md, "The Python package tools/k2d").

    results          the one reader of the result file (docs/results-format.md)
    deck, patch      the deck writer, the deck's blocks and solver names; the block on a rigid base
                     of the patch tests
    laws             the rough interface's laws and the unit conversion (docs/contact.md)
    terminal         the program's terminal output (header, progress lines, summary totals)
    examples         the decks of the paper's examples and their variants
    published        the paper's Tables 1 and 2
    build, batch     find or build the program, run a deck; many decks in parallel, measured runs
    tables, analysis CSV and Markdown tables; contact pairs along the surface, contact radius
    checks           the expected values of a good deck (<deck>.check)
    paper, study, increment_study, plot   the work of the scripts of the same purpose
    history          the figures of a run's history (approach, load stages, width, slip zone)
    history_plot     the history plots and the stage table (tools/plot_history.py, tools/run.sh)
    loops            paths along the interface law, shear-slip loops, energy per cycle (tools/plot_energy.py)
    compare          a deck against a varied card, or two decks: runs and report (tools/compare.py)
    adapt, refine    refinement to a requested accuracy; a card deck split uniformly (tools/adapt.py)

The scripts in tools/ import from here, e.g. ``from k2d.results import Result``: Python puts a
script's own directory (tools/) first on sys.path, so they run without installation
(``python3 tools/plot_history.py ...``).  Elsewhere set PYTHONPATH=<source>/tools (ctest does for
the test checkers) or install the package: ``pip install -e tools`` (tools/pyproject.toml).
"""
__all__ = ["adapt", "analysis", "batch", "build", "calibration", "calibration_data", "calibration_plots",
           "calibration_replay", "checks", "compare", "deck", "examples", "history", "history_plot",
           "increment_study", "laws", "loops", "paper", "patch", "plot", "published", "refine", "results", "scenes",
           "study", "tables", "terminal"]
