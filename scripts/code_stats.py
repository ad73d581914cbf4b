#!/usr/bin/env python3
"""Size figures of Prism's sources: files over a line count and functions over a line count.

Functions are found by brace matching: a '{' that opens a body after ')' (optionally followed by
const, noexcept, override, an initializer list or a trailing return type) at namespace or class
level starts a function; its length runs to the matching '}'. Lambdas inside a body count
towards their function. Comments and string literals are skipped. A heuristic, good enough
for the file and function sizes it reports; it never parses templates' angle brackets.

Usage: scripts/code_stats.py [--files N] [--functions N] [FOLDER ...]
  (default: --files 400 --functions 80, folders master slave common gui)
"""

import argparse
import re
from pathlib import Path


def strip(text: str) -> str:
    """Blanks comments and string/char literals, keeping newlines (so line numbers hold)."""
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
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


HEAD = re.compile(r"\)\s*(const\s*)?(noexcept\s*)?(override\s*)?(final\s*)?(->\s*[\w:<>,\s*&]+)?"
                  r"(:\s*[^;{}]*)?$", re.S)
NAME = re.compile(r"([~\w:]+(?:<[^()]*>)?)\s*\([^;{}]*\)[^;{}()]*$", re.S)
KEYWORDS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype"}


def functions(path: Path):
    text = strip(path.read_text(errors="replace"))
    results, depth_kind, i = [], [], 0
    last = 0  # where the text before the current '{' starts (after the last ; { or })
    while i < len(text):
        c = text[i]
        if c == "{":
            before = text[last:i]
            in_function = any(k == "function" for k, _ in depth_kind)
            kind = "block"
            if not in_function and HEAD.search(before.rstrip()):
                m = NAME.search(before.rstrip())
                name = m.group(1) if m else "?"
                if name.split("::")[-1] not in KEYWORDS:
                    kind = "function"
                    results.append([name, text.count("\n", 0, i) + 1, None])
            depth_kind.append((kind, len(results) - 1))
            last = i + 1
        elif c == "}":
            if depth_kind:
                kind, index = depth_kind.pop()
                if kind == "function":
                    results[index][2] = text.count("\n", 0, i) + 1
            last = i + 1
        elif c == ";":
            last = i + 1
        i += 1
    return [(name, start, end - start + 1) for name, start, end in results if end]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--files", type=int, default=400)
    parser.add_argument("--functions", type=int, default=80)
    parser.add_argument("folders", nargs="*", default=["master", "slave", "common", "gui"])
    args = parser.parse_args()
    root = Path(__file__).resolve().parent.parent
    sources = sorted(p for f in args.folders for p in (root / f).rglob("*")
                     if p.suffix in (".h", ".cpp") and p.is_file())
    big_files = [(p, sum(1 for _ in p.open(errors="replace"))) for p in sources]
    big_files = [(p, n) for p, n in big_files if n > args.files]
    print(f"files over {args.files} lines: {len(big_files)}")
    for p, n in sorted(big_files, key=lambda x: -x[1]):
        print(f"  {n:5d}  {p.relative_to(root)}")
    long_functions = [(p, name, start, n) for p in sources for name, start, n in functions(p)
                      if n > args.functions]
    print(f"functions over {args.functions} lines: {len(long_functions)}")
    for p, name, start, n in sorted(long_functions, key=lambda x: -x[3]):
        print(f"  {n:5d}  {p.relative_to(root)}:{start}  {name}")


if __name__ == "__main__":
    main()
