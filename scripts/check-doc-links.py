#!/usr/bin/env python3
"""Checks that every relative Markdown link in README.md and docs/ resolves to a file or folder.

Usage: scripts/check-doc-links.py   (from anywhere; exit status 1 and one line per broken link)
"""
import pathlib
import re
import sys

root = pathlib.Path(__file__).resolve().parent.parent
files = [root / "README.md", *sorted((root / "docs").rglob("*.md"))]
link = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
broken = 0
for md in files:
    text = md.read_text(encoding="utf-8")
    # links inside code spans or indented code blocks are commands, not links
    text = re.sub(r"`[^`\n]*`", "", text)
    for target in link.findall(text):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        path = target.split("#", 1)[0]
        if not (md.parent / path).exists():
            print(f"{md.relative_to(root)}: broken link {target}")
            broken += 1
sys.exit(1 if broken else 0)
