#!/usr/bin/env python3
"""Checks the engine's built library graph and its includes against the target graph that
docs/architecture.md declares (its fenced block `rooms`), and that no plugin reaches into the
engine. Exit status 0 when they agree, 1 with one line per difference otherwise.

    tools/check_architecture.py [--root DIR] [--scratch DIR] [--dot FILE]

The built graph comes from `cmake --graphviz` on a fresh configuration of this source tree
(tests and benchmarks off, nothing is built) in DIR (a temporary directory by default). --dot
writes the engine's part of that graph, rooms and the packages they link, for `dot`
(tools/architecture_graph.sh draws docs/architecture.svg from it).
"""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent  # --root changes it (the check's own test)

# A package's headers, as a room includes them: a room that includes them must link the package,
# and a room that links it must include them. Packages without a clear header (Threads, dl) are
# checked as links only.
PACKAGE_HEADERS = {
    "rumble_sdk": r"<rumble/",
    "nlohmann_json::nlohmann_json": r"<nlohmann/",
    "Eigen3::Eigen": r"<Eigen/",
    "Boost::headers": r"<boost/",
    "spdlog::spdlog": r"<spdlog/",
    "PkgConfig::FFTW3": r"<fftw3\.h>",
    "PkgConfig::LAPACKE": r"<lapacke\.h>",
    "OpenSSL::Crypto": r"<openssl/",
}
ALWAYS_LINKED = {"rumble_engine_options"}  # compile settings every room shares, not an arrow


def declared_rooms(doc_text):
    """{room: (set of rooms, set of packages)} from the ```rooms block of docs/architecture.md."""
    block = re.search(r"```rooms\n(.*?)```", doc_text, re.S)
    if not block:
        sys.exit("docs/architecture.md: no ```rooms block (the target graph) found")
    rooms = {}
    for line in block.group(1).splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        name, rest = line.split(":", 1)
        uses, _, packages = rest.partition("|")
        rooms[name.strip()] = (set(uses.split()), set(packages.split()))
    return rooms


def built_edges(scratch):
    """{target: {direct link dependencies}} of a fresh configuration, from `cmake --graphviz`."""
    build = pathlib.Path(scratch) / "configure"
    build.mkdir(parents=True, exist_ok=True)
    (build / "CMakeGraphVizOptions.cmake").write_text(
        "set(GRAPHVIZ_GENERATE_PER_TARGET FALSE)\nset(GRAPHVIZ_GENERATE_DEPENDERS FALSE)\n")
    graph = pathlib.Path(scratch) / "built.dot"
    configure = subprocess.run(
        ["cmake", "-S", str(ROOT), "-B", str(build), "-DRUMBLE_BUILD_TESTS=OFF",
         "-DRUMBLE_BUILD_BENCH=OFF", f"--graphviz={graph}"],
        capture_output=True, text=True)
    if configure.returncode != 0:
        sys.exit("configuring the source tree failed:\n" + configure.stdout + configure.stderr)
    edges = {}
    for line in graph.read_text().splitlines():
        m = re.search(r'->.*// (\S+) -> (\S+)', line)
        if m:
            edges.setdefault(m.group(1), set()).add(m.group(2))
    return edges


