#!/usr/bin/env python3
"""generated_docs_check.py [--update] SOURCE_DIR GENERATED_DIR: the docs made at build time
(GENERATED_DIR, i.e. build/docs) are the ones in the tree: each stage's page docs/stages/<stage>.md
(its --help text) and the scene key table between the markers of docs/scene.md
(valve-simulate --scene-keys). Prints each page that differs and exits 1; --update writes them
(cmake --build build --target update-docs)."""
import pathlib
import sys

update = "--update" in sys.argv
source, generated = (pathlib.Path(a) for a in sys.argv[1:] if a != "--update")
BEGIN = "<!-- scene keys: made by `valve-simulate --scene-keys`; `cmake --build build --target update-docs` -->\n"
END = "<!-- end of scene keys -->\n"

stale = []
pages = {p.name: p.read_text() for p in sorted((generated / "stages").glob("*.md"))}
if not pages:
    sys.exit(f"{generated / 'stages'}: expected the stages' generated pages, found none (build first)")
tree_pages = source / "docs" / "stages"
for name, text in pages.items():
    page = tree_pages / name
    if not page.exists() or page.read_text() != text:
        stale.append(str(page))
        if update:
            tree_pages.mkdir(exist_ok=True)
            page.write_text(text)
for page in sorted(tree_pages.glob("*.md")):
    if page.name not in pages:
        stale.append(f"{page} (no stage of that name)")
        if update:
            page.unlink()

scene = source / "docs" / "scene.md"
text = scene.read_text()
if BEGIN not in text or END not in text:
    sys.exit(f"{scene}: expected the scene key markers, found none")
head, rest = text.split(BEGIN, 1)
_, tail = rest.split(END, 1)
table = (generated / "scene-keys.md").read_text()
current = head + BEGIN + table + END + tail
if current != text:
    stale.append(f"{scene} (scene key table)")
    if update:
        scene.write_text(current)

for page in stale:
    print(("updated " if update else "not current: ") + page)
if not stale:
    print(f"{len(pages)} stage pages and the scene key table are current")
sys.exit(0 if update or not stale else 1)
