#!/usr/bin/env python3
"""The wall between ABI versions (docs/decisions/0011-abi-wall.md): past the adapter at the loader,
the engine knows only the current ABI's shape. Fails (exit status 1, one line per breach) when a
file of the engine outside the wall tells ABI minors apart or calls what only an older minor has,
or when an in-tree plugin or template reports a step the ABI 1.0 way.

    check_abi_wall.py [ROOT]     (ROOT: the source tree, by default the one this script is in)
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)

# The wall: the adapter, and the load-time check of what each minor's table must hold.
WALL = {
    "engine/plugin/include/plugin/abi_adapter.hpp",
    "engine/plugin/src/abi_adapter.cpp",
    "engine/plugin/src/function_table.cpp",
}

ENGINE_RULES = [
    (re.compile(r"\bstep_done\b"), "names step_done, the ABI 1.0 step report"),
    (re.compile(r"RUMBLE_HAS_FIELD"), "reads a field by the producer's struct_size"),
    (re.compile(r"abi_minor\s*(<|<=|>|>=|==|!=)\s*[0-9]"), "compares an ABI minor"),
    (re.compile(r"(->|\.)lifecycle\b"), "reads a table's lifecycle pointer (1.1 on)"),
    (re.compile(r"\b(mass_matrix|forces|wheel_kinematics|tangent|output_names|outputs)\s*\(\s*"
                r"(handle\(\)|handle_|self)\s*,"),
     "calls a vehicle's ABI 1.0 form without array lengths"),
]
PLUGIN_RULES = [
    (re.compile(r"(\.|->)step_done\s*\("), "reports a step with step_done, not step_report"),
]


def sources(directory):
    return sorted(p for p in (ROOT / directory).rglob("*")
                  if p.suffix in (".cpp", ".hpp", ".h", ".c") and p.is_file())


def breaches(directory, rules):
    for path in sources(directory):
        name = path.relative_to(ROOT).as_posix()
        if name in WALL:
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            for pattern, what in rules:
                if pattern.search(line):
                    yield f"{name}:{number}: {what}: past the ABI adapter (abi_adapter.hpp)"


found = list(breaches("engine", ENGINE_RULES))
for directory in ("plugins", "sdk/template", "sdk/template_coupler", "sdk/template_vehicle"):
    found += breaches(directory, PLUGIN_RULES)
print("\n".join(found) if found else "the engine past the ABI adapter knows the current ABI only")
sys.exit(1 if found else 0)
