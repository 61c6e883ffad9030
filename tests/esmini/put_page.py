#!/usr/bin/env python3
"""Append one page of a stored file (a read_file answer, 16,000 characters a page) to a kit file.

usage: put_page.py PATH OFFSET [TOTAL] < page.json
stdin holds the page's "text" value as the answer prints it: a JSON string, quotes included, so
tabs, carriage returns and backslashes come through exactly. The page is refused unless OFFSET is
the file's current length in characters, so no page is skipped or written twice; with TOTAL (the
answer's total_chars) it says whether the file is complete. Python 3, standard library only.
"""

import json
import os
import sys


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__.strip().split('\n')[2])
    path, offset = sys.argv[1], int(sys.argv[2])
    total = int(sys.argv[3]) if len(sys.argv) == 4 else None
    text = json.loads(sys.stdin.read().strip())
    have = ''
    if os.path.exists(path):
        with open(path, encoding='utf-8', newline='') as f:
            have = f.read()
    if len(have) != offset:
        sys.exit(f'{path}: has {len(have)} characters, the page starts at {offset}')
    os.makedirs(os.path.dirname(path) or '.', exist_ok=True)
    with open(path, 'a', encoding='utf-8', newline='') as f:
        f.write(text)
    n = len(have) + len(text)
    state = '' if total is None else (' COMPLETE' if n == total else f' of {total}')
    print(f'{path}: {n} characters{state}')


if __name__ == '__main__':
    main()