def included_rooms(room_dir, rooms):
    """{included room or package pattern: first file that includes it} for one engine room."""
    found = {}
    for path in sorted(room_dir.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h"):
            continue
        text = path.read_text()
        for m in re.finditer(r'#include "([a-z_]+)/', text):
            if m.group(1) in rooms:
                found.setdefault(m.group(1), path)
        for package, pattern in PACKAGE_HEADERS.items():
            if re.search(r"#include " + pattern, text):
                found.setdefault(package, path)
    return found


def check(rooms, edges):
    problems = []
    targets = {f"rumble_{r}": r for r in rooms}
    for room, (uses, packages) in rooms.items():
        target = f"rumble_{room}"
        if target not in edges and (uses or packages):
            problems.append(f"{target}: not built, or it links nothing")
            continue
        linked = edges.get(target, set()) - ALWAYS_LINKED
        want = {f"rumble_{u}" for u in uses} | packages
        for extra in sorted(linked - want):
            problems.append(f"{target} links {extra}, which docs/architecture.md does not allow"
                            f" (its rooms block says {room}: {' '.join(sorted(uses))} |"
                            f" {' '.join(sorted(packages))})")
        for missing in sorted(want - linked):
            problems.append(f"{target} does not link {missing}, which docs/architecture.md "
                            "declares: remove the arrow from the doc or link it")
        room_dir = ROOT / "engine" / room
        if not room_dir.is_dir():
            problems.append(f"engine/{room}: the room docs/architecture.md declares is missing")
            continue
        includes = included_rooms(room_dir, rooms)
        for used, where in sorted(includes.items()):
            if used == room:
                continue
            allowed = used in uses if used in rooms else used in packages
            if not allowed:
                problems.append(f"{where.relative_to(ROOT)} includes {used}, which room "
                                f"{room} may not use (docs/architecture.md)")
        for used in sorted((uses | (packages & PACKAGE_HEADERS.keys())) - includes.keys()):
            problems.append(f"room {room} links {used} but includes none of its headers: "
                            "remove the arrow")
    # Nothing but the engine's own rooms and the executable may link a room: plugins build
    # against the SDK alone, as a third party would.
    for target, deps in sorted(edges.items()):
        if target in targets or target in ("rumble", "rumble_engine"):
            continue
        for dep in sorted(deps & targets.keys()):
            problems.append(f"{target} links the engine's {dep}: plugins use the SDK only")
    for path in sorted((ROOT / "plugins").rglob("*")):
        if path.suffix in (".hpp", ".cpp", ".h"):
            for m in re.finditer(r'#include "([a-z_]+)/', path.read_text()):
                own = any((p / m.group(1)).is_dir() for p in path.parents
                          if p.is_relative_to(ROOT / "plugins"))  # a plugin's own folder
                if m.group(1) in rooms and not own:
                    problems.append(f"{path.relative_to(ROOT)} includes the engine's "
                                    f"{m.group(1)}/: plugins use the SDK only")
    return problems


def write_dot(rooms, edges, out):
    """The rooms as boxes naming the packages they link, and the arrows between rooms. Arrows
    implied by others (A -> B -> C makes A -> C) are left to `tred` to drop for the picture."""
    short = {"nlohmann_json::nlohmann_json": "json", "rumble_sdk": "sdk", "Eigen3::Eigen": "Eigen",
             "Boost::headers": "Boost", "spdlog::spdlog": "spdlog", "Threads::Threads": "threads",
             "PkgConfig::FFTW3": "FFTW", "PkgConfig::LAPACKE": "LAPACKE",
             "OpenSSL::Crypto": "OpenSSL"}
    lines = ["digraph rumble_engine {",
             '  rankdir=BT; node [shape=box, style=rounded, fontname="Helvetica", fontsize=11];']
    for room in rooms:
        linked = edges.get(f"rumble_{room}", set()) - ALWAYS_LINKED
        packages = sorted(short.get(d, d) for d in linked if d.removeprefix("rumble_") not in rooms)
        label = room + (f"\\n<{', '.join(packages)}>" if packages else "")
        lines.append(f'  "{room}" [label="{label}"];')
        for dep in sorted(d.removeprefix("rumble_") for d in linked):
            if dep in rooms:
                lines.append(f'  "{room}" -> "{dep}";')
    lines += ['  "rumble (executable)" [style=solid];', '  "rumble (executable)" -> "cli";', "}"]
    pathlib.Path(out).write_text("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", help="the source tree to check (default: this script's)")
    parser.add_argument("--scratch", help="directory for the configuration (default: temporary)")
    parser.add_argument("--dot", help="write the engine's built graph to this file")
    args = parser.parse_args()
    global ROOT
    if args.root:
        ROOT = pathlib.Path(args.root).resolve()
    rooms = declared_rooms((ROOT / "docs" / "architecture.md").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        edges = built_edges(args.scratch or tmp)
    problems = check(rooms, edges)
    if args.dot:
        write_dot(rooms, edges, args.dot)
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} difference(s) between the built engine and docs/architecture.md")
        return 1
    print(f"the engine's {len(rooms)} rooms link and include as docs/architecture.md declares")
    return 0


if __name__ == "__main__":
    sys.exit(main())
