#!/usr/bin/env python3
"""The library's public surface, counted from its documentation.

    python3 scripts/public_items.py            # runs `cargo doc --no-deps -p lanecast` first
    python3 scripts/public_items.py --no-build # counts target/doc/lanecast as it is

An item is public when rustdoc gives it a page of its own (a module, struct, enum, trait,
function, constant, static, type alias or macro); rustdoc's redirect pages (an item re-exported
under a second path) are not counted again. The members listed on those pages are counted
beside them: inherent methods (not methods of trait implementations), struct fields, enum
variants and trait methods. Prints one line per kind and the total of items.
"""

import argparse
import collections
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "target", "doc", "lanecast")
KINDS = ("mod", "struct", "enum", "trait", "fn", "constant", "static", "type", "macro")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--no-build", action="store_true", help="count the documentation as it is")
    args = ap.parse_args()
    if not args.no_build:
        subprocess.run(["cargo", "doc", "--no-deps", "-p", "lanecast", "--quiet"], cwd=ROOT,
                       check=True)
    if not os.path.isdir(DOC):
        sys.exit(f"{DOC} is missing: run `cargo doc --no-deps -p lanecast` first")
    items, members = collections.Counter(), collections.Counter()
    for folder, _, files in os.walk(DOC):
        for name in files:
            if not name.endswith(".html") or name in ("all.html",):
                continue
            text = open(os.path.join(folder, name), encoding="utf-8").read()
            if 'http-equiv="refresh"' in text:
                continue  # a re-export's redirect to the item's page
            kind = "mod" if name == "index.html" else name.split(".", 1)[0]
            if kind not in KINDS:
                continue
            items[kind] += 1
            inherent = text.split('id="trait-implementations"')[0]
            inherent = inherent.split('id="synthetic-implementations"')[0]
            for member in ("method", "structfield", "variant", "tymethod"):
                members[member] += len(re.findall(rf'id="{member}\.\w+"', inherent))
    for kind in KINDS:
        print(f"{kind:10} {items[kind]:5}")
    names = {"method": "methods", "structfield": "fields", "variant": "variants",
             "tymethod": "trait fns"}
    for member, label in names.items():
        print(f"{label:10} {members[member]:5}  (members)")
    print(f"{'items':10} {sum(items.values()):5}")


if __name__ == "__main__":
    main()
