#!/usr/bin/env python3
"""Every relative link of README.md and docs/**/*.md leads somewhere: the file (or folder) exists and
an #anchor names a heading of the target Markdown file, as GitHub derives anchors from headings
(lower case, punctuation dropped, spaces to hyphens, "-1", "-2", ... after repeats) or an
`<a id="...">` of that file.

    check_links.py ROOT          check the repository at ROOT; exit 1 listing each broken link
    check_links.py --self-test   plant a broken file link and broken anchors (one in a link whose
                                 text wraps); fail unless each is found
"""

import pathlib
import re
import sys
import tempfile

FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
# [text](target) and [text](target "title"); images too. Code spans are removed first.
LINK = re.compile(r"\[[^\]\[]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_ID = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")


def prose_lines(text):
    """The lines outside fenced code blocks, with their numbers."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def anchor_of(heading):
    text = CODE_SPAN.sub(lambda m: m.group(0).strip("`"), heading)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)  # GitHub keeps letters, digits, _, - and spaces
    return text.replace(" ", "-")


def anchors(path, cache):
    if path not in cache:
        seen = {}
        found = set()
        for _, line in prose_lines(path.read_text(encoding="utf-8")):
            found.update(HTML_ID.findall(line))  # <a id="snow"></a>
            match = HEADING.match(line)
            if not match:
                continue
            base = anchor_of(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        cache[path] = found
    return cache[path]


def broken_links(root):
    root = pathlib.Path(root).resolve()
    files = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    problems = []
    cache = {}
    for source in files:
        # The prose with code blocks blanked (line numbers kept): a link's text may wrap.
        text = source.read_text(encoding="utf-8")
        lines = [""] * len(text.splitlines())
        for number, line in prose_lines(text):
            lines[number - 1] = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
        prose = "\n".join(lines)
        for match in LINK.finditer(prose):
            target = match.group(1)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, mailto:, ...
                continue
            file_part, _, anchor = target.partition("#")
            where = f"{source.relative_to(root)}:{prose.count(chr(10), 0, match.start()) + 1}"
            destination = (source.parent / file_part).resolve() if file_part else source
            if not destination.exists():
                problems.append(f"{where}: no file {file_part}")
            elif anchor and destination.suffix == ".md" and anchor not in anchors(destination, cache):
                problems.append(f"{where}: no heading #{anchor} in {file_part or source.name}")
    return problems


def self_test():
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        (root / "docs").mkdir()
        (root / "docs/a.md").write_text(
            "# A\n\n## Figures: 1,000 cars (tried, dropped)\n\n## Figures\n\n## Figures\n"
            "```\n## not a heading\n```\n<a id=\"snow\"></a>Snow. [back](../README.md#corsa)\n", encoding="utf-8")
        good = ("# Corsa\n\n[a](docs/a.md#figures-1000-cars-tried-dropped) [b](docs/a.md#figures-1) "
                "[c](docs/) [s](docs/a.md#snow) [d](https://example.org/x#y) `[e](docs/missing.md)`\n"
                "[a wrapped\nlink](docs/a.md#figures)\n")
        (root / "docs/sub").mkdir()  # a file in a subfolder is checked, its links relative to it
        (root / "docs/sub/b.md").write_text("# B\n\n[a](../a.md#figures-1) [r](../../README.md#corsa) [self](#b)\n",
                                            encoding="utf-8")
        (root / "README.md").write_text(good, encoding="utf-8")
        if broken_links(root):
            print("self-test: a good tree reported broken:", broken_links(root))
            return 1
        (root / "README.md").write_text(good + "[f](docs/missing.md) [g](docs/a.md#not-a-heading) [h\ni](docs/a.md#x)\n",
                                        encoding="utf-8")
        (root / "docs/sub/b.md").write_text("# B\n\n[a](a.md) [b](../a.md#figures-3)\n", encoding="utf-8")
        found = broken_links(root)
        expected = ["README.md:6: no file docs/missing.md",
                    "README.md:6: no heading #not-a-heading in docs/a.md",
                    "README.md:6: no heading #x in docs/a.md",
                    "docs/sub/b.md:3: no file a.md",
                    "docs/sub/b.md:3: no heading #figures-3 in ../a.md"]
        if found != expected:
            print("self-test: expected", expected, "got", found)
            return 1
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    problems = broken_links(sys.argv[1])
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
