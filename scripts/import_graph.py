#!/usr/bin/env python3
"""The import graph of a crate's modules, and its circles.

A module is a source file (`src/a/b.rs` and `src/a/b/mod.rs` are `a::b`); it imports another when its
text names a path `crate::a::b…` (in a `use` or inline; `super::` and `self::` paths are resolved), and
imports the deepest module that path reaches. Test modules (`#[cfg(test)]` files `tests.rs`, and the
`mod tests` blocks at the end of a file) and comments (doc links) are left out: tests may look anywhere.

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
    cut = re.search(r"#\[cfg\(test\)\]\s*mod\s+tests\s*\{", text)
    text = text[: cut.start()] if cut else text
    return re.sub(r"//.*", "", text)


def targets(module: tuple[str, ...], text: str, known: set[tuple[str, ...]]) -> set[tuple[str, ...]]:
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
    out = set()
    for p in paths:
        parts = p.split("::")
        head, rest = parts[0], parts[1:]
        if head == "crate":
            base: list[str] = []
        elif head == "self":
            base = list(module)
        else:  # super
            base = list(module[:-1])
            while rest and rest[0] == "super":
                base, rest = base[:-1], rest[1:]
        full = base + [r for r in rest if r != "self"]
        # the deepest known module on this path
        for k in range(len(full), 0, -1):
            if tuple(full[:k]) in known:
                target = tuple(full[:k])
                if target != module and not module[: len(target)] == target:
                    out.add(target)
                break
    return out


def graph(crate: pathlib.Path, top: bool) -> dict[str, set[str]]:
    found = modules(crate / "src")
    known = set(found)
    edges: dict[str, set[str]] = {}
    for module, path in found.items():
        text = code(path.read_text())
        name = "::".join(module[:1] if top else module) or "lib"
        for t in targets(module, text, known):
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("crate", type=pathlib.Path)
    parser.add_argument("--top", action="store_true", help="modules at the level of the crate's top modules")
    parser.add_argument("--check", action="store_true", help="exit 1 when the graph has a circle")
    args = parser.parse_args()
    edges = graph(args.crate, args.top)
    found = circles(edges)
    for component in found:
        inner = {v: sorted(w for w in edges[v] if w in component) for v in component}
        print(" ↔ ".join(component), "   (", "; ".join(f"{v} → {', '.join(ws)}" for v, ws in inner.items()), ")")
    if not found:
        print(f"no circle among the {len(edges)} modules of {args.crate}")
    return 1 if (args.check and found) else 0


if __name__ == "__main__":
    sys.exit(main())
