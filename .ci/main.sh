#!/usr/bin/env bash
# Sets up, builds and runs the main job on sample_data/: the single aortic leaflet of the
# seed (Fig. 3.6) closed under 80 mmHg with the mass-spring and the membrane FE model;
# each run prints its solver report and leaflet dimensions. Outputs go to out/main/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup.sh
rm -rf out/main
for model in mass_spring membrane_fe; do
  echo "== $model"
  build/stages/valve-simulate --scene sample_data/aortic_leaflet.scene.json --model "$model" --out "out/main/$model"
done
echo "seed Table 3.2: mass-spring 26.3 / 15.2 mm, FE 26.20 / 15.60 mm (free edge / midline; undeformed 20.0 / 10.0)"
