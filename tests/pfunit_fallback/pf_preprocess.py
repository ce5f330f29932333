#!/usr/bin/env python3
"""Fallback preprocessor for pFUnit 4 test suites: turns test_foo.pf into test_foo.F90.

PFUnitFallback.cmake runs it when CMake finds no pFUnit. It accepts the subset of pFUnit's
.pf syntax listed in docs/DEVELOPERS.md and generates what pFUnit's preprocessor (funitproc)
generates, against the `funit` module of funit.f90 beside this script:

  * every `@assertXxx(args)` line becomes
        call assertXxx(args, location=SourceLocation('test_foo.pf', line)); if (anyExceptions()) return
    so the first failing assertion ends the test;
  * `@test`, `@before` and `@after` become comments, and the subroutine that follows each is
    registered as a test, the set-up or the tear-down of the module;
  * after the module, a module Wrap<module> holds `<module>_suite()`, which runs each test
    through the fallback runner; the test executable's driver calls it.

`#line` markers send compiler messages back to the .pf file and line. Anything it cannot
translate exactly as pFUnit would (a continued directive, a comment after a directive, an
unsupported directive or option, a module not named after the file, a module-scope name that
pFUnit's funit module also exports) is an error that names the .pf file and line; all errors
of a file are reported at once, and no output is written.

Usage: pf_preprocess.py [--allow-continuation] INPUT.pf OUTPUT.F90
Only the Python standard library is used.
"""

import argparse
import os
import re
import sys
import tempfile

MAX_LINE = 132  # gfortran's default free-form line length

# Supported assertions: lower-case suffix after '@assert' -> (generic name in funit,
# operands needed, keywords that count as operands, accepted keywords).
ASSERTIONS = {
    'equal': ('assertEqual', 2, {'expected', 'actual', 'found'},
              {'expected', 'actual', 'found', 'tolerance', 'message'}),
    'relativelyequal': ('assertRelativelyEqual', 2, {'expected', 'actual'},
                        {'expected', 'actual', 'tolerance', 'message'}),
    'true': ('assertTrue', 1, {'condition'}, {'condition', 'message'}),
    'false': ('assertFalse', 1, {'condition'}, {'condition', 'message'}),
    'all': ('assertAll', 1, {'conditions'}, {'conditions', 'message'}),
    'any': ('assertAny', 1, {'conditions'}, {'conditions', 'message'}),
    'lessthan': ('assertLessThan', 2, {'lhs', 'rhs'}, {'lhs', 'rhs', 'message'}),
    'lessthanorequal': ('assertLessThanOrEqual', 2, {'lhs', 'rhs'}, {'lhs', 'rhs', 'message'}),
    'greaterthan': ('assertGreaterThan', 2, {'lhs', 'rhs'}, {'lhs', 'rhs', 'message'}),
    'greaterthanorequal': ('assertGreaterThanOrEqual', 2, {'lhs', 'rhs'},
                           {'lhs', 'rhs', 'message'}),
    'exceptionraised': ('assertExceptionRaised', 0, set(), {'message'}),
}

# Valid pFUnit 4 that this fallback does not implement.
PFUNIT_ONLY_ASSERTIONS = {
    'fail', 'notequal', 'isinfinite', 'isfinite', 'isnan', 'ismemberof', 'contains', 'none',
    'notall', 'ispermutationof', 'sameshape', 'that', '_that', 'associated', 'notassociated',
    'unassociated', 'equaluserdefined', 'equivalent',
}
PFUNIT_ONLY_DIRECTIVES = {'testcase', 'suite', 'disable', 'testparameter', 'mpitest'}

SUPPORTED_LIST = ('@test, @before, @after, ' +
                  ', '.join('@' + ASSERTIONS[k][0] for k in ASSERTIONS))

