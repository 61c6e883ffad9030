#!/usr/bin/env python3
"""Checks that Corsa's modules depend on each other one way only (DESIGN.md, "Modules").

Every module is a top-level folder with `include/corsa/<module>/` (public) and `src/` (private).
A module may include and link only itself and the modules below it:

    core <- xodr <- {ngii, render, engine};  core <- xosc <- engine <- sensors <- collect;
    core <- geo <- sensors;  engine <- sweep <- suite;  apps (the `corsa` command line) and python
    may use every module.

What is checked, in every module's sources, headers, tools and CMakeLists.txt:
  1. `#include <corsa/M/...>` and `#include "corsa/M/..."` name an allowed module M;
  2. relative includes ("../x.h") stay inside the module's folder;
  3. a module's public headers live in `include/corsa/<module>/` and nowhere else under
     `include/corsa/`, so that the include path names the module that owns the header;
  4. `target_link_libraries` of a module's targets name only targets of allowed modules;
  5. a module's CMakeLists.txt does not reach into another module's folder (compiling its sources
     or putting its private `src/` on an include path).

Usage:
    check_layering.py [ROOT]        check the tree at ROOT (default: this repository); exit 1 and
                                    one `file:line: error: ...` per violation when one is found
    check_layering.py --self-test   plant violations in temporary trees and check that each one
                                    is found (and that a clean tree passes)
"""

from __future__ import annotations

import pathlib
import re
import sys
import tempfile

# Module -> (folder relative to the root, the modules it builds on directly). What a module may use
# is the closure of these arrows. None: may use every module.
MODULES: dict[str, tuple[str, list[str] | None]] = {
    "core": ("core", []),
    "geo": ("geo", ["core"]),
    "xodr": ("xodr", ["core"]),
    "ngii": ("ngii", ["xodr"]),
    "render": ("render", ["xodr"]),
    "xosc": ("xosc", ["core"]),
    "engine": ("engine", ["xodr", "xosc"]),
    "sensors": ("sensors", ["engine", "geo"]),
    "collect": ("collect", ["sensors"]),
    "sweep": ("sweep", ["engine"]),
    "suite": ("suite", ["sweep"]),
    "apps": ("apps", None),
    "python": ("python", None),
}

SOURCE_SUFFIXES = {".h", ".hpp", ".c", ".cc", ".cpp", ".in"}
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
CORSA_INCLUDE_RE = re.compile(r"^corsa/([A-Za-z0-9_]+)/")
TARGET_DEF_RE = re.compile(r"\badd_(?:library|executable)\s*\(\s*([A-Za-z0-9_]+)")
LINK_RE = re.compile(r"\btarget_link_libraries\s*\(([^)]*)\)", re.S)
PROJECT_PATH_RE = re.compile(r"\$\{(?:PROJECT|CMAKE)_SOURCE_DIR\}/([A-Za-z0-9_./-]+)")


def allowed_modules(module: str) -> set[str] | None:
    """The modules `module` may use (itself included), or None for every module."""
    if MODULES[module][1] is None:
        return None
    allowed = {module}
    stack = list(MODULES[module][1])
    while stack:
        below = stack.pop()
        if below not in allowed:
            allowed.add(below)
            stack.extend(MODULES[below][1] or [])
    return allowed


def may_use(user: str, used: str) -> bool:
    allowed = allowed_modules(user)
    return allowed is None or used in allowed


