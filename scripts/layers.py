#!/usr/bin/env python3
"""The layer check: every source file's references to the crate's own items, against the
declared order of layers (docs/architecture.md, "Layers").

    python3 scripts/layers.py            # check; exit 1 on an edge against the order or a cycle
    python3 scripts/layers.py --edges    # also print every edge between files

What it reads: each crate's module tree from its root (`mod NAME;` declarations), and in each
file every path that names the crate's own items: `use` trees and paths in code that start with
`crate::`, `super::`, `self::` or a child module's name. Each path is resolved to the file that
defines the item, following `pub use` re-exports, so an edge runs from the file that uses an
item to the file that defines it (a re-export is a name, not a use). Comments and string
literals are skipped. Test code (`#[cfg(test)]` items and the modules declared under it) is left
out: a test may read any layer.

What it checks, for each crate:
- the modules' layers: a file may use items of its own top-level module or of a module in a
  lower layer (the tables of docs/architecture.md, "Layers"); a use of a higher layer is an
  error;
- cycles: the strongly connected components of the graph of files (two files or more that
  reach each other), and of the graph of top-level modules. Both counts must be 0.

It is a reader of Rust text, not a compiler: a path it cannot resolve (a macro's expansion, a
method call through a trait) makes no edge. What it resolves, it resolves exactly.
"""

import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

DOC = os.path.join(ROOT, "docs", "architecture.md")


