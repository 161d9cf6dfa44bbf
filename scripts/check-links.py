#!/usr/bin/env python3
"""Link check of the tracked Markdown: every relative link and image target of a tracked *.md
file must name a file or folder that exists in the checkout (a link's #fragment is not checked).
Links to other sites (http, https, mailto) and pure #anchors are left alone, as are materials/
(third-party example files). Exit status 1 with each broken link as FILE:LINE: TARGET, 0 with a
one-line count otherwise.

Usage: scripts/check-links.py (from anywhere in the checkout), e.g. beside scripts/check-words.sh
in the format step of scripts/test.sh.
"""
import os
import re
import subprocess
import sys

# [text](target) and ![alt](target); the target ends at whitespace or the closing bracket, so a
# title ("...") after it is ignored. Inline code spans are removed first: `[a](b)` in backticks
# is an example, not a link.
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
CODE_SPAN = re.compile(r"`[^`]*`")
EXTERNAL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")  # http:, https:, mailto:, ...


def tracked_markdown(root):
    listing = subprocess.run(["git", "-C", root, "ls-files", "-z", "--", "*.md", ":!:materials/*"],
                             check=True, capture_output=True, text=True).stdout
    return [path for path in listing.split("\0") if path]


def broken_links(root, path):
    broken = []
    in_fence = False
    with open(os.path.join(root, path), encoding="utf-8") as text:
        for number, line in enumerate(text, start=1):
            if line.lstrip().startswith("```"):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            for match in LINK.finditer(CODE_SPAN.sub("", line)):
                target = match.group(1)
                if EXTERNAL.match(target) or target.startswith("#"):
                    continue
                file_part = target.split("#", 1)[0]
                resolved = os.path.normpath(os.path.join(root, os.path.dirname(path), file_part))
                if not os.path.exists(resolved):
                    broken.append(f"{path}:{number}: {target}")
    return broken


def main():
    root = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse", "--show-toplevel"],
                          check=True, capture_output=True, text=True).stdout.strip()
    files = tracked_markdown(root)
    broken = [entry for path in files for entry in broken_links(root, path)]
    if broken:
        print("check-links: links to files that do not exist:", file=sys.stderr)
        print("\n".join(broken), file=sys.stderr)
        return 1
    print(f"check-links: {len(files)} tracked Markdown files, every relative link resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
