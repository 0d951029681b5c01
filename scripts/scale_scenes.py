"""Where the measurement scripts find a scene named on their command line: the path as given,
else the scaling scene `target/scale/NAME.sc`, which `../shared/anchors/gen_scenes.py` writes."""

import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene_path(name):
    """`name` if it exists, else `target/scale/NAME.sc`; exits with a message naming both."""
    if os.path.exists(name):
        return name
    path = os.path.join(ROOT, "target", "scale", name + ".sc")
    if not os.path.exists(path):
        sys.exit(f"{name}: no such file, nor {path}; the scaling scenes K_N are written into "
                 "target/scale/ by `python3 ../shared/anchors/gen_scenes.py --out target/scale` "
                 "(../shared/anchors lies beside the checkout, not in this repository)")
    return path
