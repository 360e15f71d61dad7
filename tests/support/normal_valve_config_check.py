#!/usr/bin/env python3
"""Checks that the normal aortic valve's recorded choices (configs/aortic_valve_normal.json)
are what the tools use: valve-generate's default fiber angle and graft commissure gap (from its
summary), the closure
scene's bending modulus and root preset, and that preset's modulus, stiffening pressure and
stiffness index.

usage: normal_valve_config_check.py REPO VALVE_GENERATE WORK_DIR
"""
import json
import os
import subprocess
import sys


def main():
    repo, generate, work = sys.argv[1:4]
    record = json.load(open(os.path.join(repo, "configs", "aortic_valve_normal.json")))
    subprocess.run([generate, "aortic_valve", "--triangles", "60", "--out", work, "--quiet"], check=True)
    summary = json.load(open(os.path.join(work, "generate.summary.json")))
    scene = json.load(open(os.path.join(repo, "pipelines", "scenes", "aortic_valve_closure.json")))
    root = scene.get("aortic_root", {})
    preset_name = root.get("preset", "aortic_root")
    preset = json.load(open(os.path.join(repo, "configs", "materials", preset_name + ".json")))
    pairs = [
        ("fiber_angle_deg", record["fiber_angle_deg"], "valve-generate aortic_valve's default", summary["parameters"]["fiber_angle_deg"]),
        ("graft_commissure_gap_mm", record["graft_commissure_gap_mm"], "valve-generate aortic_valve's default",
         summary["parameters"]["graft_commissure_gap_mm"]),
        ("bending_modulus", record["bending_modulus"], "the scene's bending.modulus", scene.get("bending", {}).get("modulus")),
        ("root_preset", record["root_preset"], "the scene's aortic_root.preset", preset_name),
        ("root_youngs_modulus", record["root_youngs_modulus"], "the root's youngs_modulus",
         root.get("youngs_modulus", preset.get("youngs_modulus"))),
        ("root_stiffening_pressure", record["root_stiffening_pressure"], "the root's stiffening_pressure",
         root.get("stiffening_pressure", preset.get("stiffening_pressure"))),
        ("root_stiffness_index", record["root_stiffness_index"], "the root's stiffness_index",
         root.get("stiffness_index", preset.get("stiffness_index", "continuous"))),
    ]
    bad = [f"configs/aortic_valve_normal.json: {key}: expected {used} ({where}), found {recorded}"
           for key, recorded, where, used in pairs if recorded != used]
    for line in bad:
        print(line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
