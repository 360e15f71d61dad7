#!/usr/bin/env python3
"""check_slicer_xml.py STAGE_EXECUTABLE

The stage's --xml must be a 3D Slicer CLI module description (SlicerExecutionModel) that
offers every option its --help names. The two are parsed here independently of the stage:
the help text by a regular expression over its words, the XML by Python's own parser.
"""
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

exe = sys.argv[1]
name = exe.rsplit("/", 1)[-1]


def run(flag):
    p = subprocess.run([exe, flag], capture_output=True, text=True)
    if p.returncode != 0 or p.stderr:
        sys.exit(f"{name} {flag}: exit {p.returncode}, stderr {p.stderr!r}")
    return p.stdout


help_text = run("--help")
xml_text = run("--xml")
try:
    root = ET.fromstring(xml_text)
except ET.ParseError as e:
    sys.exit(f"{name} --xml is not well-formed XML: {e}")

errors = []
# The element order SlicerExecutionModel's ModuleDescription.xsd fixes for <executable>.
head = ["category", "title", "description", "version", "documentation-url", "license", "contributor"]
tags = [c.tag for c in root]
if root.tag != "executable" or tags[: len(head)] != head or not tags[len(head):] or set(tags[len(head):]) != {"parameters"}:
    errors.append(f"expected <executable> with {head} then <parameters>, found <{root.tag}> with {tags}")
if root.findtext("title") != name:
    errors.append(f"title: expected {name}, found {root.findtext('title')!r}")

parameter_tags = {"integer", "boolean", "float", "double", "string", "string-enumeration", "file", "directory",
                  "image", "geometry", "point", "point-vector", "region", "transform", "table"}
names, longflags, indices = set(), set(), []
for group in root.findall("parameters"):
    if not group.findtext("label"):
        errors.append("a <parameters> group without a <label>")
    for p in group:
        if p.tag in ("label", "description"):
            continue
        if p.tag not in parameter_tags:
            errors.append(f"unknown parameter element <{p.tag}>")
            continue
        pname = p.findtext("name") or ""
        # Slicer uses the name as a variable name: a C identifier, unique in the module.
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", pname) or pname in names:
            errors.append(f"<{p.tag}> name {pname!r}: expected a unique identifier")
        names.add(pname)
        for child in ("label", "description"):
            if p.find(child) is None:
                errors.append(f"{pname}: no <{child}>")
        flag, index = p.findtext("longflag"), p.findtext("index")
        if (flag is None) == (index is None):
            errors.append(f"{pname}: expected a <longflag> or an <index>, found {'both' if flag else 'neither'}")
        if flag is not None:
            longflags.add(flag)
        if index is not None:
            indices.append(int(index))
        if p.tag in ("file", "image", "geometry") and p.findtext("channel") not in ("input", "output"):
            errors.append(f"{pname}: <{p.tag}> needs <channel> input or output")
        if p.tag == "boolean" and p.findtext("default") != "false":
            errors.append(f"{pname}: a switch is off unless given, expected <default>false")
        if p.tag == "string-enumeration":
            elements = [e.text for e in p.findall("element")]
            if p.findtext("default") not in elements:
                errors.append(f"{pname}: default {p.findtext('default')!r} not among {elements}")
if sorted(indices) != list(range(len(indices))):
    errors.append(f"positional indices: expected 0..{len(indices) - 1}, found {sorted(indices)}")

# Every option the help names, except the two that print instead of run.
help_options = set(re.findall(r"(?<![\w-])--([a-z][a-z0-9-]*)", help_text)) - {"help", "xml"}
missing = sorted(help_options - longflags)
if missing:
    errors.append("options in --help but not in --xml: " + " ".join("--" + m for m in missing))
# The positional arguments of the synopsis (the words before its first option).
synopsis = help_text.split("\n", 1)[0].split()
first_option = next((i for i, w in enumerate(synopsis[1:]) if w.startswith(("-", "["))), len(synopsis) - 1)
positional = synopsis[1 : 1 + first_option]
if len(indices) != len(positional):
    errors.append(f"positional arguments: --help shows {positional}, --xml has {len(indices)} indexed parameters")

if errors:
    print(f"{name}:", *errors, sep="\n  ")
    sys.exit(1)
print(f"{name}: {len(longflags)} options and {len(indices)} positional arguments, as in --help")
