#!/usr/bin/env python3
"""pipeline_descriptions_check.py PIPELINES_DIR: every pipeline's description says what it does in
at most three sentences (a sentence ends at . ! or ? followed by a space or the end); the detail
belongs in docs/pipelines.md and the results pages."""
import json
import pathlib
import re
import sys

failures = []
files = sorted(pathlib.Path(sys.argv[1]).glob("*.json"))
for path in files:
    description = json.loads(path.read_text()).get("description", "")
    sentences = len(re.findall(r"[.!?](?:\s|$)", description.strip()))
    if not description.strip():
        failures.append(f"{path}: description: expected a description, found none")
    elif sentences > 3:
        failures.append(f"{path}: description: expected at most 3 sentences, found {sentences}")
print("\n".join(failures) if failures else f"{len(files)} pipeline descriptions of at most 3 sentences")
sys.exit(1 if failures else 0)
