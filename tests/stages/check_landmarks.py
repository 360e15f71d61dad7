#!/usr/bin/env python3
"""check_landmarks.py FILE.mrk.json

The landmark curves of a single leaflet (the sample aortic leaflet): Slicer markups (schema
v1.0.3 "@schema", LPS) holding an open annulus arc and an open free edge that meet at the two
attached corners, the free edge running from one corner to the other.
"""
import json
import sys

doc = json.load(open(sys.argv[1]))
errors = []
if "markups-schema-v1.0.3" not in doc.get("@schema", ""):
    errors.append(f"@schema: {doc.get('@schema')!r}")
curves = {m["name"]: m for m in doc["markups"]}
if set(curves) != {"annulus", "free edge"}:
    errors.append(f"curves: expected annulus and free edge, found {sorted(curves)}")
else:
    ends = {}
    for name, m in curves.items():
        if m["type"] != "Curve" or m["coordinateSystem"] != "LPS" or len(m["controlPoints"]) < 3:
            errors.append(f"{name}: {m['type']}, {m['coordinateSystem']}, {len(m['controlPoints'])} points")
        p = [c["position"] for c in m["controlPoints"]]
        ends[name] = sorted([tuple(p[0]), tuple(p[-1])])
    if ends["annulus"] != ends["free edge"]:
        errors.append(f"annulus ends {ends['annulus']} are not the free edge's {ends['free edge']}")
if errors:
    print(*errors, sep="\n")
    sys.exit(1)
print("annulus and free edge meet at the corners")
