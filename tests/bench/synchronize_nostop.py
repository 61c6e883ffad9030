#!/usr/bin/env python3
"""Writes synchronize without its stop trigger, for the 1,200 s benchmark.

esmini's quoted figure for synchronize (1,123 ms) is for a 1,200 s run, but the kit's file stops
at 94.63 s (its StopTrigger: the Ego travelled 5 m, or NPC4 stood 2 s). This writes a copy whose
StopTrigger is empty (`<StopTrigger/>`) and whose relative file and directory paths (map,
catalogs) are made absolute so that the copy may live anywhere, and prints the copy's path.
esmini's file itself is not committed.

usage: synchronize_nostop.py [KIT_XOSC [OUT_XOSC]]
  KIT_XOSC defaults to /work/notes/esmini/resources/xosc/synchronize.xosc,
  OUT_XOSC to synchronize_nostop.xosc in the current directory.
then:  corsa run OUT_XOSC --quiet --duration 1200 --threads 1
"""
import os
import re
import sys


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "/work/notes/esmini/resources/xosc/synchronize.xosc"
    out = sys.argv[2] if len(sys.argv) > 2 else "synchronize_nostop.xosc"
    with open(src, encoding="utf-8") as f:
        text = f.read()
    # The storyboard's StopTrigger is the last one in the file (Acts and Stories may hold their own).
    starts = [m.start() for m in re.finditer(r"<StopTrigger\b", text)]
    if not starts:
        sys.exit(f"{src}: error: no StopTrigger")
    begin = starts[-1]
    end_tag = "</StopTrigger>"
    end = text.find(end_tag, begin)
    if end < 0 or "</Storyboard>" not in text[end:]:
        sys.exit(f"{src}: error: the last StopTrigger is not the storyboard's")
    text = text[:begin] + "<StopTrigger/>" + text[end + len(end_tag):]
    base = os.path.dirname(os.path.abspath(src))

    def absolute(m):
        path = m.group(2)
        if os.path.isabs(path):
            return m.group(0)
        return f'{m.group(1)}="{os.path.normpath(os.path.join(base, path))}"'

    text = re.sub(r'\b(path|filepath)="([^"]*)"', absolute, text)
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)
    print(out)


if __name__ == "__main__":
    main()
