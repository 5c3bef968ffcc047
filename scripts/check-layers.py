#!/usr/bin/env python3
"""Checks that every #include of quadtri's library runs downward through the layers.

The build enforces this too (a layer's include path holds only itself and the layers below),
but this check names the offending file and line, and also covers the tests' mirror folders.
Exit status 1 lists every violation."""
import pathlib
import re
import sys

# Each layer and the layers it may include directly; inclusion is transitive.
BELOW = {
    "math": [],
    "io": ["math"],
    "mesh": ["io"],
    "surface": ["mesh"],
    "geometry": ["surface"],
    "analysis": ["geometry"],
    "render": ["geometry"],
    "scene": ["render"],
    "report": ["scene", "analysis"],
}


def allowed(layer):
    seen, todo = {layer}, [layer]
    while todo:
        for below in BELOW[todo.pop()]:
            if below not in seen:
                seen.add(below)
                todo.append(below)
    return seen


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    include = re.compile(r'^\s*#\s*include\s+"quadtri/([a-z_]+)/')
    problems = []
    for layer in BELOW:
        ok = allowed(layer)
        for path in sorted((root / "src" / layer).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            for number, line in enumerate(path.read_text().splitlines(), 1):
                m = include.match(line)
                if m and m.group(1) not in ok:
                    problems.append(f"{path.relative_to(root)}:{number}: layer '{layer}' "
                                    f"includes '{m.group(1)}', which is not below it")
    for p in problems:
        print(p)
    if not problems:
        print(f"layers: {len(BELOW)} layers, every include runs downward")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
