#!/usr/bin/env python3
"""Which files a primitive family is written into: the files a new family would touch.

    python3 scripts/family_files.py          # the quad family (the default probe)
    python3 scripts/family_files.py sphere   # another family

The probe is a family the scene format already has: every file whose code names it (an
identifier or a keyword string containing the family's name, in any case; comments and test
code left out)
is a place where the engine asks something of that family, so a new family would be written
there too. Searched: the library, the lab, the fronts (Rust, Python, JavaScript), the fuzz
dictionary and README.md; tests are not counted (a new family brings its own). Prints the files
by crate and their number.
"""

import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from layers import drop_test_code  # noqa: E402  (the same rule for test code as the layer check)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PLACES = ["src", "lab/src", "python/src", "python/lanecast", "web/src", "web/www", "fuzz"]
SKIP = re.compile(r"(^|/)(tests?|target|node_modules|corpus|artifacts)(/|$)|(^|/)tests?\.rs$|_tests\.rs$")


def code_of(path, text):
    """The text to search: Rust without comments and test code (strings kept); other files as
    they are."""
    if not path.endswith(".rs"):
        return text
    out, i = [], 0
    for m in re.finditer(r"//[^\n]*|/\*.*?\*/", text, re.S):
        out.append(text[i:m.start()])
        i = m.end()
    out.append(text[i:])
    return drop_test_code("".join(out))[0]


def main():
    family = sys.argv[1] if len(sys.argv) > 1 else "quad"
    pattern = re.compile(family, re.I)
    found = []
    for place in PLACES:
        for folder, dirs, files in os.walk(os.path.join(ROOT, place)):
            rel_folder = os.path.relpath(folder, ROOT)
            if SKIP.search(rel_folder):
                dirs[:] = []
                continue
            for name in sorted(files):
                rel = os.path.join(rel_folder, name)
                if SKIP.search(rel) or not name.endswith((".rs", ".py", ".pyi", ".js", ".mjs", ".dict")):
                    continue
                text = open(os.path.join(ROOT, rel), encoding="utf-8", errors="replace").read()
                if pattern.search(code_of(rel, text)):
                    found.append(rel)
    readme = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    if pattern.search(readme):
        found.append("README.md")
    by = {}
    for rel in found:
        by.setdefault(rel.split("/")[0] if "/" in rel else ".", []).append(rel)
    for group, rels in sorted(by.items()):
        print(f"{group}: {len(rels)}")
        for rel in rels:
            print(f"  {rel}")
    print(f"files naming `{family}`: {len(found)}")


if __name__ == "__main__":
    main()
