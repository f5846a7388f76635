#!/usr/bin/env python3
"""The architecture check (tools/check_architecture.py) must fail on what docs/architecture.md
forbids. Copies the source tree (what git tracks) to a scratch directory, breaks the rules there
three ways, and expects one message per breach and exit status 1:
  - the post room includes a header of the run room (an arrow the target graph lacks);
  - the core room links FFTW (a package it does not use);
  - the Winkler soil plugin links the engine's core room (plugins use the SDK only);
that the function-length check (tools/check_function_length.py) fails on a function of 90
lines that tools/long_functions.txt does not list, and that the declared-once check
(tools/check_declared_once.py) fails on a default written again in C++.

    violations_test.py SOURCE_DIR SCRATCH_DIR
"""
import pathlib
import shutil
import subprocess
import sys

source, scratch = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
shutil.rmtree(scratch, ignore_errors=True)
tree = scratch / "tree"
tracked = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=source,
                         capture_output=True, text=True, check=True).stdout.split("\n")
for name in filter(None, tracked):
    if (source / name).is_file():
        (tree / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source / name, tree / name)


def edit(path, old, new):
    p = tree / path
    text = p.read_text()
    assert old in text, f"{path}: '{old}' not found: update this test"
    p.write_text(text.replace(old, new, 1))


edit("engine/post/src/ppv.cpp", '#include "post/ppv.hpp"\n',
     '#include "post/ppv.hpp"\n#include "run/run_scenario.hpp"\n')
edit("engine/CMakeLists.txt", "PUBLIC spdlog::spdlog Threads::Threads",
     "PUBLIC spdlog::spdlog Threads::Threads PkgConfig::FFTW3")
with open(tree / "plugins/soils/winkler/CMakeLists.txt", "a") as f:
    f.write("target_link_libraries(winkler PRIVATE rumble_core)\n")

with open(tree / "engine/post/src/ppv.cpp", "a") as f:
    f.write("namespace rumble {\nint too_long_for_a_reader() {\n  int x = 0;\n" +
            "  ++x;\n" * 86 + "  return x;\n}\n}  // namespace rumble\n")


def expect_caught(tool, message, what):
    """Runs tools/`tool` on the broken tree; exits unless it fails (status 1) saying `message`."""
    run = subprocess.run([sys.executable, str(tree / "tools" / tool)], capture_output=True,
                         text=True)
    print(run.stdout, run.stderr)
    if run.returncode != 1 or message not in run.stdout:
        print(f"{tool}: exit status {run.returncode} (1 expected), {what} not reported")
        sys.exit(1)


expect_caught("check_function_length.py", "too_long_for_a_reader is 90 lines",
              "the 90-line function")
edit("plugins/vehicles/single_wheel/single_wheel.cpp", 'p.get<double>("wheel_radius")',
     'p.get_or<double>("wheel_radius", 0.46)')
expect_caught("check_declared_once.py", 'writes the default of "wheel_radius" again',
              "the repeated default")

check = subprocess.run([sys.executable, str(tree / "tools/check_architecture.py"),
                        "--scratch", str(scratch / "check")], capture_output=True, text=True)
print(check.stdout, check.stderr)
expected = [
    "engine/post/src/ppv.cpp includes run, which room post may not use",
    "rumble_core links PkgConfig::FFTW3, which docs/architecture.md does not allow",
    "winkler links the engine's rumble_core: plugins use the SDK only",
]
missing = [e for e in expected if e not in check.stdout]
if check.returncode != 1 or missing:
    print(f"exit status {check.returncode} (1 expected); not reported: {missing}")
    sys.exit(1)
print("each breach was reported")
