#!/usr/bin/python3
"""Checks the relative links of the project's Markdown pages.

Usage: check_links.py [FILE_OR_DIR ...]     (default: README.md docs/)

Every [text](target) and ![alt](target) outside code blocks and code spans whose target
is not a URL must name an existing file or directory (relative to the page); a
#fragment must name a heading of the target page (GitHub's anchors: lower case,
punctuation dropped, spaces as hyphens, -1, -2, ... for repeats). Prints one line per
broken link, "page:line: target: reason", and exits 1 if there is any, 0 otherwise.
Standard library only (Debian's /usr/bin/python3).
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
URL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def prose_lines(text):
    """(line number, line without code spans) for every line outside fenced code blocks."""
    fenced = False
    for n, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if fenced or line.startswith("    ") or line.startswith("\t"):
            continue
        yield n, re.sub(r"`[^`]*`", "``", line)


def slug(heading):
    """GitHub's anchor of a heading's text."""
    s = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link in a heading: its text
    s = s.strip().lower()
    s = "".join(c for c in s if c.isalnum() or c in " -_")
    return s.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            text = f.read()
        fenced = False
        for line in text.split("\n"):
            if FENCE.match(line):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if m:
                base = slug(m.group(2))
                k = seen.get(base, 0)
                seen[base] = k + 1
                found.add(base if k == 0 else f"{base}-{k}")
        cache[path] = found
    return cache[path]


def check_page(page):
    errors = []
    with open(page, encoding="utf-8") as f:
        text = f.read()
    here = os.path.dirname(page)
    for n, line in prose_lines(text):
        for m in LINK.finditer(line):
            target = m.group(1)
            if URL.match(target):
                continue
            path, _, fragment = target.partition("#")
            full = os.path.normpath(os.path.join(here, path)) if path else page
            if not os.path.exists(full):
                errors.append(f"{page}:{n}: {target}: no such file or directory")
                continue
            if fragment and full.endswith(".md") and os.path.isfile(full):
                if fragment.lower() not in anchors(full):
                    errors.append(f"{page}:{n}: {target}: no heading with the anchor "
                                  f"#{fragment} in {full}")
    return errors


def pages(args):
    for a in args:
        if os.path.isdir(a):
            for root, dirs, files in os.walk(a):
                dirs[:] = sorted(d for d in dirs if d not in ("node_modules", ".git"))
                for name in sorted(files):
                    if name.endswith(".md"):
                        yield os.path.join(root, name)
        elif os.path.isfile(a):
            yield a
        else:
            sys.exit(f"check_links: {a}: no such file or directory")


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(__doc__)
        return 0
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    args = sys.argv[1:] or [os.path.relpath(os.path.join(root, p)) for p in ("README.md", "docs")]
    errors, count = [], 0
    for page in pages(args):
        count += 1
        errors += check_page(page)
    for e in errors:
        print(e)
    print(f"check_links: {count} pages, {len(errors)} broken links", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
