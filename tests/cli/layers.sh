#!/usr/bin/env bash
# The layers point one way (docs/design.md, "Layout"): every #include "..." of a source file names a folder its
# layer may use. Prints each include that points the wrong way and exits 1; exits 0 when there is none.
#
#   bash tests/cli/layers.sh SOURCE_DIR
set -euo pipefail
cd "${1:?usage: layers.sh SOURCE_DIR}"

# layer: the folders its files may include (its own included). Listed top-down; a file belongs to the first
# layer whose folder prefixes its path.
layers=(
  "host/cli: base kernels fluid trees host/runtime host/stages io viz host/app host/bench host/cli"
  "host/bench: base kernels fluid trees host/runtime host/stages io viz host/app host/bench"
  "host/app: base kernels fluid trees host/runtime host/stages io viz host/app"
  "viz: base kernels fluid trees io viz"
  "io: base kernels fluid trees io"
  "host/stages: base kernels fluid trees host/runtime host/stages"
  "host/runtime: base kernels host/runtime"
  "trees: base kernels fluid trees"
  "fluid: base kernels fluid"
  "kernels: kernels"
  "base: base"
)

status=0
checked=0
while IFS= read -r file; do
  layer="" allowed=""
  for entry in "${layers[@]}"; do
    folder=${entry%%:*}
    if [[ $file == "$folder"/* ]]; then
      layer=$folder
      allowed=${entry#*: }
      break
    fi
  done
  [ -n "$layer" ] || continue
  while IFS= read -r included; do
    ok=0
    for folder in $allowed; do
      [[ $included == "$folder"/* ]] && ok=1 && break
    done
    # A header beside the file (the kernels' includes) is its own layer.
    [[ $included != */* ]] && ok=1
    if [ $ok -eq 0 ]; then
      echo "$file: includes \"$included\", but $layer/ may use only: $allowed" >&2
      status=1
    fi
    checked=$((checked + 1))
  done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$file")
done < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.cl'; git ls-files -o --exclude-standard '*.cpp' '*.hpp' '*.h' '*.cl')

echo "layers: $checked includes checked"
exit $status
