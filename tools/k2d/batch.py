"""Running many decks: a pool of parallel runs, a run measured for its cost, the model size
and timing the program prints.

    from k2d.batch import run_parallel, run_decks, run_measured, parse_log
    for item, result in run_parallel(fn, items, jobs=2):  # fn(item) in `jobs` threads, as they finish
        ...
    done = run_decks(exe, {"name": "deck.dat"}, out, jobs=2)   # {name: (exit code, seconds)}
    rc, wall, cpu, rss = run_measured(exe, deck, h5, log, ["-s", "umfpack"], timeout=900)
    parse_log(log)              # {"nodes", "equations", "pairs", "program_s"} from the terminal output
"""
import concurrent.futures
import os
import signal
import subprocess
import threading
import time

from .build import run_deck
from .terminal import program_seconds, read_terminal

__all__ = ["run_parallel", "run_decks", "GNU_TIME", "run_measured", "parse_log"]


def run_parallel(fn, items, jobs, in_order=False):
    """Call fn(item) for every item in `jobs` threads (the runs themselves are processes);
    yields (item, result) as the calls finish, or in the order of `items` with in_order."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        if in_order:
            for item, res in zip(items, pool.map(fn, items)):
                yield item, res
            return
        futures = {pool.submit(fn, item): item for item in items}
        for fut in concurrent.futures.as_completed(futures):
            yield futures[fut], fut.result()


def run_decks(exe, decks, out, jobs, report=None):
    """Run the decks {name: path} in parallel into out/h5/<name>.h5, the terminal output and
    the listing into out/logs/<name>.log and .lis; the biggest decks first, so that the pool
    stays busy.  report(name, rc, seconds) is called as each run ends, in that order.
    Returns {name: (exit code, seconds of wall time)}."""
    for sub in ("h5", "logs"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)

    def one(name):
        t0 = time.time()
        rc = run_deck(exe, decks[name], os.path.join(out, "h5", name + ".h5"),
                      listing=os.path.join(out, "logs", name + ".lis"),
                      log=os.path.join(out, "logs", name + ".log"))
        return rc, time.time() - t0

    done = {}
    order = sorted(decks, key=lambda n: -os.path.getsize(decks[n]))
    for name, (rc, dt) in run_parallel(one, order, jobs, in_order=True):
        done[name] = (rc, dt)
        if report:
            report(name, rc, dt)
    return done


GNU_TIME = "/usr/bin/time"


def run_measured(exe, deck, h5, log, extra=(), timeout=900.0):
    """Run kontakt2d on one deck, its terminal output into `log`; returns (exit code, wall s,
    user + system CPU s, max RSS MB).  The run is killed after `timeout` seconds.

    The CPU time is the rusage of the child (os.wait4: this process alone, whatever else
    runs).  The peak memory comes from GNU time (Debian package `time`) when it is there: a
    child forked from this Python process inherits its resident set in ru_maxrss, so the
    fallback, the child's own ru_maxrss, is only an upper bound."""
    cmd = [exe, deck, "-o", h5] + list(extra)
    rss_file = os.path.splitext(log)[0] + ".rss"
    if os.path.exists(GNU_TIME):
        cmd = [GNU_TIME, "-f", "%M", "-o", rss_file] + cmd
    with open(log, "w") as f:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT)
        timer = threading.Timer(timeout, lambda: os.kill(p.pid, signal.SIGKILL))
        timer.start()
        try:
            _, status, ru = os.wait4(p.pid, 0)      # the rusage of this child alone
        finally:
            timer.cancel()
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    rss = ru.ru_maxrss / 1024.0
    if cmd[0] == GNU_TIME:
        try:
            with open(rss_file) as f:
                rss = float(f.read().split()[-1]) / 1024.0
        except (OSError, ValueError, IndexError):
            pass
    return p.returncode, wall, ru.ru_utime + ru.ru_stime, rss


def parse_log(log):
    """Model size and the program's own timing from its terminal output (a run without -q):
    {"nodes", "equations", "pairs", "program_s"}, "" where not found."""
    t = read_terminal(log)
    if t is None:
        raise OSError("cannot read %s" % log)
    secs = program_seconds(t)
    out = {k: ("" if t[k] is None else t[k]) for k in ("nodes", "equations", "pairs")}
    out["program_s"] = "" if secs is None else secs
    return out
