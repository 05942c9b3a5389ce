#!/usr/bin/env python3
"""Documentation links stay inside the repository and point at something.

    check_doc_links.py [FILE.md ...]     (default: README.md and docs/*.md)

Checks every Markdown link [text](target) and image ![alt](target) that is not a web
address: the file must exist inside the repository (a link that leaves it, such as
../shared/MODEL.md, breaks for everyone who clones it), and a #fragment must name an
anchor of that file: an explicit <a id="..."> or a heading, slugged as GitHub does
(lower case, punctuation dropped, spaces to hyphens, -1, -2 ... for repeats).
Exit 1 with one line per broken link, file:line first.
"""
import os
import re
import sys

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
EXPLICIT_ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def slug(heading):
    """GitHub's heading anchor: lower case, keep letters, digits, spaces, hyphens, underscores."""
    text = re.sub(r"<[^>]+>", "", heading)            # inline HTML such as <a id>
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def lines_outside_code(path):
    """(line number, text) of the lines not inside fenced code blocks."""
    inside = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                inside = not inside
                continue
            if not inside:
                yield number, line


def anchors(path):
    found, seen = set(), {}
    for _, line in lines_outside_code(path):
        found.update(EXPLICIT_ANCHOR.findall(line))
        match = HEADING.match(line)
        if match:
            base = slug(match.group(2))
            count = seen.get(base, 0)
            found.add(base if count == 0 else f"{base}-{count}")
            seen[base] = count + 1
    return found


def check(path, root=SOURCE_DIR):
    """Broken links of one Markdown file, as 'file:line: message' strings."""
    problems, cache = [], {}
    relative = os.path.relpath(path, root)
    for number, line in lines_outside_code(path):
        for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            file_part, _, fragment = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            where = f"{relative}:{number}: ({target})"
            if os.path.relpath(resolved, root).startswith(".."):
                problems.append(f"{where} leaves the repository")
                continue
            if not os.path.exists(resolved):
                problems.append(f"{where} names a file that does not exist")
                continue
            if fragment and resolved.endswith(".md"):
                if resolved not in cache:
                    cache[resolved] = anchors(resolved)
                if fragment not in cache[resolved]:
                    problems.append(f"{where} names no anchor of {os.path.relpath(resolved, root)}")
    return problems


def main():
    files = sys.argv[1:] or [os.path.join(SOURCE_DIR, "README.md")] + sorted(
        os.path.join(SOURCE_DIR, "docs", f) for f in os.listdir(os.path.join(SOURCE_DIR, "docs")) if f.endswith(".md"))
    problems = [p for f in files for p in check(os.path.abspath(f))]
    for p in problems:
        print(p)
    print(f"documentation links: {len(files)} files, {len(problems)} broken")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
