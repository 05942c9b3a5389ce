#!/usr/bin/env python3
"""Layer check: the include graph of src/ must point one way.

    check_layers.py [--src DIR] [--layers FILE] [--mode report|enforce]

Reads the layer map (default: src/layers.toml; its comments state the rules), builds the
graph of every `#include "..."` between files of src/, and reports:
- upward edges: a file including a file of a component in a higher layer;
- sideways edges: a file including a file of another component of its own layer;
- component cycles: groups of components that reach each other through includes
  (strongly connected components of the component graph, Tarjan 1972), with one cycle
  of each written out, and every pair of components that include each other directly;
- file cycles: headers that include themselves through others.

Exit status: 0 when clean, or in report mode whatever the findings; 1 in enforce mode
when anything above was found; 2 when the map is wrong (a file of src/ no component
owns, an unknown mode). `--mode` overrides the map's `mode`.
"""
import argparse
import contextlib
import io
import os
import re
import sys
import tomllib
from collections import defaultdict

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
SOURCE_SUFFIXES = (".hpp", ".cpp", ".h", ".cc", ".hh", ".ipp", ".inl")


class MapError(Exception):
    """The layer map is wrong or does not cover the tree (exit 2)."""


def read_map(path):
    """(mode, [(component, rank, layer name, [paths])]) from the TOML map."""
    with open(path, "rb") as f:
        data = tomllib.load(f)
    components, seen = [], set()
    for rank, layer in enumerate(data.get("layer", [])):
        for name, paths in layer.get("components", {}).items():
            if name in seen:
                raise MapError(f"{path}: component '{name}' appears in two layers")
            seen.add(name)
            components.append((name, rank, layer["name"], [p.strip("/") for p in paths]))
    if not components:
        raise MapError(f"{path}: no [[layer]] with components")
    return data.get("mode", "report"), components


def owner(relative_path, components):
    """(component, rank) owning a file: the longest matching path."""
    best = None
    for name, rank, _, paths in components:
        for p in paths:
            if relative_path == p or relative_path.startswith(p + "/"):
                if best is None or len(p) > best[0]:
                    best = (len(p), name, rank)
    return None if best is None else best[1:]


def source_files(src):
    found = []
    for root, _, files in os.walk(src):
        for name in files:
            if name.endswith(SOURCE_SUFFIXES):
                found.append(os.path.relpath(os.path.join(root, name), src).replace(os.sep, "/"))
    return sorted(found)


def includes(src, relative_path):
    """Quoted includes of a file that resolve to files of src/ (beside it first, then src/)."""
    resolved = []
    with open(os.path.join(src, relative_path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            beside = os.path.normpath(os.path.join(os.path.dirname(relative_path), target)).replace(os.sep, "/")
            for candidate in (beside, os.path.normpath(target).replace(os.sep, "/")):
                if os.path.isfile(os.path.join(src, candidate)):
                    resolved.append((candidate, number))
                    break
    return resolved


def strongly_connected(nodes, edges):
    """Tarjan's algorithm (iterative): the strongly connected components of a digraph."""
    index, low, on_stack, stack, groups, counter = {}, {}, set(), [], [], [0]
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            advanced = False
            for nxt in successors:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter[0]
                    counter[0] += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(edges.get(nxt, ())))))
                    advanced = True
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.append(member)
                    if member == node:
                        break
                groups.append(sorted(group))
    return groups


def one_cycle(group, edges):
    """A cycle through the first member of a strongly connected group (breadth-first)."""
    members, start = set(group), group[0]
    previous, frontier = {start: None}, [start]
    while frontier:
        following = []
        for node in frontier:
            for nxt in sorted(edges.get(node, ())):
                if nxt == start:
                    path = [node]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    return list(reversed(path)) + [start]
                if nxt in members and nxt not in previous:
                    previous[nxt] = node
                    following.append(nxt)
        frontier = following
    return group + [group[0]]


