#!/usr/bin/env python3
"""Lists the include edges between Prism's source folders and the cycles among them.

A folder is a directory of common/ (common/scene, common/render, ...) or of master/
(master/dispatch, master/frame, master/live, master/analysis, master/commands, ...), or one of
the rank folders slave and gui. master/main.cpp, the composition root that may include every
folder, counts as a node of its own ("main"). An edge A -> B means some file in A includes a file in B.
The script resolves each quoted include the way the build does: first against the repository
root (master/..., slave/..., gui/...), then against common/ (the core's include root).

Usage: scripts/include_edges.py [--root DIR] [--why] [--check]
  --why    print, under each edge, the including file and the included header
  --check  exit 1 when the folder graph has a cycle (for CI or a pre-commit hook)
"""

import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
TOP_FOLDERS = ("master", "slave", "gui")
SUFFIXES = {".h", ".hpp", ".cpp"}


def folder_of(root: Path, path: Path) -> str:
    rel = path.relative_to(root)
    if rel.as_posix() == "master/main.cpp":
        return "main"
    if rel.parts[0] in ("common", "master"):
        return rel.parts[0] + "/" + rel.parts[1] if len(rel.parts) > 2 else rel.parts[0]
    return rel.parts[0]


def resolve(root: Path, including: Path, name: str):
    for base in (including.parent, root, root / "common"):
        candidate = base / name
        if candidate.is_file():
            return candidate.resolve()
    return None


def collect_edges(root: Path):
    edges = defaultdict(list)  # (from, to) -> [(file, header)]
    sources = [root / "common", *(root / f for f in TOP_FOLDERS)]
    for top in sources:
        for path in sorted(top.rglob("*")):
            if path.suffix not in SUFFIXES or not path.is_file():
                continue
            source = folder_of(root, path)
            for name in INCLUDE.findall(path.read_text(errors="replace")):
                target_path = resolve(root, path, name)
                if target_path is None:
                    continue
                target = folder_of(root, target_path)
                if target != source:
                    edges[(source, target)].append(
                        (str(path.relative_to(root)), str(target_path.relative_to(root))))
    return edges


def strongly_connected(nodes, edges):
    """Tarjan's algorithm; returns the components with more than one folder."""
    graph = defaultdict(set)
    for a, b in edges:
        graph[a].add(b)
    index, low, on_stack, stack, components = {}, {}, set(), [], []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph[node]):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    for node in sorted(nodes):
        if node not in index:
            visit(node)
    return components


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=Path(__file__).resolve().parent.parent, type=Path)
    parser.add_argument("--why", action="store_true")
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    root = args.root.resolve()

    edges = collect_edges(root)
    nodes = {n for edge in edges for n in edge}
    print(f"{len(edges)} include edges between {len(nodes)} folders")
    for (a, b), why in sorted(edges.items()):
        print(f"  {a} -> {b}  ({len(why)})")
        if args.why:
            for file, header in why:
                print(f"      {file}: {header}")

    cycles = strongly_connected(nodes, edges)
    if not cycles:
        print("no cycles")
        return 0
    print(f"{len(cycles)} cycle(s):")
    for component in cycles:
        members = set(component)
        print("  " + " <-> ".join(component))
        for (a, b), why in sorted(edges.items()):
            if a in members and b in members:
                print(f"      {a} -> {b}: " + ", ".join(sorted({f"{f} ({h})" for f, h in why})))
    return 1 if args.check else 0


if __name__ == "__main__":
    sys.exit(main())
