#!/usr/bin/env python3
"""Fails when a file of the repository cites a Markdown document that is not in the repository:
what the code relies on is written in docs/ (docs/architecture.md, "House rules"), so a reader of
the code can open every document a comment names.

    tools/check_citations.py

A citation is any name ending in .md; it resolves from the repository's root, from the citing
file's folder, or from docs/. Names of files that tools write into results directories (a
table.md under results/) are not citations.
"""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CITATION = re.compile(r"(?<![\w./-])((?:\.\./|\./)?[\w./-]*[\w-]+\.md)\b")
TEXT = re.compile(r"(\.(cpp|hpp|h|py|sh|cmake|txt|md|json|in|dict)|CMakeLists\.txt)$")


def written_by_a_tool(ref):
    return ref.startswith("/") or "results/" in ref or "WORK/" in ref or ref.endswith("table.md")


def main():
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout.split("\n")
    problems = []
    for name in filter(TEXT.search, files):
        path = os.path.join(ROOT, name)
        if not os.path.isfile(path):
            continue
        with open(path, errors="replace") as f:
            text = f.read()
        for m in CITATION.finditer(text):
            ref = m.group(1)
            where = [os.path.join(ROOT, ref), os.path.join(os.path.dirname(path), ref),
                     os.path.join(ROOT, "docs", ref)]
            if not written_by_a_tool(ref) and not any(os.path.exists(w) for w in where):
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{name}:{line}: cites {ref}, which is not in the repository: "
                                "write what it says into docs/ and cite that")
    for p in problems:
        print(p)
    print(f"{len(problems)} citation(s) of documents outside the repository")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