def analyse(src, layers_path):
    """Every finding, as a dict of lists; raises MapError when the map does not fit."""
    mode, components = read_map(layers_path)
    layer_of = {name: (rank, layer) for name, rank, layer, _ in components}
    files = source_files(src)
    unowned = [f for f in files if owner(f, components) is None]
    if unowned:
        raise MapError(f"{layers_path}: no component owns " + ", ".join(unowned)
                       + " (add the folder or file to a component)")
    component_of = {f: owner(f, components)[0] for f in files}

    file_edges = defaultdict(set)
    component_edges = defaultdict(lambda: defaultdict(list))  # a -> b -> ["file:line -> file"]
    upward, sideways, edge_count = [], [], 0
    for f in files:
        for target, line in includes(src, f):
            if target == f:
                continue
            edge_count += 1
            file_edges[f].add(target)
            a, b = component_of[f], component_of[target]
            if a == b:
                continue
            where = f"{f}:{line} -> {target}"
            component_edges[a][b].append(where)
            rank_a, rank_b = layer_of[a][0], layer_of[b][0]
            if rank_b > rank_a:
                upward.append((a, b, where))
            elif rank_b == rank_a:
                sideways.append((a, b, where))

    names = sorted(layer_of)
    graph = {a: set(bs) for a, bs in component_edges.items()}
    groups = [g for g in strongly_connected(names, graph) if len(g) > 1]
    two_way = sorted({tuple(sorted((a, b))) for a in graph for b in graph[a] if a in graph.get(b, ())})
    file_groups = [g for g in strongly_connected(files, file_edges) if len(g) > 1]
    return {
        "mode": mode, "files": files, "edges": edge_count, "component_edges": component_edges,
        "upward": upward, "sideways": sideways, "layer_of": layer_of,
        "component_cycles": [(g, one_cycle(g, graph)) for g in groups], "two_way": two_way,
        "file_cycles": [(g, one_cycle(g, file_edges)) for g in file_groups],
    }


def print_edges(title, edges, layer_of):
    by_pair = defaultdict(list)
    for a, b, where in edges:
        by_pair[(a, b)].append(where)
    print(f"{title}: {len(edges)} include(s) between {len(by_pair)} component pair(s)")
    for (a, b), wheres in sorted(by_pair.items()):
        print(f"  {a} ({layer_of[a][1]}) -> {b} ({layer_of[b][1]}): {len(wheres)}")
        for where in wheres:
            print(f"    {where}")


def report(findings, src, layers_path):
    layer_of = findings["layer_of"]
    cross = sum(len(w) for bs in findings["component_edges"].values() for w in bs.values())
    print(f"layer check of {src} against {layers_path} (mode {findings['mode']}): "
          f"{len(findings['files'])} files, {findings['edges']} includes, {cross} between components")
    print_edges("upward edges", findings["upward"], layer_of)
    print_edges("sideways edges", findings["sideways"], layer_of)
    print(f"component cycles: {len(findings['component_cycles'])} group(s); "
          f"{len(findings['two_way'])} pair(s) of components include each other")
    for group, cycle in findings["component_cycles"]:
        print(f"  group {{{', '.join(group)}}}; for example {' -> '.join(cycle)}")
        for a, b in zip(cycle, cycle[1:]):
            print(f"    {a} -> {b}: {findings['component_edges'][a][b][0]}")
    for a, b in findings["two_way"]:
        print(f"  {a} <-> {b}")
    print(f"file cycles: {len(findings['file_cycles'])}")
    for group, cycle in findings["file_cycles"]:
        print(f"  {' -> '.join(cycle)}")
    total = (len(findings["upward"]) + len(findings["sideways"]) + len(findings["component_cycles"])
             + len(findings["file_cycles"]))
    print(f"summary: upward {len(findings['upward'])}, sideways {len(findings['sideways'])}, "
          f"component cycles {len(findings['component_cycles'])} (two-way pairs {len(findings['two_way'])}), "
          f"file cycles {len(findings['file_cycles'])}")
    return total


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--src", default=os.path.join(SOURCE_DIR, "src"), help="the source tree (default: src/)")
    parser.add_argument("--layers", help="the layer map (default: SRC/layers.toml)")
    parser.add_argument("--mode", choices=("report", "enforce"), help="override the map's mode")
    parser.add_argument("--quiet", action="store_true",
                        help="print the report only when it finds a violation (the build's check)")
    args = parser.parse_args()
    layers_path = args.layers or os.path.join(args.src, "layers.toml")
    try:
        findings = analyse(args.src, layers_path)
    except (MapError, OSError, tomllib.TOMLDecodeError, KeyError) as error:
        print(f"check_layers: {error}", file=sys.stderr)
        return 2
    mode = args.mode or findings["mode"]
    if mode not in ("report", "enforce"):
        print(f"check_layers: {layers_path}: mode = '{mode}' must be 'report' or 'enforce'", file=sys.stderr)
        return 2
    findings["mode"] = mode
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        violations = report(findings, args.src, layers_path)
    if violations or not args.quiet:
        print(printed.getvalue(), end="")
    if violations and mode == "enforce":
        print(f"FAILED: {violations} layering violation(s)")
        return 1
    if violations:
        print(f"report mode: {violations} violation(s) reported, not enforced (src/layers.toml: mode)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
