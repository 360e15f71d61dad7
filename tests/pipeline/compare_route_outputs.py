#!/usr/bin/env python3
"""compare_route_outputs.py A B: the tables and meshes of two output folders of one pipeline.

Every CSV in A (required pipelines' folders included) must exist in B with the same header and the same cells, except
columns whose name says they hold a measured time (wall_time_s, wall_s, cpu_s: they differ
from run to run; simulated_time_ms is a result and is compared).
Every .vtp in A must exist in B byte for byte, and B must have no other:
both routes run the same executables with the same arguments, and the stages are
deterministic (DESIGN.md), so any difference is a difference in what ran.
Prints what it compared; exit 1 on the first difference.
"""
import csv
import os
import sys


def timing(column):
    return "wall" in column.lower() or "cpu" in column.lower()


def table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if not timing(name)]
    return [[row[i] if i < len(row) else "" for i in keep] for row in rows], len(rows[0]) - len(keep)


def files(root, suffix):
    """Relative paths of the files ending in suffix, outside snakemake's own folder."""
    found = set()
    for folder, subfolders, names in os.walk(root):
        subfolders[:] = [d for d in subfolders if d != ".snakemake"]
        found.update(os.path.relpath(os.path.join(folder, f), root) for f in names if f.endswith(suffix))
    return found


def main(a, b):
    csvs = sorted(files(a, ".csv"))
    if not csvs:
        sys.exit(f"no CSV table in {a}")
    for name in csvs:
        if not os.path.isfile(os.path.join(b, name)):
            sys.exit(f"{name}: in {a}, missing in {b}")
        ta, skipped = table(os.path.join(a, name))
        tb, _ = table(os.path.join(b, name))
        if ta != tb:
            sys.exit(f"{name}: tables differ\n{a}: {ta}\n{b}: {tb}")
        print(f"{name}: {len(ta) - 1} rows equal ({skipped} measured-time column(s) left out)")
    ma, mb = files(a, ".vtp"), files(b, ".vtp")
    if not ma:
        sys.exit(f"no .vtp in {a}")
    if ma != mb:
        sys.exit(f"meshes differ in name: only in {a}: {sorted(ma - mb)}; only in {b}: {sorted(mb - ma)}")
    for rel in sorted(ma):
        with open(os.path.join(a, rel), "rb") as fa, open(os.path.join(b, rel), "rb") as fb:
            if fa.read() != fb.read():
                sys.exit(f"{rel}: bytes differ between {a} and {b}")
    print(f"{len(ma)} meshes byte-identical")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
