#!/usr/bin/env python3
"""Circles between the files of a Rust crate: file A uses file B and B uses A, directly or
through other files.

    python3 scripts/module_cycles.py                 # every crate in crates/
    python3 scripts/module_cycles.py crates/plan     # one crate
    python3 scripts/module_cycles.py --edges crates/plan   # and list the edges

An edge A -> B is a path in A's code that names an item of B: `use crate::b::X;`,
`crate::b::f(..)`, `super::X`, `self::b::X`, or `b::X` where `b` is a child module of A's
module (expanded through `use` trees with braces and globs). A `mod b;` declaration is not an
edge (it owns B, it does not use it). A path through a `pub use` re-export counts as using the
module the item comes from (`crate::FacadeError` with `pub use error::FacadeError` in lib.rs is
an edge to error.rs), so re-exporting does not make a circle of its own. Comments and string
literals are ignored. Code under `#[cfg(test)]` (inline `mod tests { .. }` blocks and files
declared under `#[cfg(test)]`) is kept apart: circles of library code are listed first, then
the circles that appear only when test code counts too. An edge from a file to itself (an
inline `mod tests` using `super::*`) is no edge.

Exit status: 0 with no circles in library code, 1 otherwise (2 on usage errors). Standard
library only.
"""

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip(src):
    """`src` with comments removed and string / char literal contents blanked (lengths kept
    only approximately; positions are not needed later)."""
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            i = n if j < 0 else j
            continue
        if src.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if src.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif src.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    i += 1
            out.append(" ")
            continue
        m = re.match(r'(?:b|c)?r(#*)"', src[i:i + 260])
        if m and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_")):
            end = '"' + m.group(1)
            j = src.find(end, i + m.end())
            i = n if j < 0 else j + len(end)
            out.append('""')
            continue
        if c == '"' or (c in "bc" and src.startswith('"', i + 1)
                        and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_"))):
            i = i + 1 if c == '"' else i + 2
            while i < n and src[i] != '"':
                i += 2 if src[i] == "\\" else 1
            i += 1
            out.append('""')
            continue
        if c == "'":
            # A char literal ('x', '\n', '\u{1F600}') or a lifetime ('a).
            if src.startswith("\\", i + 1):
                j = src.find("'", i + 2)
                i = n if j < 0 else j + 1
                out.append("' '")
                continue
            if i + 2 < n and src[i + 2] == "'":
                i += 3
                out.append("' '")
                continue
        out.append(c)
        i += 1
    return "".join(out)


def parse_use_tree(text):
    """Expands a use tree (`crate::a::{b::X, c::{self, Y as Z}, *}`) into (segments, alias)
    pairs; `self` in braces names the prefix itself."""
    tokens = re.findall(r"::|[{},*]|" + IDENT, text)
    pos = 0

    def tree(prefix):
        nonlocal pos
        segs = list(prefix)
        out = []
        while pos < len(tokens):
            t = tokens[pos]
            if t == "{":
                pos += 1
                while pos < len(tokens) and tokens[pos] != "}":
                    out.extend(tree(segs))
                    if pos < len(tokens) and tokens[pos] == ",":
                        pos += 1
                pos += 1
                return out
            if t == "*":
                pos += 1
                return [(segs + ["*"], None)]
            if t == "::":
                pos += 1
                continue
            if t in ",}":
                break
            if t == "as":
                alias = tokens[pos + 1] if pos + 1 < len(tokens) else None
                pos += 2
                return [(segs, alias)]
            if t == "self" and segs:
                pos += 1
                continue
            segs.append(t)
            pos += 1
        if not out:
            out.append((segs, None))
        return out

    return tree([])


class Crate:
    def __init__(self, path):
        self.path = Path(path)
        src = self.path / "src"
        roots = [p for p in (src / "lib.rs", src / "main.rs") if p.exists()]
        if not roots:
            raise SystemExit(f"{path}: no src/lib.rs or src/main.rs")
        self.root = roots[0]
        self.files = {}  # file -> dict(module=tuple, test=bool, text=str)
        self.modules = {}  # module path tuple -> file
        self.children = {}  # module path tuple -> set of child names
        self.warnings = []
        self._load(self.root, (), False)
        self.reexports = {f: self._reexports(f) for f in self.files}

    def _load(self, file, module, test):
        text = strip(file.read_text(encoding="utf-8"))
        self.files[file] = {"module": module, "test": test, "text": text}
        self.modules[module] = file
        self.children.setdefault(module, set())
        base = file.parent if file.name in ("lib.rs", "main.rs", "mod.rs") else \
            file.parent / file.stem
        for scope, is_test, start, end in self._inline_modules(text):
            self.modules.setdefault(module + scope, file)
            if scope:
                self.children.setdefault(module + scope[:-1], set()).add(scope[-1])
                self.children.setdefault(module + scope, set())
        for m in re.finditer(
            r"((?:#\[[^\]]*\]\s*)*)(?:pub(?:\([^)]*\))?\s+)?mod\s+(" + IDENT + r")\s*;", text
        ):
            attrs, name = m.group(1), m.group(2)
            scope = self._scope_at(text, m.start())
            if scope:
                self.warnings.append(f"{file}: `mod {name};` inside an inline module skipped")
                continue
            pm = re.search(r'#\[path\s*=\s*""\]', attrs)
            if pm:
                self.warnings.append(f"{file}: #[path] on `mod {name}` not followed")
                continue
            child = base / f"{name}.rs"
            if not child.exists():
                child = base / name / "mod.rs"
            if not child.exists():
                self.warnings.append(f"{file}: no file for `mod {name};`")
                continue
            self.children[module].add(name)
            self._load(child, module + (name,), test or "cfg(test)" in attrs)

    @staticmethod
    def _inline_modules(text):
        """(scope, is_test, start, end) of every inline `mod name { .. }` block; scope is the
        tuple of inline module names from the file's module down."""
        found = []
        stack = []  # (name, depth at which it closes, is_test, start)
        depth = 0
        pending = None
        i = 0
        pattern = re.compile(r"((?:#\[[^\]]*\]\s*)*)(?:pub(?:\([^)]*\))?\s+)?mod\s+(" + IDENT
                             + r")\s*\{")
        while i < len(text):
            c = text[i]
            if c == "m" or c == "#" or c == "p":
                m = pattern.match(text, i)
                if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
                    pending = (m.group(2), "cfg(test)" in m.group(1))
                    i = m.end() - 1
                    continue
            if c == "{":
                depth += 1
                if pending:
                    parent_test = stack[-1][2] if stack else False
                    stack.append((pending[0], depth, pending[1] or parent_test, i))
                    pending = None
            elif c == "}":
                if stack and stack[-1][1] == depth:
                    name, _, is_test, start = stack.pop()
                    found.append((tuple(s[0] for s in stack) + (name,), is_test, start, i))
                depth -= 1
            i += 1
        return found

    def _scope_at(self, text, pos):
        best = ()
        for scope, _, start, end in self._inline_modules(text):
            if start < pos < end and len(scope) > len(best):
                best = scope
        return best

    def _spans(self, file):
        """Inline module spans of `file`: list of (scope, is_test, start, end)."""
        info = self.files[file]
        if "spans" not in info:
            info["spans"] = self._inline_modules(info["text"])
        return info["spans"]

    def _context(self, file, pos):
        """(module path, is_test) of the code at `pos` in `file`."""
        info = self.files[file]
        scope, test = (), info["test"]
        for s, is_test, start, end in self._spans(file):
            if start < pos < end and len(s) >= len(scope):
                scope, test = s, info["test"] or is_test
        return info["module"] + scope, test

    def _resolve(self, module, segs, seen=None):
        """The file a path names an item of, or None for paths outside the crate."""
        if not segs:
            return None
        segs = list(segs)
        first = segs[0]
        if first == "crate":
            cur, segs = (), segs[1:]
        elif first in ("super", "self"):
            cur = module
            while segs and segs[0] in ("super", "self"):
                if segs[0] == "super":
                    if not cur:
                        return None
                    cur = cur[:-1]
                segs = segs[1:]
        else:
            # A child module of this module, or (from an inline `mod tests`, which imports its
            # file's names with `use super::*`) of an enclosing one.
            cur = module
            while cur and first not in self.children.get(cur, ()) and cur in self.modules \
                    and cur[:-1] in self.modules and self.modules[cur[:-1]] == self.modules[cur]:
                cur = cur[:-1]
            if first not in self.children.get(cur, ()):
                return None
        while segs and segs[0] in self.children.get(cur, ()):
            cur, segs = cur + (segs[0],), segs[1:]
        file = self.modules.get(cur)
        if file is None:
            return None
        # An item re-exported by `pub use`: the module it comes from.
        if segs and segs[0] != "*":
            target = self.reexports.get(file, {}).get(segs[0]) if hasattr(self, "reexports") \
                else None
            if target is not None:
                seen = seen or set()
                key = (cur, segs[0])
                if key not in seen:
                    seen.add(key)
                    tm, tsegs = target
                    resolved = self._resolve(tm, tsegs, seen)
                    if resolved is not None:
                        return resolved
        return file

    def _uses(self, file):
        """(start, segments, alias, is_pub) of every `use` item in `file`."""
        text = self.files[file]["text"]
        for m in re.finditer(r"(?<![\w:])(pub(?:\([^)]*\))?\s+)?use\s+([^;]*);", text):
            for segs, alias in parse_use_tree(m.group(2)):
                yield m.start(), segs, alias, m.group(1) is not None

    def _reexports(self, file):
        out = {}
        for pos, segs, alias, is_pub in self._uses(file):
            if not is_pub or not segs or segs[-1] == "*":
                continue
            module, _ = self._context(file, pos)
            if module != self.files[file]["module"]:
                continue
            out[alias or segs[-1]] = (module, segs)
        return out

    def edges(self):
        """{(a, b): is_test_only} over files a != b."""
        found = {}

        def add(a, b, test):
            if b is None or a == b:
                return
            found[(a, b)] = found.get((a, b), True) and test

        for file, info in self.files.items():
            text = info["text"]
            use_spans = []
            for m in re.finditer(r"(?<![\w:])(pub(?:\([^)]*\))?\s+)?use\s+([^;]*);", text):
                use_spans.append((m.start(), m.end()))
                module, test = self._context(file, m.start())
                for segs, _ in parse_use_tree(m.group(2)):
                    add(file, self._resolve(module, segs), test)
            path_re = re.compile(r"(?<![\w:])((?:" + IDENT + r")(?:\s*::\s*" + IDENT + r")+)")
            for m in path_re.finditer(text):
                if any(s <= m.start() < e for s, e in use_spans):
                    continue
                if re.search(r"\bin\s+$", text[max(0, m.start() - 4):m.start()]):
                    continue  # pub(in crate::x)
                segs = [s.strip() for s in m.group(1).split("::")]
                module, test = self._context(file, m.start())
                add(file, self._resolve(module, segs), test)
        return found

    def rel(self, file):
        return str(file.relative_to(self.path / "src"))


def cycles(nodes, edges):
    """Strongly connected components with more than one file (Tarjan), each as a sorted list,
    and one shortest circle through each."""
    graph = {n: sorted({b for (a, b) in edges if a == n}) for n in nodes}
    index, low, on, stack, comps = {}, {}, set(), [], []
    counter = [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
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
            if len(comp) > 1:
                comps.append(sorted(comp))

    for n in sorted(nodes):
        if n not in index:
            visit(n)
    out = []
    for comp in comps:
        members = set(comp)
        start = comp[0]
        # Breadth-first search for the shortest way back to `start` inside the component.
        prev = {start: None}
        queue = [start]
        circle = None
        while queue and circle is None:
            nxt = []
            for v in queue:
                for w in graph[v]:
                    if w not in members:
                        continue
                    if w == start:
                        path = [v]
                        while prev[path[-1]] is not None:
                            path.append(prev[path[-1]])
                        circle = list(reversed(path)) + [start]
                        break
                    if w not in prev:
                        prev[w] = v
                        nxt.append(w)
                if circle:
                    break
            queue = nxt
        out.append((comp, circle))
    return out


def report(crate_dir, show_edges):
    crate = Crate(crate_dir)
    edges = crate.edges()
    name = crate.path.name
    lib_edges = {e for e, test in edges.items() if not test}
    lib = cycles(crate.files, lib_edges)
    every = cycles(crate.files, set(edges))
    lib_sets = [set(c) for c, _ in lib]
    test_only = [(c, p) for c, p in every if set(c) not in lib_sets]
    print(f"{name}: {len(crate.files)} files, {len(lib_edges)} edges "
          f"(+{len(edges) - len(lib_edges)} from test code)")
    for w in crate.warnings:
        print(f"  warning: {w}")
    if show_edges:
        for (a, b), test in sorted(edges.items(), key=lambda kv: (str(kv[0][0]), str(kv[0][1]))):
            print(f"  {crate.rel(a)} -> {crate.rel(b)}{'  (tests)' if test else ''}")
    for label, found in (("library code", lib), ("with test code", test_only)):
        for comp, circle in found:
            files = ", ".join(crate.rel(f) for f in comp)
            way = " -> ".join(crate.rel(f) for f in circle) if circle else "?"
            print(f"  circle ({label}): {len(comp)} files {{{files}}}: {way}")
    if not lib and not test_only:
        print("  no circles")
    return len(lib)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("crates", nargs="*", help="crate folders (default: every crates/*)")
    ap.add_argument("--edges", action="store_true", help="list the edges too")
    args = ap.parse_args()
    dirs = args.crates or sorted(p for p in (ROOT / "crates").iterdir()
                                 if (p / "Cargo.toml").exists())
    total = 0
    for d in dirs:
        total += report(Path(d), args.edges)
    sys.exit(1 if total else 0)


if __name__ == "__main__":
    main()
