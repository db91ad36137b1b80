#!/usr/bin/python3
"""Every link and picture of the README and of docs/ leads somewhere.

    check_links.py REPOSITORY

For README.md and docs/*.md, each Markdown link or image `[text](target)` whose target is not a
web address must name a file of the repository (relative to the page), and an `#anchor` must be
a heading of the page it points into (as GitHub makes anchors: lower case, punctuation dropped,
spaces as hyphens). Exits 1 naming the page, line and target of each one that does not.
"""
import glob
import os
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def anchors_of(path):
    anchors, in_fence = set(), False
    with open(path, encoding="utf-8") as page:
        for line in page:
            if line.startswith("```"):
                in_fence = not in_fence
            heading = HEADING.match(line)
            if heading and not in_fence:
                text = re.sub(r"[^\w\- ]", "", heading.group(2).lower())
                anchors.add(text.replace(" ", "-"))
    return anchors


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    repository = os.path.abspath(sys.argv[1])
    pages = [os.path.join(repository, "README.md")]
    pages += sorted(glob.glob(os.path.join(repository, "docs", "*.md")))
    problems, checked = [], 0
    for page in pages:
        in_fence = False
        with open(page, encoding="utf-8") as file:
            lines = file.read().splitlines()
        for number, line in enumerate(lines, 1):
            if line.startswith("```"):
                in_fence = not in_fence
            if in_fence:
                continue
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target):
                    continue  # a web address
                checked += 1
                path, _, anchor = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path \
                    else page
                where = f"{os.path.relpath(page, repository)}:{number}: {target}"
                if not os.path.exists(resolved):
                    problems.append(f"{where}: no such file")
                elif anchor and resolved.endswith(".md") and anchor not in anchors_of(resolved):
                    problems.append(f"{where}: no heading with that anchor")
    print(f"{checked} links in {len(pages)} pages checked")
    for problem in problems:
        print(f"BROKEN: {problem}", file=sys.stderr)
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
