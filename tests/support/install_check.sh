#!/usr/bin/env bash
# install_check.sh BUILD_DIR WORK_DIR
# `cmake --install` into a prefix, the prefix moved elsewhere (an install is relocatable), and
# from there, with no VALVE_CONFIG_DIR and the working directory outside both trees:
#  - valve-generate writes an aortic leaflet and valve-simulate closes it with the preset
#    "aortic_leaflet", read from the moved prefix's share/valve/configs (the summary says
#    which file), not from the source tree;
#  - a program of one's own finds the package (find_package(valve)), links valve::valve_vtk
#    and reads the generated mesh: the triangle count valve-generate reported.
set -u
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/staging" >"$work/install.log" 2>&1 || { echo "install failed: $(tail -3 "$work/install.log")"; exit 1; }
mv "$work/staging" "$work/prefix"
prefix=$work/prefix
for f in bin/valve-simulate bin/valve-pipeline share/valve/configs/materials/aortic_leaflet.json \
         include/valve/io/mesh_io.hpp lib/cmake/valve/valveConfig.cmake lib/libvalve_core.a; do
  [ -e "$prefix/$f" ] || { echo "not installed: $f"; exit 1; }
done
cd "$work"
unset VALVE_CONFIG_DIR
"$prefix/bin/valve-generate" aortic_leaflet --out mesh --quiet || { echo "installed valve-generate failed"; exit 1; }
cat > scene.json <<JSON
{"mesh": "mesh/aortic_leaflet.vtp", "model": "membrane_fe", "material": "aortic_leaflet",
 "pressure": {"value": "80 mmHg", "direction": "along_normal"}, "solver": {"type": "static"}}
JSON
"$prefix/bin/valve-simulate" --scene scene.json --out sim --quiet || { echo "installed valve-simulate failed: $(cat sim/simulate.summary.json 2>/dev/null | head -c 400)"; exit 1; }
grep -q "\"file\": \"$prefix/share/valve/configs/materials/aortic_leaflet.json\"" sim/simulate.summary.json ||
  { echo "preset not read from the prefix: $(grep -o '"file": "[^"]*"' sim/simulate.summary.json)"; exit 1; }
cmake -S "$(dirname "$0")/install_consumer" -B consumer -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >consumer.log 2>&1 && cmake --build consumer >>consumer.log 2>&1 || { echo "consumer build failed: $(grep -m3 -i error consumer.log)"; exit 1; }
expected=$(grep -o '"triangles": [0-9]*' mesh/generate.summary.json | head -1 | grep -o '[0-9]*$')
found=$(./consumer/count_triangles mesh/aortic_leaflet.vtp)
[ "$found" = "$expected" ] || { echo "consumer read $found triangles, valve-generate wrote $expected"; exit 1; }
echo "installed, moved, ran from $prefix: closure ok, consumer read $found triangles"
