#!/usr/bin/env bash
# bash readme_names.sh FORESTWIND SOURCE_DIR [README]
#
# Every file, command and scenario key the README names exists: a newcomer who copies a name from it finds
# it. README defaults to SOURCE_DIR/README.md. What counts as a name is read from code (fenced blocks and
# `inline` spans) and from link targets, never from plain prose:
# - a path: a word with a '/' or ending in a source extension, or a link target. A word with a '/' must exist
#   under SOURCE_DIR (a glob must match something); a bare file name with a source extension (.cpp, .cl,
#   .md, ...) must exist somewhere in the tree. Not checked: paths under out/ (what a run writes) and build/
#   (what the build writes), bare names with other extensions (view.py, run.json: run outputs), lone
#   extensions (.vti), URLs, words with a shell variable ($PWD/build), and the usage's placeholders (FILE,
#   DIR, FOLDER, SCENARIO, OUT, QSM).
# - a command: `forestwind WORD [WORD]`. `forestwind WORD --help` must exit 0 with WORD's own usage (CLI11
#   prints the top-level help, and exits 0, for an unknown word); a second word must be a subcommand of WORD
#   when WORD has subcommands, and else a value WORD accepts (`bench wind`).
# - a scenario key: a dotted name under a top-level key (`wind.turbulence.intensity`, list indices as `[]` or
#   `[0]`), which must be a key of a table in SOURCE_DIR/docs/scenario.md.
# The test fails with one line for each name that does not exist.
set -u
forestwind=$1
source_dir=$2
readme=${3:-$source_dir/README.md}
[ -f "$readme" ] || { echo "FAIL: no README at $readme" >&2; exit 1; }
[ -x "$forestwind" ] || { echo "FAIL: no forestwind binary at $forestwind" >&2; exit 1; }
keys_page=$source_dir/docs/scenario.md

source_extensions='md|yaml|cpp|hpp|h|cl|sh|cmake|txt|pgm'
file_extensions="$source_extensions|png|py|csv|json|pvd|vti|vtp|vdb|tree|mp4|fwbasis|asc"
top_level_keys='scenario|seed|time|domain|boundaries|wind|events|obstacles|terrain|forest|solver|output'
placeholders='FILE|DIR|FOLDER|SCENARIO|OUT|QSM'

missing=()
miss() { missing+=("$1"); }

# The README's code, one piece a line: the lines of fenced blocks, then each inline span; and its link targets.
# shellcheck disable=SC2016  # the backticks are Markdown's, not the shell's
code=$(awk '/^[[:space:]]*```/ { fenced = !fenced; next } fenced { print }' "$readme"
  awk '/^[[:space:]]*```/ { fenced = !fenced; next } !fenced { print }' "$readme" |
    grep -oE '`[^`]+`' | sed -e 's/^`//' -e 's/`$//')
links=$(awk '/^[[:space:]]*```/ { fenced = !fenced; next } !fenced { print }' "$readme" |
  grep -oE '\]\([^)]+\)' | sed -e 's/^](//' -e 's/)$//' -e 's/#.*$//' -e 's/ .*$//')

