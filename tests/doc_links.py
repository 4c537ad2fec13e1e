#!/usr/bin/python3
"""ctest doc_links: the doc pages and the files they show cannot drift apart.

Every relative link or image in README.md and docs/**/*.md must name a file of the tree, and every
file under docs/images/ and docs/data/ must be linked or named by some page (a file no page shows
is not kept). Usage: doc_links.py SOURCE_DIR. Prints one line per problem; exit code 1 if any.
"""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
NAMED = re.compile(r"(?:docs/)?(?:images|data)/[\w.\-/]+")


def pages(root):
    yield root / "README.md"
    yield from sorted((root / "docs").rglob("*.md"))


def main(root):
    problems, shown = [], set()
    for page in pages(root):
        text = page.read_text(encoding="utf-8")
        for target in LINK.findall(text):
            if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                continue
            path = (page.parent / target.split("#")[0]).resolve()
            if not path.exists():
                problems.append(f"{page.relative_to(root)}: link to a missing file: {target}")
            shown.add(path)
        for name in NAMED.findall(text):
            for base in (root, root / "docs", page.parent):
                candidate = (base / name).resolve()
                if candidate.exists():
                    shown.add(candidate)
    for folder in ("docs/images", "docs/data"):
        for f in sorted((root / folder).rglob("*")):
            if f.is_file() and f.resolve() not in shown:
                problems.append(f"{f.relative_to(root)}: shown by no page (README.md, docs/)")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1]).resolve()))
