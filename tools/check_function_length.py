#!/usr/bin/env python3
"""Fails when a function of the product code (engine/, plugins/, sdk/) is longer than the limit
(80 lines, from the line of its name to its closing brace, lambdas inside it included), so that
every function stays one a reader can hold in mind (docs/architecture.md, "House rules").

    tools/check_function_length.py [--limit N] [--list]

Functions are found by Universal Ctags (Debian's universal-ctags). The functions still over the
limit while they are being broken up are listed in tools/long_functions.txt ("path function" per
line); the check also fails when one of them is no longer over the limit, so the list only
shrinks. --list prints every function over the limit, longest first.
"""
import argparse
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PRODUCT = ["engine", "plugins", "sdk"]


def function_lengths():
    """[(lines, path, name)] of every C++ function in the product code."""
    out = subprocess.run(
        ["ctags", "-x", "--_xformat=%{line} %{end} %N %F", "--kinds-C++=f", "--fields=+ne",
         "--languages=C++", "--langmap=C++:+.h", "-R"] + PRODUCT,
        cwd=ROOT, capture_output=True, text=True, check=True).stdout
    found = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[1].isdigit():
            name = re.sub(r"^__anon[0-9a-f]+$", "lambda", parts[2])  # ctags' name: a hash
            found.append((int(parts[1]) - int(parts[0]) + 1, parts[3], name))
    return sorted(found, reverse=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("--list", action="store_true")
    args = parser.parse_args()
    long = [(n, path, name) for n, path, name in function_lengths() if n > args.limit]
    if args.list:
        for n, path, name in long:
            print(f"{n:5d}  {path}  {name}")
        return 0
    allowed_file = ROOT / "tools" / "long_functions.txt"
    allowed = set()
    for line in allowed_file.read_text().splitlines():
        line = line.split("#", 1)[0].split()
        if line:
            allowed.add((line[0], line[1]))
    problems = [f"{path}: {name} is {n} lines (at most {args.limit}): break it into named steps"
                for n, path, name in long if (path, name) not in allowed]
    still_long = {(path, name) for _, path, name in long}
    problems += [f"{path}: {name} is no longer over {args.limit} lines: remove it from "
                 "tools/long_functions.txt" for path, name in sorted(allowed - still_long)]
    for p in problems:
        print(p)
    print(f"{len(long)} function(s) over {args.limit} lines, {len(allowed)} still listed in "
          "tools/long_functions.txt")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
