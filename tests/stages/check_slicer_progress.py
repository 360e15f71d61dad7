#!/usr/bin/env python3
"""check_slicer_progress.py -- COMMAND...

COMMAND (a stage given --progress slicer) must exit 0 and report on stdout in 3D Slicer's CLI
progress protocol: a <filter-start> block naming the filter, then <filter-progress>F</filter-progress>
lines with F in [0, 1] never decreasing and ending at 1, then a <filter-end> block with the
filter's name and its time. No text progress lines ("[stage] ...") go to stderr meanwhile.
"""
import re
import subprocess
import sys

cmd = sys.argv[sys.argv.index("--") + 1:]
p = subprocess.run(cmd, capture_output=True, text=True)
out, errors = p.stdout, []
if p.returncode != 0:
    sys.exit(f"exit {p.returncode}, expected 0: {p.stderr.strip()}")

start = re.search(r"<filter-start>\s*<filter-name>([^<]+)</filter-name>\s*(<filter-comment>[^<]*</filter-comment>\s*)?</filter-start>", out)
end = re.search(r"<filter-end>\s*<filter-name>([^<]+)</filter-name>\s*<filter-time>([^<]+)</filter-time>\s*</filter-end>", out)
progress = [(m.start(), m.group(1)) for m in re.finditer(r"<filter-progress>([^<]*)</filter-progress>", out)]
if not start:
    errors.append("no <filter-start> block with a <filter-name>")
if not end:
    errors.append("no <filter-end> block with <filter-name> and <filter-time>")
if not progress:
    errors.append("no <filter-progress> line")
values = []
for at, text in progress:
    try:
        values.append(float(text))
    except ValueError:
        errors.append(f"<filter-progress> {text!r}: expected a number")
if values:
    if any(not 0 <= v <= 1 for v in values):
        errors.append(f"progress outside [0, 1]: {values}")
    if any(b < a for a, b in zip(values, values[1:])):
        errors.append(f"progress goes back: {values}")
    if values[-1] != 1:
        errors.append(f"last progress {values[-1]}, expected 1")
if start and end and progress:
    if not start.end() <= progress[0][0] or not progress[-1][0] < end.start():
        errors.append("expected start, progress, end in that order")
    if start.group(1) != end.group(1):
        errors.append(f"start names {start.group(1)!r}, end names {end.group(1)!r}")
    if float(end.group(2)) < 0:
        errors.append(f"negative <filter-time> {end.group(2)}")
text_lines = [l for l in p.stderr.splitlines() if l.startswith("[")]
if text_lines:
    errors.append(f"text progress on stderr too: {text_lines[0]!r}")
if errors:
    print(*errors, sep="\n")
    sys.exit(1)
print(f"{start.group(1)}: {len(values)} progress lines from {values[0]} to {values[-1]}")