def read_layers(path=DOC):
    """Each crate's top-level modules, lowest layer first, from the ```layers CRATE blocks of
    docs/architecture.md ("Layers"), the one copy of the order: one line is one layer (text
    after `#` describes it); modules on one line may use each other's items (not in a cycle)."""
    layers, crate = {}, None
    for line in open(path, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("```layers "):
            crate = line.split()[1]
            layers[crate] = []
        elif line.startswith("```"):
            crate = None
        elif crate and line.split("#")[0].strip():
            layers[crate].append(line.split("#")[0].strip())
    if not layers:
        sys.exit(f"{path}: no ```layers blocks")
    return layers


CRATES = {
    "lanecast": ("src", ["lib.rs", "main.rs"]),
    "lanecast-lab": ("lab/src", ["lib.rs"]),
    "lanecast-python": ("python/src", ["lib.rs"]),
    "lanecast-web": ("web/src", ["lib.rs"]),
}

ITEM = re.compile(
    r"^[ \t]*(?:pub(?:\([^)]*\))?\s+)?(?:(?:const|async|unsafe|extern\s+\"C\")\s+)*"
    r"(?:fn|struct|enum|trait|type|const|static|union|macro_rules!)\s+(\w+)",
    re.M,
)
MOD_DECL = re.compile(r"^[ \t]*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;", re.M)
INLINE_MOD = re.compile(r"^[ \t]*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*\{", re.M)
USE = re.compile(r"\b(pub(?:\([^)]*\))?\s+)?use\s+([^;]*);")
PATH = re.compile(r"(?<![\w:])((?:crate|super|self)(?:\s*::\s*\w+)+)")
MACRO_EXPORT_NAME = re.compile(r"#\[macro_export\]\s*macro_rules!\s*(\w+)")


def strip(text):
    """Text with comments, string and char literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:i + 8]) and (i == 0 or not text[i - 1].isalnum()):
            m = re.match(r'r(#*)"', text[i:])
            end = text.find('"' + m.group(1), i + len(m.group(0)))
            end = n if end < 0 else end + 1 + len(m.group(1))
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j + 1
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^'\\])'", text[i:])
            if m:
                out.append("' '")
                i += len(m.group(0))
            else:  # a lifetime
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def block_end(text, open_brace):
    """Index just past the brace block opening at `open_brace`."""
    depth = 0
    for j in range(open_brace, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j + 1
    return len(text)


def drop_test_code(text):
    """Text without `#[cfg(test)]` items; and the names of modules declared under it."""
    test_mods = set()
    while True:
        m = re.search(r"#\[cfg\((?:all\()?test\b[^\]]*\]\s*", text)
        if not m:
            return text, test_mods
        start, rest = m.start(), m.end()
        while text.startswith("#[", rest):  # further attributes
            rest = text.index("]", rest) + 1
            while text[rest].isspace():
                rest += 1
        decl = MOD_DECL.match(text, rest)
        if decl:
            test_mods.add(decl.group(1))
            end = decl.end()
        else:
            semi, brace = text.find(";", rest), text.find("{", rest)
            end = semi + 1 if brace < 0 or (0 <= semi < brace) else block_end(text, brace)
        text = text[:start] + "\n" * text.count("\n", start, end) + text[end:]


def use_paths(tree):
    """The full paths of a `use` tree: `a::{b, c::{d as e}, f::*}` -> a::b, a::c::d, a::f::*."""
    tree = re.sub(r"\s*(::|\{|\}|,)\s*", r"\1", tree.strip())

    def expand(prefix, s):
        parts, depth, cur = [], 0, ""
        for ch in s:
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
                continue
            depth += ch == "{"
            depth -= ch == "}"
            cur += ch
        parts.append(cur)
        for p in filter(None, parts):
            if "{" in p:
                head, inner = p.split("{", 1)
                yield from expand(prefix + [x for x in head.split("::") if x], inner[:-1])
            else:
                yield prefix + p.split(" as ")[0].strip().split("::")

    return [p for p in expand([], tree) if p[-1] != "self"] + [
        p[:-1] for p in expand([], tree) if p[-1] == "self"
    ]


class Crate:
    def __init__(self, name, src, roots):
        self.name, self.src = name, os.path.join(ROOT, src)  # an absolute src stays as it is
        self.modules = {}  # module path (tuple) -> file (relative to the crate's src)
        self.children = {}  # module path -> {child name: child path}
        self.texts = {}  # file -> code without comments, strings and test code
        self.tests = set()  # files of test-only modules
        self.inline = {}  # module path of an inline module -> its block's text
        self.why = {}  # edge -> the paths that make it
        for r in roots:
            path = os.path.join(self.src, r)
            if os.path.exists(path):
                self.load((r[:-3],) if r != "lib.rs" else (), r, test=False)

    def load(self, modpath, rel, test):
        text, test_mods = drop_test_code(strip(open(os.path.join(self.src, rel)).read()))
        if test:
            self.tests.add(rel)
        self.modules[modpath] = rel
        self.texts[rel] = text
        kids = self.children.setdefault(modpath, {})
        here = os.path.dirname(rel) if rel.endswith(("mod.rs", "lib.rs", "main.rs")) else rel[:-3]
        for m in MOD_DECL.finditer(text):
            name = m.group(1)
            for cand in (os.path.join(here, f"{name}.rs"), os.path.join(here, name, "mod.rs")):
                if os.path.exists(os.path.join(self.src, cand)):
                    kids[name] = modpath + (name,)
                    self.load(modpath + (name,), cand, test)
                    break
        for name in test_mods:
            for cand in (os.path.join(here, f"{name}.rs"), os.path.join(here, name, "mod.rs")):
                if os.path.exists(os.path.join(self.src, cand)) and cand not in self.texts:
                    self.load(modpath + (name,), cand, True)
                    break
        for m in INLINE_MOD.finditer(text):
            sub = modpath + (m.group(1),)
            kids[m.group(1)] = sub
            self.modules[sub] = rel
            self.children.setdefault(sub, {})
            self.inline[sub] = text[m.end() - 1:block_end(text, m.end() - 1)]

    def module_text(self, mod):
        return self.inline.get(mod, self.texts[self.modules[mod]])

    def reexports(self, mod):
        """`pub use` paths of a module, each as (path, alias)."""
        out = []
        for m in USE.finditer(self.module_text(mod)):
            if m.group(1):
                for p in use_paths(m.group(2)):
                    out.append(p)
        return out

    def absolute(self, mod, path):
        """A path as written in module `mod` made absolute (a tuple), or None if external."""
        head, rest = path[0], path[1:]
        if head == "crate":
            base = ()
        elif head == "self":
            base = mod
        elif head == "super":
            base = mod[:-1]
            while rest and rest[0] == "super":
                base, rest = base[:-1], rest[1:]
        elif head in self.children.get(mod, {}):
            base, rest = mod + (head,), rest
        else:
            return None
        return base + tuple(rest)

    def resolve(self, path, seen=None):
        """The file that defines the item an absolute path names, or None."""
        seen = seen or set()
        if path in seen:
            return None
        seen.add(path)
        mod = ()
        for i, seg in enumerate(path):
            if seg in self.children.get(mod, {}):
                mod = mod + (seg,)
                continue
            if seg == "*":
                return self.modules[mod]
            text = self.module_text(mod)
            if any(m.group(1) == seg for m in ITEM.finditer(text)):
                return self.modules[mod]
            for p in self.reexports(mod):
                if p[-1] == seg or p[-1] == "*":
                    target = self.absolute(mod, p)
                    if target is None:
                        continue
                    found = self.resolve(target if p[-1] != "*" else target[:-1] + (seg,), seen)
                    if found:
                        return found
            return self.modules[mod]
        return self.modules[mod]

    def edges(self):
        """{(from file, to file)} for every use of one file's item in another (non-test)."""
        out = set()
        for mod, rel in self.modules.items():
            if rel in self.tests or mod in self.inline:
                continue
            text = self.texts[rel]
            paths = []
            for m in USE.finditer(text):
                if not m.group(1):  # a re-export makes no edge
                    paths += use_paths(m.group(2))
            code = USE.sub("", text)
            paths += [re.sub(r"\s+", "", m.group(1)).split("::") for m in PATH.finditer(code)]
            for name in self.children.get(mod, {}):
                paths += [[name, m.group(1)] for m in re.finditer(rf"(?<![\w:]){name}::(\w+)", code)]
            for p in paths:
                target = self.absolute(self.inner_module(mod, rel, p), p)
                if target is None:
                    continue
                dest = self.resolve(target)
                if dest and dest != rel and dest not in self.tests:
                    out.add((rel, dest))
                    self.why.setdefault((rel, dest), set()).add("::".join(p))
        return out

    def inner_module(self, mod, rel, path):
        return mod

    def top(self, rel):
        for mod, r in self.modules.items():
            if r == rel:
                return mod[0] if mod else "lib"
        raise KeyError(rel)


def sccs(nodes, edges):
    """Tarjan's strongly connected components with more than one node."""
    graph = {n: [] for n in nodes}
    for a, b in edges:
        graph.setdefault(a, []).append(b)
        graph.setdefault(b, [])
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

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
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def check(name, show_edges, src=None, layers=None):
    """The errors of one crate (and a summary line printed)."""
    src_default, roots = CRATES.get(name, ("src", ["lib.rs"]))
    src = src or src_default
    crate = Crate(name, src, roots)
    rank = {m: i for i, line in enumerate(layers or read_layers()[name]) for m in line.split()}
    edges = crate.edges()
    errors = []
    tops = {rel: crate.top(rel) for rel in crate.texts}
    for rel, top in sorted(tops.items()):
        if top not in rank and rel not in crate.tests:
            errors.append(f"{src}/{rel}: module `{top}` has no layer in docs/architecture.md")
    against = sorted(
        (a, b) for a, b in edges
        if tops[a] != tops[b] and rank.get(tops[b], -1) > rank.get(tops[a], -1)
    )
    for a, b in against:
        errors.append(f"{src}/{a} uses {src}/{b}: `{tops[b]}` is above `{tops[a]}` "
                      f"({', '.join(sorted(crate.why[a, b]))})")
    # A child's use of its parent's own items is Rust's `super::`: the parent is where what its
    # children share is kept, so that edge is not counted among cycles (it still counts for
    # the layers, where parent and child are one module).
    parent = {rel: crate.modules[mod[:-1]] for mod, rel in crate.modules.items() if mod}
    file_cycles = sccs(crate.texts, {(a, b) for a, b in edges if parent.get(a) != b})
    module_edges = {(tops[a], tops[b]) for a, b in edges if tops[a] != tops[b]}
    module_cycles = sccs(set(tops.values()), module_edges)
    for c in file_cycles:
        errors.append(f"cycle among files: {', '.join(f'{src}/{f}' for f in c)}")
        for a, b in sorted(edges):
            if a in c and b in c and parent.get(a) != b:
                errors.append(f"    {a} -> {b}: {', '.join(sorted(crate.why[a, b]))}")
    for c in module_cycles:
        errors.append(f"cycle among modules: {', '.join(c)}")
    if show_edges:
        for a, b in sorted(edges):
            print(f"  {src}/{a} -> {src}/{b}")
    files = len(crate.texts) - len(crate.tests)
    print(f"{name}: {files} files, {len(edges)} edges, {len(against)} against the layers, "
          f"{len(file_cycles)} cycles among files, {len(module_cycles)} among modules")
    return errors


SELF_TEST = {
    "lib.rs": "mod low;\nmod mid;\nmod top;\nmod pair;\n",
    # An upward use (low -> mid), one in test code and one in a comment (neither counts).
    "low.rs": "pub struct L;\npub fn f() { let _ = crate::mid::M; }\n"
              "// crate::top::T\n#[cfg(test)]\nmod tests { use crate::top::T; }\n",
    # A parent and its children: the children use the parent's items, the parent theirs (no
    # cycle); two siblings use each other (a cycle).
    "mid.rs": "mod a;\nmod b;\npub struct M;\npub use a::A;\npub fn g() { b::h(); }\n",
    "mid/a.rs": "use super::M;\npub struct A;\npub fn k() { super::b::h(); }\n",
    "mid/b.rs": "use super::{M, a::A};\npub fn h() { let _ = crate::low::L; }\n",
    "top.rs": "use crate::mid::{self, A};\npub struct T;\n",
    # A re-export is a name, not a use: pair names top's item, and top's layer is pair's.
    "pair.rs": "pub use crate::top::T as U;\npub fn p() { let _: crate::mid::A; }\n",
}


def self_test():
    """The check on a small crate written to break each rule once: it must find each."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        for rel, text in SELF_TEST.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            open(os.path.join(tmp, rel), "w").write(text)
        errors = check("self-test", False, tmp, ["low", "mid", "top pair", "lib"])
    against = [e for e in errors if "is above" in e]
    cycles = [e for e in errors if e.startswith("cycle among")]
    ok = (len(against) == 1 and "low.rs uses" in against[0] and "mid.rs" in against[0]
          and len(cycles) == 2 and "mid/a.rs" in cycles[0] and "mid/b.rs" in cycles[0]
          and "low" in cycles[1] and "mid" in cycles[1])
    if not ok:
        print("self-test failed; the check gave:", *errors, sep="\n  ", file=sys.stderr)
        sys.exit(1)
    print("self-test: the upward use, the cycle of siblings and the cycle of modules found; "
          "test code, comments and a parent with its children passed")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--edges", action="store_true", help="print every edge between files")
    ap.add_argument("--self-test", action="store_true",
                    help="check a small crate that breaks each rule once, first")
    ap.add_argument("crates", nargs="*", default=list(CRATES), help="crates to check")
    args = ap.parse_args()
    if args.self_test:
        self_test()
    errors = []
    for name in args.crates:
        errors += check(name, args.edges)
    for e in errors:
        print(e, file=sys.stderr)
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
