#!/usr/bin/python3
"""The README's map and layout name the home of each kind of thing; each path they name must
exist, so that a newcomer who follows the map finds the file (issue #23).

A path is a backticked token with a '/' or a file suffix in the sections "Map: ..." and "Layout".
`<kind>` placeholders are globs; `a.cpp`/`b.cpp` lists are each checked. Exit 1 naming every
missing path, 2 when the sections are absent (the test would otherwise pass on nothing)."""
import glob
import os
import re
import sys

root = sys.argv[1]
text = open(os.path.join(root, "README.md"), encoding="utf-8").read()

sections = re.findall(r"^#{2,3} (Map[^\n]*|Layout)\n(.*?)(?=^#{2,3} |\Z)", text, re.M | re.S)
if len(sections) < 2:
    print("README.md: expected a '### Map ...' and a '## Layout' section, found",
          [s[0] for s in sections])
    sys.exit(2)

file_like = re.compile(r"^[\w.<>*-]+(/[\w.<>*-]*)*(\.(cpp|hpp|md|json|yaml|py|js|html|css|sh|cmake|txt))?/?$")
checked, missing = 0, []
for title, body in sections:
    for token in re.findall(r"`([^`\n]+)`", body):
        for candidate in token.split(" + "):
            candidate = candidate.strip()
            if " " in candidate or not file_like.match(candidate):
                continue
            if "/" not in candidate and "." not in candidate:
                continue  # a word, not a path
            if candidate.startswith(("/api", "api/")):
                continue  # a URL path, checked by the API tests
            pattern = re.sub(r"<[^>]+>", "*", candidate)
            # A bare file name names a file somewhere in its row's folder: found anywhere.
            if "/" not in pattern.rstrip("/"):
                pattern = "**/" + pattern
            hits = glob.glob(os.path.join(root, pattern), recursive=True)
            hits = [h for h in hits if "/build" not in h[len(root):] and "node_modules" not in h]
            checked += 1
            if not hits:
                missing.append(f"{title}: `{candidate}`")

print(f"{checked} paths named in the README's map and layout")
if checked < 20:
    print("expected at least 20 paths: has the map lost its table?")
    sys.exit(1)
for m in missing:
    print("missing:", m)
sys.exit(1 if missing else 0)