def line_of(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def module_files(folder: pathlib.Path):
    for path in sorted(folder.rglob("*")):
        if path.is_file():
            yield path


def check_includes(root: pathlib.Path, module: str, folder: pathlib.Path, errors: list[str]):
    for path in module_files(folder):
        if path.suffix not in SOURCE_SUFFIXES:
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        for number, line in enumerate(text.splitlines(), 1):
            match = INCLUDE_RE.match(line)
            if not match:
                continue
            target = match.group(1)
            where = f"{path.relative_to(root)}:{number}"
            corsa = CORSA_INCLUDE_RE.match(target)
            if corsa:
                used = corsa.group(1)
                if used not in MODULES:
                    errors.append(f"{where}: error: <{target}> names no module "
                                  f"(modules: {', '.join(MODULES)})")
                elif not may_use(module, used):
                    errors.append(f"{where}: error: {module} includes <{target}>, but {used} "
                                  f"is not below {module}")
            elif target.startswith("../") or "/../" in target:
                resolved = (path.parent / target).resolve()
                if folder.resolve() not in resolved.parents:
                    errors.append(f"{where}: error: \"{target}\" reaches outside {module}/")


def check_header_folders(root: pathlib.Path, module: str, folder: pathlib.Path, errors: list[str]):
    for include in sorted(folder.rglob("include")):
        corsa = include / "corsa"
        if not include.is_dir() or not corsa.is_dir():
            continue
        for entry in sorted(corsa.iterdir()):
            if entry.name != module:
                errors.append(f"{entry.relative_to(root)}: error: the public headers of {module} "
                              f"belong in {module}/include/corsa/{module}/, not under "
                              f"corsa/{entry.name}/")


def cmake_files(folder: pathlib.Path):
    return [p for p in module_files(folder) if p.name == "CMakeLists.txt" or p.suffix == ".cmake"]


def strip_comments(text: str) -> str:
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def target_modules(root: pathlib.Path) -> dict[str, str]:
    owners: dict[str, str] = {}
    for module, (folder, _) in MODULES.items():
        if (root / folder).is_dir():
            for path in cmake_files(root / folder):
                for match in TARGET_DEF_RE.finditer(strip_comments(path.read_text())):
                    owners[match.group(1)] = module
    return owners


def check_cmake(root: pathlib.Path, module: str, folder: pathlib.Path, owners: dict[str, str],
                errors: list[str]):
    folders = {MODULES[m][0]: m for m in MODULES}
    for path in cmake_files(folder):
        text = strip_comments(path.read_text())
        where = path.relative_to(root)
        for match in LINK_RE.finditer(text):
            for token in match.group(1).split()[1:]:
                used = owners.get(token)
                if used is not None and not may_use(module, used):
                    errors.append(f"{where}:{line_of(text, match.start())}: error: {module} links "
                                  f"{token} of {used}, which is not below {module}")
        for match in PROJECT_PATH_RE.finditer(text):
            first = pathlib.PurePosixPath(match.group(1)).parts[0]
            other = folders.get(first)
            if other is not None and other != module:
                errors.append(f"{where}:{line_of(text, match.start())}: error: {module} reaches "
                              f"into {match.group(1)} (another module's files; link the module "
                              f"instead)")


def check(root: pathlib.Path) -> list[str]:
    errors: list[str] = []
    owners = target_modules(root)
    for module, (folder_name, _) in MODULES.items():
        folder = root / folder_name
        if not folder.is_dir():
            continue
        check_includes(root, module, folder, errors)
        check_header_folders(root, module, folder, errors)
        check_cmake(root, module, folder, owners, errors)
    return errors


# --- self test: a clean tree passes, and every kind of planted violation is found -------------

CLEAN_TREE = {
    "core/CMakeLists.txt": "add_library(corsa_core src/a.cpp)\n",
    "core/include/corsa/core/a.h": "#pragma once\n",
    "core/src/a.cpp": '#include "corsa/core/a.h"\n',
    "xodr/CMakeLists.txt": "add_library(corsa_xodr src/m.cpp)\n"
                           "target_link_libraries(corsa_xodr PUBLIC corsa_core)\n",
    "xodr/include/corsa/xodr/map.h": "#pragma once\n#include <corsa/core/a.h>\n",
    "xodr/src/m.cpp": '#include "corsa/xodr/map.h"\n#include "local.h"\n',
    "xodr/src/local.h": "#pragma once\n",
    "engine/CMakeLists.txt": "add_library(corsa_engine src/s.cpp)\n"
                             "target_link_libraries(corsa_engine PUBLIC corsa_xodr)\n",
    "engine/src/s.cpp": '#include "corsa/xodr/map.h"\n#include "../include/corsa/engine/x.h"\n',
    "engine/include/corsa/engine/x.h": "#pragma once\n",
    "apps/corsa/CMakeLists.txt": "add_executable(corsa main.cpp)\n"
                                 "target_link_libraries(corsa PRIVATE corsa_engine corsa_core)\n",
    "apps/corsa/main.cpp": '#include "corsa/engine/x.h"\n',
}

PLANTED = {
    "an upward include": ("xodr/src/m.cpp", '#include "corsa/engine/x.h"\n',
                          "xodr includes <corsa/engine/x.h>"),
    "an include of a sibling branch": ("xodr/src/m.cpp", "#include <corsa/ngii/x.h>\n",
                                       "xodr includes <corsa/ngii/x.h>"),
    "an include naming no module": ("core/src/a.cpp", '#include "corsa/cli/args.h"\n',
                                    "names no module"),
    "a relative include out of the module": ("core/src/a.cpp",
                                             '#include "../../engine/src/private.h"\n',
                                             "reaches outside core/"),
    "an upward link": ("core/CMakeLists.txt",
                       "target_link_libraries(corsa_core PRIVATE corsa_engine)\n",
                       "core links corsa_engine of engine"),
    "another module's private folder": (
        "xodr/CMakeLists.txt",
        "target_include_directories(corsa_xodr PRIVATE ${PROJECT_SOURCE_DIR}/core/src)\n",
        "xodr reaches into core/src"),
    "a header under another module's name": ("xodr/include/corsa/core/extra.h", "#pragma once\n",
                                             "belong in xodr/include/corsa/xodr/"),
}


def write_tree(root: pathlib.Path, files: dict[str, str]):
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def self_test() -> int:
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        clean = pathlib.Path(tmp) / "clean"
        write_tree(clean, CLEAN_TREE)
        errors = check(clean)
        if errors:
            print("self-test: FAIL: the clean tree was refused:\n  " + "\n  ".join(errors))
            failures += 1
        for what, (name, text, expected) in PLANTED.items():
            tree = pathlib.Path(tmp) / re.sub(r"\W+", "_", what)
            write_tree(tree, CLEAN_TREE)
            path = tree / name
            path.parent.mkdir(parents=True, exist_ok=True)
            with path.open("a") as out:
                out.write(text)
            errors = check(tree)
            if any(expected in e for e in errors) and all(": error: " in e for e in errors):
                print(f"self-test: ok: {what} is found")
            else:
                print(f"self-test: FAIL: {what} was not found (expected '{expected}', "
                      f"got {errors})")
                failures += 1
    print(f"self-test: {len(PLANTED) + 1 - failures} passed, {failures} failed")
    return 1 if failures else 0


def main(argv: list[str]) -> int:
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) > 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1]) if len(argv) == 2 else pathlib.Path(__file__).resolve().parents[2]
    errors = check(root)
    for error in errors:
        print(error)
    checked = [m for m, (folder, _) in MODULES.items() if (root / folder).is_dir()]
    print(f"module layering: {len(errors)} violation(s) in {len(checked)} modules "
          f"({', '.join(checked)})")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