RE_MODULE = re.compile(r'^\s*module\s+(\w+)\s*$', re.IGNORECASE)
RE_MODULE_COMMENT = re.compile(r'^\s*module\s+(\w+)\s*!', re.IGNORECASE)
RE_USE_FUNIT = re.compile(r'^\s*use\s*(,\s*\w+\s*::)?\s*(::)?\s*funit\b', re.IGNORECASE)
RE_SUBROUTINE = re.compile(r'^\s*subroutine\s+(\w+)\s*(\((.*)\))?\s*(!.*)?$', re.IGNORECASE)
RE_KEYWORD = re.compile(r'^([A-Za-z]\w*)\s*=(?!=)')

# Module-scope definitions, for the check against pFUnit's public names.
RE_USE_FUNIT_ONLY = re.compile(r'^\s*use\s*(,\s*\w+\s*::)?\s*(::)?\s*funit\s*,\s*only\s*:',
                               re.IGNORECASE)
RE_PROC_START = re.compile(
    r'^\s*(?:(?:pure|elemental|impure|recursive|non_recursive|module|integer|real|logical|'
    r'complex|character|double\s+precision|type\s*\(\s*\w+\s*\)|class\s*\(\s*\w+\s*\))'
    r'(?:\s*\([^)]*\))?\s+)*(?:subroutine|function)\s+(\w+)', re.IGNORECASE)
RE_PROC_END = re.compile(r'^\s*end\s*(subroutine|function)?\s*(\w+\s*)?$', re.IGNORECASE)
RE_INTERFACE_START = re.compile(r'^\s*(abstract\s+)?interface\b\s*(\w+)?\s*$', re.IGNORECASE)
RE_INTERFACE_END = re.compile(r'^\s*end\s*interface\b', re.IGNORECASE)
RE_TYPE_START = re.compile(r'^\s*type\s*(?:,[^:]*)?::\s*(\w+)|^\s*type\s+(\w+)\s*$',
                           re.IGNORECASE)
RE_TYPE_END = re.compile(r'^\s*end\s*type\b', re.IGNORECASE)
RE_DECLARATION = re.compile(
    r'^\s*(?:integer|real|logical|complex|character|double\s+precision|type\s*\(|class\s*\(|'
    r'procedure\s*\()[^!]*?::(.*)$', re.IGNORECASE)
RE_END_MODULE = re.compile(r'^\s*end\s*module\b', re.IGNORECASE)


