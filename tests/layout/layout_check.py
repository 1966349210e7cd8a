#!/usr/bin/env python3
"""The engine's folders depend on each other one way, and every header has its own name.

Reads every #include "..." of engine/src, maps each file to its top folder (sim, report, mesh...)
and fails on a cycle between folders (any length, found as a strongly connected component),
printing one include line per edge of the cycle. Also fails when two headers under engine/src and
engine/include share a file name (a reader cannot tell which one an include means).
Usage: layout_check.py REPO_ROOT
"""
import collections
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def folder_edges(src):
    """{folder: {folder: [example include line]}} over engine/src's top folders."""
    edges = collections.defaultdict(dict)
    for directory, _, files in os.walk(src):
        for name in files:
            if not name.endswith((".cpp", ".hpp", ".h")):
                continue
            path = os.path.join(directory, name)
            rel = os.path.relpath(path, src)
            if os.sep not in rel:
                continue  # a file at the top of engine/src belongs to no folder
            here = rel.split(os.sep)[0]
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            for target in INCLUDE.findall(text):
                for base in (directory, src):  # relative to the file, then to engine/src
                    resolved = os.path.normpath(os.path.join(base, target))
                    if os.path.isfile(resolved) and resolved.startswith(src + os.sep):
                        there = os.path.relpath(resolved, src).split(os.sep)[0]
                        if there != here and os.sep in os.path.relpath(resolved, src):
                            edges[here].setdefault(there, f"{rel} includes {target}")
                        break
    return edges


def strongly_connected(edges):
    """Tarjan's components with more than one folder."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    nodes = set(edges) | {w for targets in edges.values() for w in targets}
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return found


def duplicate_headers(repo, roots):
    seen = collections.defaultdict(list)
    for root in roots:
        for directory, _, files in os.walk(os.path.join(repo, root)):
            for name in files:
                if name.endswith((".hpp", ".h")):
                    seen[name].append(os.path.relpath(os.path.join(directory, name), repo))
    return {name: paths for name, paths in seen.items() if len(paths) > 1}


def main():
    repo = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    src = os.path.join(repo, "engine", "src")
    edges = folder_edges(src)
    failures = 0
    for component in strongly_connected(edges):
        failures += 1
        print(f"include cycle between engine/src folders: {' <-> '.join(component)}")
        for a in component:
            for b, line in sorted(edges[a].items()):
                if b in component:
                    print(f"  {a} -> {b}: {line}")
    duplicates = duplicate_headers(repo, ["engine/src", "engine/include"])
    for name, paths in sorted(duplicates.items()):
        failures += 1
        print(f"two headers named {name}: {', '.join(sorted(paths))}")
    if failures:
        return 1
    order = sorted(edges)
    print("engine/src folder dependencies (no cycle):")
    for a in order:
        print(f"  {a} -> {', '.join(sorted(edges[a]))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
