#!/usr/bin/env python3
"""module_cycles_check.py LIBVALVE_DIR: the modules of libvalve (valve/<module>/) form no include
cycle, so each can be read, built and tested above the ones it uses. Prints the graph's cycles
(each with one include that makes each of its edges) and exits 1 if there is any."""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1]) / "valve"
edges = {}
for path in sorted(root.glob("*/*.[ch]pp")):
    module = path.parent.name
    for used, header in re.findall(r'#include "valve/(\w+)/([\w.]+)"', path.read_text()):
        if used != module:
            edges.setdefault(module, {}).setdefault(used, f"{path.relative_to(root.parent)} includes {used}/{header}")

cycles, state, stack = [], {}, []


def visit(module):
    state[module] = "open"
    stack.append(module)
    for used in sorted(edges.get(module, {})):
        if state.get(used) == "open":
            cycle = stack[stack.index(used):] + [used]
            cycles.append(cycle)
        elif used not in state:
            visit(used)
    stack.pop()
    state[module] = "done"


for module in sorted(edges):
    if module not in state:
        visit(module)
for cycle in cycles:
    print(" -> ".join(cycle) + ": " + "; ".join(edges[a][b] for a, b in zip(cycle, cycle[1:])))
if not cycles:
    print(f"{len(edges)} modules, no include cycle")
sys.exit(1 if cycles else 0)
