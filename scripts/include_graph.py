#!/usr/bin/env python3
"""Prints the folder-level include graph of a source folder and fails if it has a loop.

    scripts/include_graph.py core        # core/'s folders: math, models, types, association, engine, ...
    scripts/include_graph.py .           # the top level: core, variants, experiments, bench, tests

Each file belongs to the first folder under the given one (files directly in it belong to "(base)"); an edge
A -> B says some file of A includes a file of B, with the number of such #include lines. The folders are then
printed lowest first, each with the folders it builds on. Exit status 1, with the loop named, where the
folders do not form such an order. Standard library only, so any python3 runs it.
"""
import argparse
import collections
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
SOURCES = (".h", ".cc")
SKIPPED = {"build", "out", ".git"}


def folder_of(path, root):
    parts = os.path.relpath(path, root).split(os.sep)
    return parts[0] if len(parts) > 1 else "(base)"


def edges_under(repo, root):
    """(from folder, to folder) -> number of #include lines, for includes that resolve inside root."""
    edges = collections.Counter()
    folders = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIPPED and not d.startswith("build"))
        for name in sorted(filenames):
            if not name.endswith(SOURCES):
                continue
            path = os.path.join(dirpath, name)
            src = folder_of(path, root)
            folders.add(src)
            with open(path, encoding="utf-8", errors="replace") as f:
                for target in INCLUDE.findall(f.read()):
                    resolved = os.path.join(repo, target)
                    if not os.path.exists(resolved):
                        continue
                    rel = os.path.relpath(resolved, root)
                    if rel.startswith(".."):
                        continue
                    dst = folder_of(resolved, root)
                    if dst != src:
                        edges[(src, dst)] += 1
    return folders, edges


def levels(folders, edges):
    """Folders in an order where each comes after every folder it includes; None and a loop where none exists."""
    deps = {f: {b for (a, b) in edges if a == f} for f in folders}
    order, placed = [], set()
    while len(placed) < len(folders):
        ready = sorted(f for f in folders if f not in placed and deps[f] <= placed)
        if not ready:
            return None, find_loop({f: deps[f] - placed for f in folders if f not in placed})
        order.extend(ready)
        placed.update(ready)
    return order, None


def find_loop(deps):
    start = next(iter(sorted(deps)))
    path, seen = [start], {start: 0}
    while True:
        nxt = sorted(deps[path[-1]])[0]
        if nxt in seen:
            return path[seen[nxt]:] + [nxt]
        seen[nxt] = len(path)
        path.append(nxt)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", help="folder whose sub-folders are the graph's nodes (repository-relative)")
    parser.add_argument("--repo", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                        help="repository root that #include paths are relative to (default: this script's)")
    args = parser.parse_args()
    repo = os.path.abspath(args.repo)
    root = os.path.abspath(os.path.join(repo, args.root))
    folders, edges = edges_under(repo, root)
    for (a, b), n in sorted(edges.items()):
        print(f"{a} -> {b}  ({n} include{'s' if n != 1 else ''})")
    order, loop = levels(folders, edges)
    if loop:
        print("loop: " + " -> ".join(loop))
        return 1
    print("\nlowest first:")
    for f in order:
        below = sorted(b for (a, b) in edges if a == f)
        print(f"  {f}" + (f"  (on {', '.join(below)})" if below else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
