#!/usr/bin/env python3
"""The layering of the source tree, checked (a CTest test and CI run it).

Floors, bottom up: sim/ (physics), io/ (loading, writing, pages), optimize/ (studies, maps),
app/ (the CLI). A file may include its own floor and the floors below it, never one above:
sim/ includes nothing from io/, optimize/ or app/; io/ nothing from optimize/ or app/;
optimize/ nothing from app/. Also: the project's includes form no cycle.

    python3 scripts/check_layers.py [ROOT]     exit 0 when both hold, 1 with the offenders
"""
import pathlib
import re
import sys

FLOORS = ["sim", "io", "optimize", "app"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def project_includes(root, path):
    """The project files `path` includes (quoted includes that exist under root)."""
    out = []
    for name in INCLUDE.findall(path.read_text(errors="replace")):
        target = root / name
        if target.is_file():
            out.append(target.relative_to(root).as_posix())
    return out


def floor_of(rel):
    top = rel.split("/", 1)[0]
    return FLOORS.index(top) if top in FLOORS else None


def layer_violations(root, graph):
    bad = []
    for src, targets in graph.items():
        f = floor_of(src)
        if f is None:
            continue
        for t in targets:
            g = floor_of(t)
            if g is not None and g > f:
                bad.append(f"{src} includes {t}: {FLOORS[f]}/ must not include {FLOORS[g]}/")
    return bad


def cycles(graph):
    """One include cycle per strongly connected component of size > 1 (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, []):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in graph.get(v, []):
                found.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def self_test():
    """The checks catch what they must: a sim/ file including io/, and a two-header cycle."""
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d)
        for rel, text in {"sim/a.hpp": '#include "io/b.hpp"\n', "io/b.hpp": "",
                          "app/c.hpp": '#include "app/d.hpp"\n', "app/d.hpp": '#include "app/c.hpp"\n'}.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
        graph = {r: project_includes(root, root / r) for r in ["sim/a.hpp", "io/b.hpp", "app/c.hpp", "app/d.hpp"]}
        assert layer_violations(root, graph) == ["sim/a.hpp includes io/b.hpp: sim/ must not include io/"]
        assert cycles(graph) == [["app/c.hpp", "app/d.hpp"]]


def main():
    self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    root = root.resolve()
    files = [p for d in FLOORS + ["tests", "bench", "fuzz", "python"] if (root / d).is_dir()
             for p in (root / d).rglob("*") if p.suffix in (".cpp", ".hpp", ".h")]
    graph = {p.relative_to(root).as_posix(): project_includes(root, p) for p in files}
    problems = layer_violations(root, graph)
    problems += ["include cycle: " + " <-> ".join(c) for c in cycles(graph)]
    for p in problems:
        print(p)
    print(f"check_layers: {len(graph)} files, {sum(map(len, graph.values()))} project includes, "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
