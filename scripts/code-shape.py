#!/usr/bin/env python3
"""Lists the longest functions and files of Lantern's C++ sources (the house aims for
functions under 80 lines and files under 500; docs/ARCHITECTURE.md).

Usage: scripts/code-shape.py [--limit 80] [--file-limit 500] [FOLDER ...]
       (default folders: engine apps benchmarks)

A function is a brace block whose opening line looks like a definition (a parameter list
before the brace, not a control statement, lambda, class or namespace); its length counts
from the line of its name to its closing brace. Comments and strings are blanked first, so
braces inside them do not count. A heuristic, good enough to find the long ones.
"""
import argparse
import os
import re
import sys

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|return)\b")


def blank(text):
    """Replaces comments and string/char literals with spaces, keeping line breaks."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + (m.group(1) if m else "") + '"', i)
            j = n if end < 0 else end + len(m.group(1) if m else "") + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    found, stack = [], []
    line = 1
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c == "{":
            head = text[max(0, i - 400):i]
            head = head[head.rfind(";") + 1:] if ";" in head else head
            head = head[head.rfind("}") + 1:] if "}" in head else head
            # The head starts after the last brace of either kind: the first function after
            # `namespace {` (or a class's opening brace) was read as part of the namespace.
            head = head[head.rfind("{") + 1:] if "{" in head else head
            flat = " ".join(head.split())
            is_fn = (")" in flat and not CONTROL.search(flat.split("(")[0] if "(" in flat else flat)
                     and not re.search(r"\]\s*\([^)]*\)\s*(mutable\s*)?(->[^{]*)?$", flat)
                     and not re.search(r"\b(class|struct|namespace|enum|union)\b", flat.split("(")[0]))
            name = ""
            if is_fn:
                m = re.search(r"([~\w:]+(?:operator\s*\S+)?)\s*\([^()]*(\([^()]*\)[^()]*)*\)[^()]*$", flat)
                name = m.group(1) if m else flat[-60:]
                start = line - head.count("\n") + (len(head) - len(head.lstrip("\n")) and 0)
                start = line - (head.rstrip().count("\n") - head[: len(head) - len(head.lstrip())].count("\n"))
            stack.append((is_fn, name, start if is_fn else line))
        elif c == "}" and stack:
            is_fn, name, start = stack.pop()
            if is_fn and not any(s[0] for s in stack):
                found.append((line - start + 1, name, start))
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folders", nargs="*", default=["engine", "apps", "benchmarks"])
    ap.add_argument("--limit", type=int, default=80)
    ap.add_argument("--file-limit", type=int, default=500)
    args = ap.parse_args()
    rows, files = [], []
    for folder in args.folders:
        for root, _, names in os.walk(folder):
            for n in names:
                if n.endswith((".cpp", ".h")):
                    p = os.path.join(root, n)
                    files.append((sum(1 for _ in open(p, encoding="utf-8", errors="replace")), p))
                    rows += [(length, name, p, start) for length, name, start in functions(p)]
    rows.sort(reverse=True)
    long_fns = [r for r in rows if r[0] > args.limit]
    print(f"functions over {args.limit} lines: {len(long_fns)}")
    for length, name, p, start in long_fns:
        print(f"  {length:4d}  {p}:{start}  {name}")
    big = sorted((f for f in files if f[0] > args.file_limit), reverse=True)
    print(f"files over {args.file_limit} lines: {len(big)}")
    for length, p in big:
        print(f"  {length:4d}  {p}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