declare -A seen=()
check_path() {
  local path=$1 origin=$2
  [[ -n "$path" && -z "${seen[p:$path]:-}" ]] || return 0
  seen[p:$path]=1
  case "$path" in
    *://* | *'$'* | out/* | build/* | ./out/* | ./build/*) return 0 ;;
  esac
  local component
  IFS=/ read -ra components <<<"$path"
  for component in "${components[@]}"; do
    [[ "${component%%.*}" =~ ^($placeholders)$ ]] && return 0
  done
  if [[ "$path" == */* ]]; then
    if [[ "$path" == *[*?]* ]]; then
      compgen -G "$source_dir/$path" >/dev/null || miss "$origin '$path': no file under $source_dir matches it"
    else
      [ -e "$source_dir/$path" ] || miss "$origin '$path': no such file or folder under $source_dir"
    fi
  elif [[ "$path" =~ \.($source_extensions)$ ]]; then
    [ -n "$(find "$source_dir" -path "$source_dir/.git" -prune -o -path "$source_dir/build*" -prune -o \
      -path "$source_dir/out" -prune -o -name "$path" -print -quit)" ] ||
      miss "$origin '$path': no file of that name in $source_dir"
  fi
}

check_key() {
  local key
  key=$(sed -E 's/\[[0-9]*\]/[]/g' <<<"$1")
  [[ -z "${seen[k:$key]:-}" ]] || return 0
  seen[k:$key]=1
  grep -qF -- "| \`$key\` |" "$keys_page" || miss "scenario key '$1': not a key in docs/scenario.md"
}

# usage_of ARGS...: the Usage line of `forestwind ARGS --help`, or nothing when it does not exit 0.
usage_of() {
  local out
  out=$("$forestwind" "$@" --help 2>&1) || return 1
  grep -m1 '^Usage:' <<<"$out"
}

check_command() {
  local w1=$1 w2=$2 usage
  local name="forestwind $w1${w2:+ $w2}"
  [[ -z "${seen[c:$name]:-}" ]] || return 0
  seen[c:$name]=1
  usage=$(usage_of "$w1") || { miss "command '$name': 'forestwind $w1 --help' fails"; return; }
  [[ "$usage" =~ ^Usage:\ [^\ ]*\ $w1(\ |$) ]] || { miss "command '$name': forestwind has no command '$w1'"; return; }
  [ -n "$w2" ] || return 0
  local usage2
  usage2=$(usage_of "$w1" "$w2") || { miss "command '$name': 'forestwind $w1 $w2 --help' fails"; return; }
  if [[ "$usage" == *SUBCOMMAND ]] && ! [[ "$usage2" =~ ^Usage:\ [^\ ]*\ $w1\ $w2(\ |$) ]]; then
    miss "command '$name': '$w1' has no subcommand '$w2'"
  fi
}

paths=0 commands=0 keys=0
while IFS= read -r piece; do
  read -ra words <<<"$piece"
  for ((i = 0; i < ${#words[@]}; i++)); do
    word=${words[i]}
    # Commands: forestwind (or a path ending in it) and the lowercase words after it.
    if [[ "$word" == forestwind || "$word" == */forestwind ]]; then
      w1=${words[i + 1]:-} w2=${words[i + 2]:-}
      if [[ "$w1" =~ ^[a-z][a-z0-9-]*$ ]]; then
        [[ "$w2" =~ ^[a-z][a-z0-9-]*$ ]] || w2=""
        check_command "$w1" "$w2"
        commands=$((commands + 1))
      fi
    fi
    # Paths and keys: strip an option's name (--script=...), brackets and punctuation around the word.
    word=${word#*=}
    word=$(sed -E -e 's/^[(["'\'']+//' -e 's/[])"'\'',;:.]+$//' <<<"$word")
    IFS='|' read -ra alternatives <<<"$word"
    for name in "${alternatives[@]}"; do
      [[ "$name" =~ ^\.[A-Za-z0-9]+$ ]] && continue  # a lone extension
      if [[ "$name" =~ ^($top_level_keys)(\[[0-9]*\])?(\.[a-z_0-9]+(\[[0-9]*\])?)+$ &&
        ! "$name" =~ \.($file_extensions)$ ]]; then
        check_key "$name"
        keys=$((keys + 1))
      elif [[ "$name" == */* || "$name" =~ \.($source_extensions)$ ]]; then
        check_path "$name" "path"
        paths=$((paths + 1))
      fi
    done
  done
done <<<"$code"
while IFS= read -r target; do
  [ -n "$target" ] || continue
  check_path "$target" "link"
  paths=$((paths + 1))
done <<<"$links"

if ((${#missing[@]} > 0)); then
  echo "FAIL: $readme names ${#missing[@]} thing(s) that do not exist:" >&2
  printf '  %s\n' "${missing[@]}" >&2
  exit 1
fi
echo "ok: $readme: $paths paths, $commands commands and $keys scenario keys named, all exist"
