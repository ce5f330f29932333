#!/usr/bin/env python3
"""Fuzz the input readers and the program against their contract (docs/fuzzing.md).

    tools/fuzz.py corpus  LIST                         write the corpus list
    tools/fuzz.py inproc  [--runs N] [--seed S] ...    in-process: tests/fuzz/fuzz_readers
    tools/fuzz.py process [--runs N] [--seed S] ...    whole program, one process per input

The corpus is every deck of inputs/ and tests/ (with the .msh file its MESH
block names), except the large *_fine decks.  Both modes use one mutation
engine (tests/fuzz/fuzz_mutation.f90): `process` asks fuzz_readers to emit the
mutated inputs (--emit) and runs kontakt2d on each, classifying the outcome
against the documented contract (docs/fuzzing.md):

  exit 2  the messages name file:line, no result file, no runtime trace;
  exit 0  a result file whose every number is finite (also exit 4, completed with doubts);
  exit 3  a numerical failure reported, no runtime trace;
  else    a crash (signal, exit 1 internal error, runtime or sanitizer report);
  and no run longer than --timeout seconds (a hang).

Both modes print one summary line and exit 1 when the contract was broken
(the inputs are kept in --findings), 0 otherwise.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

from k2d.results import first_nonfinite

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GMSH_CARD = re.compile(r'^GMSH\s+(\S+)', re.M)
MAX_PROCESS_INCREMENTS = 1000   # longer decks are left out of the whole-program corpus
MAX_DEBUG_PROCESS_MESH_BYTES = 80_000   # larger meshes are left out of a checked build's
                                        # whole-program corpus
LOCATED = re.compile(r'^\S+:\d+(:\d+)?: error \[[A-Z-]+\]: ', re.M)
ERROR_LINE = re.compile(r'error \[[A-Z-]+\]: ')
# one BLAS thread per run: the runs go in parallel (--jobs)
RUN_ENV = dict(os.environ, OPENBLAS_NUM_THREADS='1', OMP_NUM_THREADS='1')
TRACE = re.compile(r'Fortran runtime|Backtrace|SIGSEGV|SIGFPE|AddressSanitizer|runtime error:|LeakSanitizer|'
                   r'internal error')


def deck_increments(text):
    """Increments of a deck's load history: the sum of the NSTEP fields (columns
    1-5) of its INCREMENTS cards (1 without them); 0 when they cannot be read."""
    m = re.search(r'^INCREMENTS[ \t]*$(.*?)^END', text, re.M | re.S)
    if not m:
        return 1
    n = 0
    for line in m.group(1).splitlines():
        if not line.strip() or line.lstrip().startswith('#'):
            continue
        try:
            n += int(line[:5])
        except ValueError:
            return 0
    return n


def corpus_entries(traps=False, process=False):
    """(deck path, mesh name or '') of every deck of the corpus.  traps: the
    program is a Debug build, which traps floating-point overflow where it
    happens (-ffpe-trap): the decks made to overflow (tests/decks/fail/
    *nonfinite*, *overflow*, which ctest runs in Release builds only for the
    same reason) are left out, since their trap is the build's purpose, not a
    crash of the program.  process: the corpus of whole-program runs, which
    leaves out the decks of more than MAX_PROCESS_INCREMENTS increments (long
    analyses by design, e.g. tests/decks/options/many_increments.dat: 4 000
    increments, 5 s of CPU alone, over the 60 s hang limit of wall time on a
    loaded machine), and in a Debug build (traps) also the decks whose mesh file is larger than
    MAX_DEBUG_PROCESS_MESH_BYTES (a checked, sanitized build runs a model 10-20 times slower:
    tests/decks/bolt/joint_separation, 10 s in Release, passed the 60 s hang limit); the
    in-process readers take every deck."""
    entries = []
    for top in ('inputs', 'tests'):
        for d, _, files in sorted(os.walk(os.path.join(ROOT, top))):
            rel = os.path.relpath(d, ROOT).split(os.sep)
            if 'pfunit_fallback' in rel or 'fuzz' in rel:
                continue
            for f in sorted(files):
                if not f.endswith('.dat') or f.endswith('_fine.dat'):
                    continue
                if traps and re.search(r'nonfinite|overflow', f):
                    continue
                path = os.path.join(d, f)
                if os.path.getsize(path) > 200_000:
                    continue
                with open(path, 'rb') as fh:
                    text = fh.read().decode('latin-1')
                if process and deck_increments(text) > MAX_PROCESS_INCREMENTS:
                    continue
                mesh = ''
                mm = GMSH_CARD.search(text)
                if mm:
                    if not os.path.exists(os.path.join(d, mm.group(1))) or '/' in mm.group(1):
                        continue
                    mesh = mm.group(1)
                    if process and traps and \
                            os.path.getsize(os.path.join(d, mesh)) > MAX_DEBUG_PROCESS_MESH_BYTES:
                        continue
                entries.append((path, mesh))
    return entries


def debug_build(build):
    """Is the build directory a Debug build (CMAKE_BUILD_TYPE in its cache)?"""
    try:
        with open(os.path.join(build, 'CMakeCache.txt')) as fh:
            return re.search(r'^CMAKE_BUILD_TYPE:\w+=Debug$', fh.read(), re.M) is not None
    except OSError:
        return False


def write_corpus(path, traps=False, process=False):
    entries = corpus_entries(traps, process)
    with open(path, 'w') as fh:
        for deck, mesh in entries:
            fh.write(deck + (' ' + mesh if mesh else '') + '\n')
    return len(entries)


def build_target(build, target):
    subprocess.run(['cmake', '--build', build, '--target', target, '-j2'], check=True,
                   stdout=subprocess.DEVNULL)
    path = os.path.join(build, 'tests', 'fuzz', target) if target == 'fuzz_readers' else os.path.join(build, target)
    return os.path.abspath(path)   # the runs have their own working directories


def keep(src_dir, findings, tag):
    dest = os.path.join(findings, tag)
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(src_dir, dest)
    return dest


def cmd_inproc(a):
    exe = os.path.abspath(a.fuzzer) if a.fuzzer else build_target(a.build, 'fuzz_readers')
    os.makedirs(a.findings, exist_ok=True)
    work = tempfile.mkdtemp(prefix='k2d_fuzz_', dir=a.tmp)
    corpus = os.path.join(work, 'corpus.txt')
    n = write_corpus(corpus)
    totals = dict(runs=0, errors=0, accepted=0, no_location=0, bad_text=0, nonfinite=0, slow=0, crashes=0, hangs=0)
    max_s = 0.0
    t0 = time.time()
    chunk = 0
    while totals['runs'] < a.runs:
        runs = min(a.chunk, a.runs - totals['runs'])
        seed = a.seed + chunk
        cdir = os.path.join(work, 'c')
        shutil.rmtree(cdir, ignore_errors=True)
        os.makedirs(cdir)
        try:
            p = subprocess.run([exe, corpus, cdir, str(seed), str(runs), a.findings], capture_output=True,
                               text=True, errors='replace', timeout=a.timeout + 5.0 * runs)
            out = p.stdout + p.stderr
            m = re.search(r'runs=(\d+) errors=(\d+) accepted=(\d+) no_location=(\d+) bad_text=(\d+) '
                          r'nonfinite=(\d+) slow=(\d+) max_seconds=([\d.]+)', out)
            if m and p.returncode in (0, 1) and not TRACE.search(out):
                for k, v in zip(('runs', 'errors', 'accepted', 'no_location', 'bad_text', 'nonfinite', 'slow'),
                                m.groups()[:7]):
                    totals[k] += int(v)
                max_s = max(max_s, float(m.group(8)))
                for line in out.splitlines():
                    if line.startswith(('no location:', 'bad text:')):
                        print(f'seed {seed}: {line}')
            else:
                totals['crashes'] += 1
                totals['runs'] += runs      # an upper bound: the chunk ended early
                dest = keep(cdir, a.findings, f'crash_inproc_{seed}')
                print(f'seed {seed}: crash (exit {p.returncode}); input kept in {dest}\n{out[-2000:]}')
        except subprocess.TimeoutExpired:
            totals['hangs'] += 1
            totals['runs'] += runs
            dest = keep(cdir, a.findings, f'hang_inproc_{seed}')
            print(f'seed {seed}: no end within the time limit; input kept in {dest}')
        chunk += 1
        if a.progress:
            print('progress ' + ' '.join(f'{k}={v}' for k, v in totals.items()) +
                  f' max_seconds={max_s:.3f} wall_seconds={time.time() - t0:.0f}', flush=True)
    shutil.rmtree(work, ignore_errors=True)
    print(f'inproc corpus={n} ' + ' '.join(f'{k}={v}' for k, v in totals.items()) +
          f' max_seconds={max_s:.3f} wall_seconds={time.time() - t0:.0f}')
    bad = sum(totals[k] for k in ('no_location', 'bad_text', 'nonfinite', 'slow', 'crashes', 'hangs'))
    return 1 if bad else 0


def classify(run_dir, exe, timeout):
    """Run the program on run_dir/fuzz.dat; return (outcome, detail)."""
    res = os.path.join(run_dir, 'out.h5')
    t0 = time.time()
    try:
        p = subprocess.run([exe, 'fuzz.dat', '-q', '-o', 'out.h5', '-l', 'out.lis'], cwd=run_dir,
                           capture_output=True, timeout=timeout, env=RUN_ENV)
    except subprocess.TimeoutExpired:
        return 'hang', f'no end within {timeout} s', time.time() - t0
    dt = time.time() - t0
    err = p.stderr.decode('latin-1')
    rc = p.returncode
    # a runtime or sanitizer trace is looked for outside the program's own messages, which
    # echo the input (a deck may well say "SIGFPE" in a line the mutation made a card)
    own = re.compile(r'^(    \| |kontakt2d: |\S+:\d+(:\d+)?: (error|warning) \[)')
    trace = TRACE.search('\n'.join(ln for ln in err.splitlines() if not own.match(ln)))
    if rc < 0 or rc == 1 or trace:
        return 'crash', f'exit {rc}: {err[-600:]}', dt
    if rc == 2:
        if os.path.exists(res):
            return 'result_after_input_error', err[-300:], dt
        errs = [ln for ln in err.splitlines() if ERROR_LINE.search(ln)]
        if not errs or any(not LOCATED.match(ln) for ln in errs):
            return 'no_location', err[-600:], dt
        return 'exit2', '', dt
    if rc in (0, 4):
        # 4: completed with doubts (frozen states, law drift, invariant violations): a complete
        # result file all the same, under the same contract as a success
        if not os.path.exists(res):
            return 'no_result', '', dt
        bad = first_nonfinite(res)
        if bad:
            return 'nonfinite', bad, dt
        return 'exit%d' % rc, '', dt
    if rc == 3:
        return 'exit3', '', dt
    return 'crash', f'exit {rc}', dt


def cmd_process(a):
    exe = os.path.abspath(a.program) if a.program else build_target(a.build, 'kontakt2d')
    fuzzer = os.path.abspath(a.fuzzer) if a.fuzzer else build_target(a.build, 'fuzz_readers')
    os.makedirs(a.findings, exist_ok=True)
    work = tempfile.mkdtemp(prefix='k2d_fuzzp_', dir=a.tmp)
    corpus = os.path.join(work, 'corpus.txt')
    n = write_corpus(corpus, traps=debug_build(a.build) and not a.program, process=True)
    counts = {}
    bad_kinds = ('crash', 'hang', 'no_location', 'nonfinite', 'result_after_input_error', 'no_result')
    t0 = time.time()
    done = 0
    max_s = 0.0
    batch = 0
    from concurrent.futures import ThreadPoolExecutor
    while done < a.runs:
        runs = min(a.chunk, a.runs - done)
        seed = a.seed + batch
        bdir = os.path.join(work, 'b')
        shutil.rmtree(bdir, ignore_errors=True)
        dirs = [os.path.join(bdir, str(i)) for i in range(1, runs + 1)]
        for d in dirs:
            os.makedirs(d)
        subprocess.run([fuzzer, corpus, bdir, str(seed), str(runs), '--emit'], check=True,
                       stdout=subprocess.DEVNULL)
        with ThreadPoolExecutor(max_workers=a.jobs) as pool:
            results = list(pool.map(lambda d: classify(d, exe, a.timeout), dirs))
        for i, (kind, detail, dt) in enumerate(results, start=1):
            counts[kind] = counts.get(kind, 0) + 1
            max_s = max(max_s, dt)
            if kind in bad_kinds:
                dest = keep(dirs[i - 1], a.findings, f'{kind}_process_{seed}_{i}')
                print(f'seed {seed} run {i}: {kind}: {detail.strip()[:400]} (kept in {dest})', flush=True)
        done += runs
        batch += 1
        if a.progress:
            print(f'progress runs={done} ' + ' '.join(f'{k}={v}' for k, v in sorted(counts.items())) +
                  f' max_seconds={max_s:.2f} wall_seconds={time.time() - t0:.0f}', flush=True)
    shutil.rmtree(work, ignore_errors=True)
    print(f'process corpus={n} runs={done} ' + ' '.join(f'{k}={v}' for k, v in sorted(counts.items())) +
          f' max_seconds={max_s:.2f} wall_seconds={time.time() - t0:.0f}')
    return 1 if any(counts.get(k, 0) for k in bad_kinds) else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest='cmd', required=True)
    c = sub.add_parser('corpus', help='write the corpus list')
    c.add_argument('list')
    for name in ('inproc', 'process'):
        s = sub.add_parser(name)
        s.add_argument('--runs', type=int, default=2000)
        s.add_argument('--seed', type=int, default=1)
        s.add_argument('--build', default=os.path.join(ROOT, 'build'), help='build directory (default build/)')
        s.add_argument('--fuzzer', help='the fuzz_readers executable (default: built in --build)')
        s.add_argument('--findings', default='fuzz-findings', help='where inputs that break the contract go')
        s.add_argument('--tmp', default=None, help='scratch directory (default: the system\'s)')
        s.add_argument('--timeout', type=float, default=60.0, help='seconds before a run counts as a hang')
        s.add_argument('--progress', action='store_true', help='print the totals after every chunk')
        s.add_argument('--chunk', type=int, default=20000 if name == 'inproc' else 500,
                       help='inputs per fuzzer process (a crash loses the rest of its chunk)')
        if name == 'process':
            s.add_argument('--program', help='the kontakt2d executable (default: built in --build)')
            s.add_argument('--jobs', type=int, default=2)
    a = ap.parse_args()
    if a.cmd == 'corpus':
        print(write_corpus(a.list))
        return 0
    return cmd_inproc(a) if a.cmd == 'inproc' else cmd_process(a)


if __name__ == '__main__':
    sys.exit(main())
