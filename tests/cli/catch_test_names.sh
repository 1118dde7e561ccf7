#!/usr/bin/env bash
# bash catch_test_names.sh TEST_EXECUTABLE...
#
# Every Catch test case must become one CTest test of the same name. catch_discover_tests (Catch2 2.13)
# turns the names into a CMake list, so a ';' in a name splits it into two tests that match nothing, and an
# unmatched '[' glues every following name into one test; either way test cases silently stop running.
# This check fails on such a name and says which executable holds it.
set -euo pipefail

status=0
for executable in "$@"; do
  while IFS= read -r name; do
    [ -z "$name" ] && continue
    if [[ "$name" == *";"* ]]; then
      echo "$(basename "$executable"): test name contains ';' (CMake splits it): $name" >&2
      status=1
    fi
    depth=0
    for ((i = 0; i < ${#name}; i++)); do
      case "${name:i:1}" in
        "[") depth=$((depth + 1)) ;;
        "]") depth=$((depth - 1)) ;;
      esac
      if ((depth < 0)); then break; fi
    done
    if ((depth != 0)); then
      echo "$(basename "$executable"): test name has unbalanced brackets (CMake joins the names after it): $name" >&2
      status=1
    fi
  done < <("$executable" --list-test-names-only)
  echo "$(basename "$executable"): names checked"
done
exit "$status"
