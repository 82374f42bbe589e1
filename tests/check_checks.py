#!/usr/bin/env python3
"""check_checks: a `check "description" [ A ] && [ B ]` in an end-to-end script checks A alone: the
shell runs `[ B ]` after check returns, and its result counts nowhere. Fails, naming file and line,
on any check whose command is a bare `[` test followed by && or || on the same logical line (the
one-command forms: check "d" eval '[ A ] && [ B ]', or a helper function).

Usage: check_checks.py SCRIPT...
"""
import re
import sys

# check, its quoted description, then a bare test command; later, && or || outside quotes
HEAD = re.compile(r'^\s*check\s+"(?:[^"\\]|\\.)*"\s+\[\s')


def unquoted(text):
    """text with its single- and double-quoted parts (and $( ... ) inside them) blanked."""
    out, quote = [], None
    for ch in text:
        if quote:
            if ch == quote:
                quote = None
            out.append(" ")
        elif ch in "'\"":
            quote = ch
            out.append(" ")
        else:
            out.append(ch)
    return "".join(out)


def logical_lines(path):
    """(first line number, text) of each line joined with its backslash continuations."""
    with open(path, encoding="utf-8", errors="replace") as f:
        start, acc = None, ""
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if start is None:
                start = n
            if line.endswith("\\"):
                acc += line[:-1] + " "
                continue
            yield start, acc + line
            start, acc = None, ""


def main(paths):
    bad = 0
    for path in paths:
        for n, text in logical_lines(path):
            if HEAD.match(text) and re.search(r"(&&|\|\|)", unquoted(text)):
                print(f"{path}:{n}: check's command is a bare [ test joined by && or ||: only the first "
                      "test is checked; use eval '...' or a function", file=sys.stderr)
                bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
