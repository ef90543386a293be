#!/usr/bin/env python3
"""The import graph of a crate's modules, and its circles.

A module is a source file (`src/a/b.rs` and `src/a/b/mod.rs` are `a::b`); it imports another when its
text names a path `crate::a::b…` (in a `use` or inline; `super::` and `self::` paths are resolved), and
imports the deepest module that path reaches. Test modules (`#[cfg(test)]` files `tests.rs`, and the
`#[cfg(test)]` modules at the end of a file) and comments (doc links) are left out: tests may look anywhere.

    python3 scripts/import_graph.py crates/ddirac            # the circles, one per line
    python3 scripts/import_graph.py crates/ddirac --top      # at the level of the top modules
    python3 scripts/import_graph.py crates/ddirac --check    # exit 1 when there is a circle
"""

import argparse
import pathlib
import re
import sys

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{([^;]*)\};", re.S)


def modules(src: pathlib.Path) -> dict[tuple[str, ...], pathlib.Path]:
    found = {}
    for path in src.rglob("*.rs"):
        parts = list(path.relative_to(src).with_suffix("").parts)
        if parts[-1] in ("mod", "lib", "main"):
            parts = parts[:-1]
        if parts and parts[-1] == "tests":
            continue
        found[tuple(parts)] = path
    return found


def code(text: str) -> str:
    """The text without comments (doc links are not imports) and without its `mod tests` block."""
    cut = re.search(r"#\[cfg\(test\)\]\s*(pub(\([a-z]+\))?\s+)?mod\s+\w+\s*\{", text)
    text = text[: cut.start()] if cut else text
    return re.sub(r"//.*", "", text)


def uses(text: str) -> list[str]:
    """The paths a text names, with `use a::{b, c}` groups spelled out."""
    paths = []
    for m in USE_GROUP.finditer(text):
        base = m.group(1) + m.group(2)
        for item in re.split(r",", m.group(3)):
            item = item.strip().split(" as ")[0].strip()
            item = re.sub(r"::\{.*", "", item, flags=re.S)
            if item:
                paths.append(base + "::" + item)
    for m in PATH.finditer(text):
        paths.append(m.group(1) + m.group(2))
    return paths


REEXPORT = re.compile(r"\bpub(?:\([a-z]+\))?\s+use\s+([^;]*);", re.S)


def absolute(module: tuple[str, ...], path: list[str]) -> list[str]:
    """`path` as written in `module` (from `crate`, `self`, `super` or a child module) from the crate root."""
    head, rest = path[0], path[1:]
    if head == "crate":
        base: list[str] = []
    elif head == "self":
        base = list(module)
    elif head == "super":
        base = list(module[:-1])
        while rest and rest[0] == "super":
            base, rest = base[:-1], rest[1:]
    else:  # a child module, or an external crate (which no module of this crate is named after)
        base, rest = list(module), path
    return base + [r for r in rest if r != "self"]


def reexports(module: tuple[str, ...], text: str) -> dict[str, list[str]]:
    """The names `module` re-exports (`pub use a::b::{C, D}`), each with the absolute path it comes from."""
    found = {}
    for m in REEXPORT.finditer(text):
        body = re.sub(r"\s+", "", m.group(1))
        group = re.match(r"(.*?)::\{(.*)\}$", body)
        items = [(group.group(1), i) for i in group.group(2).split(",") if i] if group else [(None, body)]
        for prefix, item in items:
            item = item.split("as")[0] if "as" in item and "::" not in item.split("as")[-1] else item
            path = (prefix.split("::") if prefix else []) + item.split("::")
            if path and path[-1] not in ("self", "*", ""):
                found[path[-1]] = absolute(module, path)
    return found


def targets(module: tuple[str, ...], text: str, known: set[tuple[str, ...]],
            exports: dict[tuple[str, ...], dict[str, list[str]]]) -> set[tuple[str, ...]]:
    out = set()
    for p in uses(text):
        full = absolute(module, p.split("::"))
        for _ in range(8):  # follow re-exports to the module that defines the item
            k = max((k for k in range(len(full) + 1) if tuple(full[:k]) in known), default=-1)
            if k < 0:
                break
            names = exports.get(tuple(full[:k]), {})
            if k < len(full) and full[k] in names and names[full[k]] != full[: k + 1]:
                full = names[full[k]] + full[k + 1:]
                continue
            target = tuple(full[:k])
            if target and target != module and not module[: len(target)] == target:
                out.add(target)
            break
    return out


def graph(crate: pathlib.Path, top: bool) -> dict[str, set[str]]:
    found = modules(crate / "src")
    known = set(found)
    exports = {module: reexports(module, code(path.read_text())) for module, path in found.items()}
    edges: dict[str, set[str]] = {}
    tests = set()
    for module, path in found.items():
        for m in re.finditer(r"#\[cfg\(test\)\]\s*(pub(\([a-z]+\))?\s+)?mod\s+(\w+)\s*;", path.read_text()):
            tests.add(module + (m.group(3),))
    for module, path in found.items():
        if module in tests:
            continue
        text = code(path.read_text())
        name = "::".join(module[:1] if top else module) or "lib"
        for t in targets(module, text, known, exports):
            target = "::".join(t[:1] if top else t)
            if target != name and t:
                edges.setdefault(name, set()).add(target)
        edges.setdefault(name, set())
    return edges


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return sorted(out)


def layers(edges: dict[str, set[str]]) -> list[list[str]]:
    """The modules of an acyclic graph by the length of the longest chain of imports below each."""
    depth: dict[str, int] = {}

    def of(v: str) -> int:
        if v not in depth:
            depth[v] = 1 + max((of(w) for w in edges.get(v, ())), default=-1)
        return depth[v]

    for v in edges:
        of(v)
    return [sorted(v for v in depth if depth[v] == d) for d in range(max(depth.values(), default=-1) + 1)]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("crate", type=pathlib.Path)
    parser.add_argument("--top", action="store_true", help="modules at the level of the crate's top modules")
    parser.add_argument("--check", action="store_true", help="exit 1 when the graph has a circle")
    parser.add_argument("--why", nargs=2, metavar=("FROM", "TO"), help="the paths by which module FROM imports TO")
    parser.add_argument("--layers", action="store_true",
                        help="the modules by layer: each imports only from the layers below it")
    args = parser.parse_args()
    if args.why:
        found = modules(args.crate / "src")
        exports = {m: reexports(m, code(p.read_text())) for m, p in found.items()}
        source, target = (tuple(x.split("::")) for x in args.why)
        for p in uses(code(found[source].read_text())):
            if target in targets(source, p, set(found), exports):
                print(p)
        return 0
    edges = graph(args.crate, args.top)
    found = circles(edges)
    for component in found:
        inner = {v: sorted(w for w in edges[v] if w in component) for v in component}
        print(" ↔ ".join(component), "   (", "; ".join(f"{v} → {', '.join(ws)}" for v, ws in inner.items()), ")")
    if not found:
        print(f"no circle among the {len(edges)} modules of {args.crate}")
    if args.layers:  # a circle counts as one module, its names joined by ↔
        merged = {v: " ↔ ".join(c) for c in found for v in c}
        condensed: dict[str, set[str]] = {}
        for v, ws in edges.items():
            a = merged.get(v, v)
            condensed.setdefault(a, set()).update(merged.get(w, w) for w in ws if merged.get(w, w) != a)
        for depth, layer in enumerate(layers(condensed)):
            print(f"{depth:3}  {'  '.join(layer)}")
    return 1 if (args.check and found) else 0


if __name__ == "__main__":
    sys.exit(main())