def load_pfunit_names():
    """Public names of pFUnit's funit module, from pfunit_funit_names.txt beside this file."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'pfunit_funit_names.txt')
    with open(path, encoding='utf-8') as f:
        return {line.strip().lower() for line in f
                if line.strip() and not line.startswith('#')}


class PfError(Exception):
    """An error at one line of the .pf file."""

    def __init__(self, line, message):
        super().__init__(message)
        self.line = line
        self.message = message


def strip_comment(text, quote=None):
    """Split off a trailing '!' comment that is outside character constants.

    Returns (code, quote): quote is the delimiter of a character constant still open at the
    end of text (continued on the next line), or None.
    """
    i = 0
    while i < len(text):
        c = text[i]
        if quote:
            if c == quote:
                if i + 1 < len(text) and text[i + 1] == quote:
                    i += 2
                    continue
                quote = None
        elif c in '"\'':
            quote = c
        elif c == '!':
            return text[:i], None
        i += 1
    return text, quote


def matching_paren(text, start):
    """Index of the ')' closing the '(' at text[start]; None if it is never closed."""
    depth = 0
    quote = None
    i = start
    while i < len(text):
        c = text[i]
        if quote:
            if c == quote:
                if i + 1 < len(text) and text[i + 1] == quote:
                    i += 2
                    continue
                quote = None
        elif c in '"\'':
            quote = c
        elif c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
            if depth == 0:
                return i if c == ')' else None
            if depth < 0:
                return None
        i += 1
    return None


def split_arguments(text):
    """Split at commas outside parentheses, brackets and character constants."""
    args = []
    depth = 0
    quote = None
    current = ''
    i = 0
    while i < len(text):
        c = text[i]
        if quote:
            current += c
            if c == quote:
                if i + 1 < len(text) and text[i + 1] == quote:
                    current += text[i + 1]
                    i += 2
                    continue
                quote = None
        elif c in '"\'':
            quote = c
            current += c
        elif c in '([':
            depth += 1
            current += c
        elif c in ')]':
            depth -= 1
            current += c
        elif c == ',' and depth == 0:
            args.append(current.strip())
            current = ''
        else:
            current += c
        i += 1
    if quote:
        raise ValueError('unterminated character constant')
    if depth != 0:
        raise ValueError('unbalanced parentheses or brackets')
    if current.strip() or args:
        args.append(current.strip())
    return args


def fortran_string(text):
    return "'" + text.replace("'", "''") + "'"


class Preprocessor:
    def __init__(self, pf_path, out_path, allow_continuation):
        self.pf_path = pf_path
        self.out_path = out_path
        self.allow_continuation = allow_continuation
        self.base = os.path.basename(pf_path)
        self.stem = os.path.splitext(self.base)[0]
        self.errors = []
        self.warnings = []
        self.out = []             # output lines, without newlines
        self.modules = []         # (name, line) of every module statement
        self.uses_funit = False
        self.assertion_lines = []
        self.tests = []           # (name, line)
        self.fixture = {'before': None, 'after': None}   # name -> (procedure, line)
        self.pending = None       # ('test' | 'before' | 'after', line) awaiting its subroutine
        # Module-scope names defined by the test module (checked against pFUnit's names when
        # the module uses funit without an only: list).
        self.pfunit_names = load_pfunit_names()
        self.in_module = False
        self.unrestricted_funit = False
        self.defined = []         # (name, line)
        self.depth = 0            # procedure nesting
        self.in_interface = 0
        self.in_type = False

    # ------------------------------------------------------------------ helpers
    def line_marker(self, line):
        marker = '#line %d "%s"' % (line, self.pf_path)
        if not self.out or self.out[-1] != marker:
            self.out.append(marker)

    def error(self, line, message):
        self.errors.append((line, message))

    # ------------------------------------------------------------------ main loop
    def run(self, lines):
        self.out.append('! Generated from %s by the pFUnit fallback preprocessor; do not edit.'
                        % self.base)
        self.line_marker(1)
        i = 0
        while i < len(lines):
            n = i + 1
            line = lines[i]
            stripped = line.strip()
            consumed = 1
            try:
                if stripped == '' or stripped.startswith('!'):
                    self.out.append(line)
                elif stripped.startswith('@'):
                    consumed = self.directive(lines, i)
                elif self.pending:
                    self.procedure_line(n, line)
                else:
                    self.plain_line(n, line)
            except PfError as exc:
                self.error(exc.line, exc.message)
                self.out.append('')
            i += consumed
        if self.pending:
            kind, line = self.pending
            self.error(line, '@%s is not followed by a subroutine' % kind)
        self.check_module()
        if not self.errors:
            self.wrapper()

    def plain_line(self, n, line):
        m = RE_MODULE.match(line)
        if m:
            self.modules.append((m.group(1), n))
            self.in_module = True
            self.unrestricted_funit = False
            self.defined = []
            self.depth = self.in_interface = 0
            self.in_type = False
        elif RE_MODULE_COMMENT.match(line):
            raise PfError(n, 'pFUnit recognises the module statement only when it is alone '
                             'on its line: move the comment to a line of its own')
        else:
            self.scan_scope(n, line)
        if RE_USE_FUNIT.match(line):
            self.uses_funit = True
            if self.depth == 0 and not RE_USE_FUNIT_ONLY.match(line):
                self.unrestricted_funit = True
        self.out.append(line)

    def scan_scope(self, n, line):
        """Track procedure, interface and type nesting; note names defined at module scope."""
        if not self.in_module:
            return
        code = strip_comment(line)[0]
        if RE_END_MODULE.match(code):
            self.in_module = False
            return
        if RE_INTERFACE_END.match(code):
            self.in_interface = max(0, self.in_interface - 1)
            return
        m = RE_INTERFACE_START.match(code)
        if m:
            if self.depth == 0 and m.group(2):
                self.defined.append((m.group(2), n))
            self.in_interface += 1
            return
        if RE_TYPE_END.match(code):
            self.in_type = False
            return
        if self.in_type:
            return
        m = RE_PROC_START.match(code)
        if m:
            if self.depth == 0:
                self.defined.append((m.group(1), n))
            self.depth += 1
            return
        if RE_PROC_END.match(code) and not RE_TYPE_END.match(code):
            self.depth = max(0, self.depth - 1)
            return
        if self.depth > 0 or self.in_interface:
            return
        m = RE_TYPE_START.match(code)
        if m:
            self.defined.append((m.group(1) or m.group(2), n))
            self.in_type = True
            return
        m = RE_DECLARATION.match(code)
        if m:
            try:
                entities = split_arguments(m.group(1))
            except ValueError:
                return
            for entity in entities:
                e = re.match(r'\s*(\w+)', entity)
                if e:
                    self.defined.append((e.group(1), n))

    def procedure_line(self, n, line):
        kind, at = self.pending
        self.pending = None
        if line.strip().startswith('#'):
            raise PfError(n, 'a preprocessor line between @%s (line %d) and its subroutine is '
                             'not supported' % (kind, at))
        m = RE_SUBROUTINE.match(line)
        if not m:
            raise PfError(n, "@%s (line %d) must be followed by a line 'subroutine <name>()' "
                             "(no prefix such as recursive or module; pFUnit recognises only "
                             "this form)" % (kind, at))
        name, arglist = m.group(1), m.group(3)
        if arglist is not None and arglist.strip():
            raise PfError(n, "test, set-up and tear-down procedures take no arguments here: "
                             "'%s(%s)' looks like a pFUnit @testcase method, which the "
                             "fallback does not support" % (name, arglist.strip()))
        if kind == 'test':
            self.tests.append((name, n))
        else:
            self.fixture[kind] = (name, n)
        self.scan_scope(n, line)
        self.out.append(line)

    # ------------------------------------------------------------------ directives
    def directive(self, lines, i):
        """Translate the directive starting at lines[i]; return the number of lines used."""
        n = i + 1
        line = lines[i]
        stripped = line.strip()
        m = re.match(r'@(\w+)', stripped)
        if not m:
            raise PfError(n, "'@' at the start of a line must begin a directive (%s)"
                          % SUPPORTED_LIST)
        word = m.group(1)
        key = word.lower()
        rest = stripped[m.end():]
        if self.pending:
            kind, at = self.pending
            self.pending = None
            raise PfError(n, '@%s (line %d) must be followed by its subroutine, not by @%s'
                          % (kind, at, word))
        if key == 'test':
            if rest.strip() not in ('', '()'):
                if rest.lstrip().startswith('('):
                    raise PfError(n, '@test options %s are not supported by the pFUnit fallback'
                                  % rest.strip())
                raise PfError(n, 'unexpected text after @test: %s' % rest.strip())
            self.pending = ('test', n)
            self.out.append(line.replace('@', '!@', 1))
            return 1
        if key in ('before', 'after'):
            if rest.strip():
                raise PfError(n, '@%s takes nothing after it (pFUnit would not recognise '
                                 "'%s')" % (key, stripped))
            if self.fixture[key]:
                raise PfError(n, 'a second @%s: the module already has one (%s, line %d)'
                              % (key, self.fixture[key][0], self.fixture[key][1]))
            self.pending = (key, n)
            self.fixture[key] = ('?', n)
            self.out.append(line.replace('@', '!@', 1))
            return 1
        if key.startswith('assert'):
            variant = key[len('assert'):]
            if variant in ASSERTIONS:
                return self.assertion(lines, i, word, variant)
            if variant in PFUNIT_ONLY_ASSERTIONS:
                raise PfError(n, '@%s is pFUnit syntax that the pFUnit fallback does not '
                                 'support (supported: %s)' % (word, SUPPORTED_LIST))
        if key in PFUNIT_ONLY_DIRECTIVES or key.startswith('mpiassert'):
            raise PfError(n, '@%s is pFUnit syntax that the pFUnit fallback does not support '
                             '(supported: %s)' % (word, SUPPORTED_LIST))
        raise PfError(n, 'unknown directive @%s (supported: %s)' % (word, SUPPORTED_LIST))

    def assertion(self, lines, i, word, variant):
        n = i + 1
        stripped = lines[i].strip()
        code, quote = strip_comment(stripped)
        code = code.rstrip()
        used = 1
        if code.endswith('&'):
            if not self.allow_continuation:
                raise PfError(n, "@%s is continued with '&': pFUnit 4 reads a directive from "
                                 "one line only and would hand this one to the compiler "
                                 "unchanged. Write it on one line (test sources are compiled "
                                 "without a line-length limit)." % word)
            text = code[:-1] if quote else code[:-1].rstrip()
            while True:
                if i + used >= len(lines):
                    raise PfError(n, "@%s: the file ends inside its continuation lines" % word)
                nxt = lines[i + used].lstrip()
                used += 1
                if nxt.startswith('&'):
                    nxt = nxt[1:]
                elif quote:
                    raise PfError(i + used, "a continued character constant must resume "
                                            "after '&' on the next line")
                if nxt.strip() == '' or nxt.lstrip().startswith('!'):
                    continue
                piece, quote = strip_comment(nxt, quote)
                piece = piece if quote else piece.rstrip()
                if piece.endswith('&'):
                    text += piece[:-1] if quote else piece[:-1].rstrip()
                    continue
                text += piece
                break
            code = text
        args = self.parse_arguments(n, word, variant, code[len(word) + 1:])
        if used == 1 and len(code) < len(stripped):
            raise PfError(n, 'a comment after a directive is not allowed: pFUnit would not '
                             'recognise the directive. Put the comment on its own line.')
        generic = ASSERTIONS[variant][0]
        self.assertion_lines.append(n)
        location = 'location=SourceLocation(%s, %d)' % (fortran_string(self.base), n)
        self.line_marker(n)
        single = '  call %s(%s); if (anyExceptions()) return' % (
            generic, ', '.join(args + [location]))
        if len(single) <= MAX_LINE:
            self.out.append(single)
        else:
            self.out.append('  call %s( &' % generic)
            for arg in args:
                self.out.append('      %s, &' % arg)
            self.out.append('      %s)' % location)
            self.out.append('  if (anyExceptions()) return')
        self.line_marker(n + used)
        return used

    def parse_arguments(self, n, word, variant, text):
        text = text.strip()
        if not text.startswith('('):
            raise PfError(n, "@%s must be followed by '(' and its arguments" % word)
        close = matching_paren(text, 0)
        if close is None:
            raise PfError(n, '@%s: unbalanced parentheses, brackets or quotes in its '
                             'arguments' % word)
        if text[close + 1:].strip():
            raise PfError(n, "@%s: unexpected text after the closing parenthesis: '%s'"
                          % (word, text[close + 1:].strip()))
        try:
            args = split_arguments(text[1:close])
        except ValueError as exc:
            raise PfError(n, '@%s: %s' % (word, exc))
        _, needed, operand_keywords, keywords = ASSERTIONS[variant]
        seen = set()
        positional = 0
        operands = 0
        for arg in args:
            if not arg:
                raise PfError(n, '@%s: empty argument' % word)
            m = RE_KEYWORD.match(arg)
            if m:
                kw = m.group(1).lower()
                if kw == 'location':
                    raise PfError(n, '@%s: location= is added by the preprocessor; remove it'
                                  % word)
                if kw not in keywords:
                    raise PfError(n, '@%s: keyword %s= is not accepted (accepted: %s)'
                                  % (word, m.group(1), ', '.join(sorted(keywords))))
                if kw in seen:
                    raise PfError(n, '@%s: keyword %s= given twice' % (word, m.group(1)))
                seen.add(kw)
                if kw in operand_keywords:
                    operands += 1
            else:
                if seen:
                    raise PfError(n, '@%s: a positional argument follows a keyword argument'
                                  % word)
                positional += 1
        operands += min(positional, needed)
        if operands < needed:
            raise PfError(n, '@%s needs %d argument%s' % (word, needed,
                                                          '' if needed == 1 else 's'))
        if variant == 'relativelyequal' and positional < 3 and 'tolerance' not in seen:
            raise PfError(n, '@%s needs a tolerance (tolerance=...): pFUnit has no default '
                             'relative tolerance' % word)
        return args

    # ------------------------------------------------------------------ module and wrapper
    def check_module(self):
        if not self.modules:
            self.error(1, "no 'module %s' statement: the fallback needs the tests in a module "
                          "named after the file" % self.stem)
            return
        name, line = self.modules[-1]
        if name.lower() != self.stem.lower():
            self.error(line, 'module name (%s) and file name (%s) do not match (ignoring case), '
                             'which pFUnit requires' % (name, self.stem))
        if self.assertion_lines and not self.uses_funit:
            self.error(line, "module %s uses assertion directives but has no 'use funit'"
                             % name)
        if self.unrestricted_funit:
            for defined, at in self.defined:
                if defined.lower() in self.pfunit_names:
                    self.error(at, "'%s' is also a public name of pFUnit's funit module: with "
                                   "'use funit' this module does not compile under a real "
                                   "pFUnit. Rename it, or give 'use funit' an only: list."
                                   % defined)
        if not self.tests:
            self.warnings.append((line, 'no @test in this file: the suite will run no test'))

    def wrapper(self):
        module = self.modules[-1][0]
        suite = module + '_suite'
        self.out.append('#line %d "%s"' % (len(self.out) + 2, self.out_path))
        names = [t[0] for t in self.tests]
        before = self.fixture['before'][0] if self.fixture['before'] else None
        after = self.fixture['after'][0] if self.fixture['after'] else None
        imports = names + [p for p in (before, after) if p]
        self.out += ['',
                     'module Wrap%s' % module]
        if names:
            self.out.append('   use funit, only: pff_run_test')
        for name in imports:
            self.out.append('   use %s, only: %s' % (module, name))
        self.out += ['   implicit none',
                     '   private',
                     '   public :: %s' % suite,
                     'contains',
                     '   subroutine %s()' % suite]
        for name in names:
            call = "      call pff_run_test('%s', '%s', %s" % (suite, name, name)
            if before:
                call += ', set_up=%s' % before
            if after:
                call += ', tear_down=%s' % after
            self.out.append(call + ')')
        self.out += ['   end subroutine %s' % suite,
                     'end module Wrap%s' % module]


def main(argv=None):
    parser = argparse.ArgumentParser(
        description='Fallback preprocessor for pFUnit 4 .pf test suites (see '
                    'docs/DEVELOPERS.md).')
    parser.add_argument('--allow-continuation', action='store_true',
                        help="accept directives continued with '&' (pFUnit 4 does not)")
    parser.add_argument('input', help='the .pf file')
    parser.add_argument('output', help='the .F90 file to write')
    opts = parser.parse_args(argv)

    pf_path = os.path.abspath(opts.input)
    out_path = os.path.abspath(opts.output)
    try:
        with open(pf_path, encoding='utf-8', errors='surrogateescape') as f:
            lines = f.read().splitlines()
    except OSError as exc:
        print('%s: error: cannot read: %s' % (opts.input, exc.strerror), file=sys.stderr)
        return 1

    pre = Preprocessor(pf_path, out_path, opts.allow_continuation)
    pre.run(lines)
    for line, message in pre.warnings:
        print('%s:%d: warning: %s' % (opts.input, line, message), file=sys.stderr)
    if pre.errors:
        for line, message in sorted(pre.errors):
            print('%s:%d: error: %s' % (opts.input, line, message), file=sys.stderr)
            if 1 <= line <= len(lines):
                print('    %s' % lines[line - 1].strip(), file=sys.stderr)
        print('%s: %d error%s; no test code generated' % (
            opts.input, len(pre.errors), '' if len(pre.errors) == 1 else 's'), file=sys.stderr)
        return 1

    out_dir = os.path.dirname(out_path)
    os.makedirs(out_dir, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=out_dir, prefix='.pf_preprocess.', suffix='.tmp')
    try:
        with os.fdopen(fd, 'w', encoding='utf-8', errors='surrogateescape') as f:
            f.write('\n'.join(pre.out) + '\n')
        os.replace(tmp, out_path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return 0


if __name__ == '__main__':
    sys.exit(main())
