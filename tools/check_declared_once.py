#!/usr/bin/env python3
"""Fails when the product code (engine/, plugins/, sdk/) writes a parameter's default a second
time: a constant fallback in `get_or<T>("key", constant)` or `json.value("key", constant)`.
Each parameter is declared once, in its schema (docs/architecture.md, "House rules"): the host
fills the declared defaults before anything reads them, and rumble::Params falls back to the
schema itself (docs/plugin-guide.md, "Each parameter is declared once"), so a reader uses
`get<T>(key)` or `at(key)`.

    tools/check_declared_once.py

A fallback that is not a parameter's default (a key of a file the engine writes itself, of a
plugin's own description) is listed in tools/not_parameters.txt as "path key  # why"; the check
also fails when a listed one is gone, so the list only shrinks.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PRODUCT = ["engine", "plugins", "sdk/include", "sdk/template", "sdk/template_vehicle",
           "sdk/template_coupler"]
CONSTANT = r'(-?[0-9.]+(?:[eE][-+]?[0-9]+)?u?|"[^"]*"|true|false|std::string\("[^"]*"\)|' \
           r'std::size_t\{[0-9]+\})'
FALLBACK = re.compile(r'(?:get_or<[^>]*>|\.value)\(\s*"([A-Za-z_0-9]+)"\s*,\s*' + CONSTANT +
                      r'\s*\)')


def main():
    found = set()
    for folder in PRODUCT:
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h") or not path.is_file():
                continue
            relative = path.relative_to(ROOT).as_posix()
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                for m in FALLBACK.finditer(line):
                    found.add((relative, m.group(1), number, m.group(0)))
    listed = set()
    for line in (ROOT / "tools" / "not_parameters.txt").read_text().splitlines():
        entry = line.split("#", 1)[0].split()
        if len(entry) == 2:
            listed.add(tuple(entry))
    problems = []
    for relative, key, number, text in sorted(found):
        if (relative, key) not in listed:
            problems.append(f"{relative}:{number}: {text} writes the default of \"{key}\" again: "
                            "read it with get<T>(key) or at(key); the schema declares it")
    present = {(relative, key) for relative, key, _, _ in found}
    for relative, key in sorted(listed - present):
        problems.append(f"tools/not_parameters.txt lists {relative} {key}, which is gone: "
                        "delete the line")
    for p in problems:
        print(p)
    print(f"{len(problems)} default(s) written twice or stale entries")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
