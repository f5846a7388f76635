#!/usr/bin/env bash
# Fails when a C/C++ file (tracked, or new and not ignored) is not clang-formatted (.clang-format at the top level).
set -euo pipefail
cd "$(dirname "$0")/.."
bad=()
while IFS= read -r f; do
  [ -f "$f" ] || continue
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files --cached --others --exclude-standard '*.cpp' '*.hpp' '*.h' '*.c')
if ((${#bad[@]})); then
  printf 'not clang-formatted (run clang-format -i):\n'; printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "format: ok"
