#!/usr/bin/env python3
"""module_layers_check.py LIBVALVE_DIR: libvalve's modules (valve/<module>/) sit in layers, and a
module includes only modules of lower layers, so each can be read, built and tested above the
ones it uses, and the graph has no cycle. Prints every include that crosses a layer upward or
sideways, and every module the table below does not place, and exits 1 if there is any."""
import pathlib
import re
import sys

# Lowest first. config reads JSON into the laws' options (material/); remesh reports its
# meshes' distance to a reference (analysis/); phantom voxelizes models io/ reads; scene
# assembles everything a scene file declares, so it sits on top.
LAYERS = [
    ["core"],
    ["mesh", "material", "pipeline"],
    ["config", "imaging", "mechanics", "analysis"],
    ["solver", "chordae", "remesh"],
    ["io"],
    ["phantom"],
    ["scene"],
]
layer_of = {module: k for k, modules in enumerate(LAYERS) for module in modules}

root = pathlib.Path(sys.argv[1]) / "valve"
problems = []
modules = sorted({path.parent.name for path in root.glob("*/*.[ch]pp")})
for module in modules:
    if module not in layer_of:
        problems.append(f"valve/{module}/: a module the layer table of {pathlib.Path(__file__).name} does not place")
for path in sorted(root.glob("*/*.[ch]pp")):
    module = path.parent.name
    if module not in layer_of:
        continue
    for used, header in re.findall(r'#include "valve/(\w+)/([\w.]+)"', path.read_text()):
        if used == module:
            continue
        if used not in layer_of or layer_of[used] >= layer_of[module]:
            problems.append(f"{path.relative_to(root.parent)} includes {used}/{header}: "
                            f"{module} (layer {layer_of[module]}) may include only lower layers, "
                            f"{used} is layer {layer_of.get(used, '?')}")
for problem in problems:
    print(problem)
if not problems:
    print(f"{len(modules)} modules in {len(LAYERS)} layers, every include points down")
sys.exit(1 if problems else 0)
