#!/usr/bin/env python3
"""The repository explains itself: every relative link in README.md and docs/*.md resolves to a file in
the repository, and no tracked file cites a file outside it (the model, spec, render and style notes
and the paper's text that live beside the repository, or any path into the shared folder next to it).
Exit 1 listing each offence."""
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
bad = []
link = re.compile(r"\]\(([^)\s]+)\)")
for page in [root / "README.md", *sorted((root / "docs").glob("*.md"))]:
    for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        for target in link.findall(line):
            if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                continue  # a web address or a section of the same page
            path = target.split("#", 1)[0]
            if not (page.parent / path).exists():
                bad.append(f"{page.relative_to(root)}:{n}: link to {target}: no such file")
# the names, assembled so that this file does not match itself
names = "|".join(["MODEL", "SPEC", "RENDER-NOTES", "STYLE"])
outside = re.compile(r"\.\./" + "shared" + r"|\b(" + names + r")\.md\b|\b" + "paper" + r"\.md\b")
tracked = subprocess.run(["git", "-C", str(root), "ls-files"], capture_output=True, text=True, check=True).stdout.split()
for name in tracked:
    f = root / name
    if not f.is_file():
        continue
    try:
        text = f.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        continue
    for n, line in enumerate(text.splitlines(), 1):
        if outside.search(line):
            bad.append(f"{name}:{n}: cites a file outside the repository: {line.strip()[:100]}")
for b in bad:
    print(b)
print(f"{len(bad)} problem(s)" if bad else "README and docs: every link resolves, nothing cited outside the repository")
sys.exit(1 if bad else 0)
