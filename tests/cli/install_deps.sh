#!/usr/bin/env bash
# bash install_deps.sh SCRIPT WORK
#
# scripts/install-deps.sh without root and without apt: FORESTWIND_DEPS_ASSUME_INSTALLED fakes what dpkg
# has installed, and stub `id` (root) and `apt-get` (records its arguments) on PATH show whether apt-get
# would run. With python3-paraview installed it must stop with code 3 and a message naming the conflict
# and both ways out, before any apt-get call; without it, it must run apt-get update and install as before.
set -u
script=$1
work=$2
rm -rf "$work"
mkdir -p "$work/bin"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cat >"$work/bin/id" <<'STUB'
#!/bin/sh
[ "${1-}" = "-u" ] && { echo 0; exit 0; }
exec /usr/bin/id "$@"
STUB
cat >"$work/bin/apt-get" <<STUB
#!/bin/sh
echo "apt-get \$*" >>"$work/apt.log"
STUB
chmod +x "$work/bin/id" "$work/bin/apt-get"

# run NAME FAKE_INSTALLED ARGS...: runs the script with the stubs; sets rc, out, err.
run() {
  local name=$1 installed=$2
  shift 2
  rm -f "$work/apt.log"
  PATH="$work/bin:$PATH" FORESTWIND_DEPS_ASSUME_INSTALLED="$installed" \
    bash "$script" "$@" >"$work/$name.out" 2>"$work/$name.err"
  rc=$?
  out=$(cat "$work/$name.out")
  err=$(cat "$work/$name.err")
}
expect_in_err() {
  [[ "$err" == *"$1"* ]] || fail "$name: stderr lacks '$1':"$'\n'"$err"
}

# python3-paraview installed: code 3 before apt-get, with the facts and both choices.
for args in "" "--check-only"; do
  name="paraview${args:+-check-only}"
  # shellcheck disable=SC2086
  run "$name" "paraview python3-paraview" $args
  [ "$rc" -eq 3 ] || fail "$name: exit code $rc, expected 3; stderr: $err"
  [ ! -e "$work/apt.log" ] || fail "$name: apt-get ran: $(cat "$work/apt.log")"
  expect_in_err "python3-paraview"
  expect_in_err "libvtk9-dev depends on"
  expect_in_err "python3-vtk9"
  expect_in_err "Conflicts: python3-vtk9"
  expect_in_err "apt-get remove python3-paraview"
  expect_in_err "pvpython"
  expect_in_err "paraview --script"
  expect_in_err "container"
  expect_in_err "Nothing has been installed or removed"
done

# ParaView without its Python (or nothing at all) does not conflict.
for installed in "" "paraview"; do
  run check-only "$installed" --check-only
  [ "$rc" -eq 0 ] || fail "check-only with '$installed' installed: exit code $rc; stderr: $err"
  [ -z "$err" ] || fail "check-only with '$installed' installed wrote to stderr: $err"
  [[ "$out" == *"no known conflict"* ]] || fail "check-only with '$installed' installed printed: $out"
  [ ! -e "$work/apt.log" ] || fail "--check-only ran apt-get"
done

# The ordinary run (CI, as root, clean Debian 12) still calls apt-get update, then install with libvtk9-dev.
run clean "paraview"
[ "$rc" -eq 0 ] || fail "clean run: exit code $rc; stderr: $err"
[ -e "$work/apt.log" ] || fail "clean run did not call apt-get"
[ "$(sed -n 1p "$work/apt.log")" = "apt-get update" ] || fail "first apt-get call: $(sed -n 1p "$work/apt.log")"
install=$(sed -n 2p "$work/apt.log")
[[ "$install" == "apt-get install -y --no-install-recommends "*" libvtk9-dev "*" catch2" ]] ||
  fail "second apt-get call: $install"

# Without the override the script asks dpkg-query: a stub reports python3-paraview in a given state.
mkdir -p "$work/dpkg"
cat >"$work/dpkg/dpkg-query" <<STUB
#!/bin/sh
for last; do :; done
if [ "\$last" = python3-paraview ] && [ -s "$work/paraview-status" ]; then cat "$work/paraview-status"; exit 0; fi
echo "dpkg-query: no packages found matching \$last" >&2
exit 1
STUB
chmod +x "$work/dpkg/dpkg-query"
for status in installed half-configured unpacked config-files not-installed absent; do
  if [ "$status" = absent ]; then : >"$work/paraview-status"; else echo "$status" >"$work/paraview-status"; fi
  rm -f "$work/apt.log"
  env -u FORESTWIND_DEPS_ASSUME_INSTALLED PATH="$work/dpkg:$work/bin:$PATH" \
    bash "$script" >"$work/dpkg.out" 2>"$work/dpkg.err"
  rc=$?
  case "$status" in
    installed | half-configured | unpacked) want=3 ;;
    *) want=0 ;;
  esac
  [ "$rc" -eq "$want" ] || fail "dpkg-query says python3-paraview is '$status': exit code $rc, expected $want"
  if [ "$want" -eq 3 ]; then
    [ ! -e "$work/apt.log" ] || fail "dpkg-query says '$status': apt-get ran"
  else
    [ -e "$work/apt.log" ] || fail "dpkg-query says '$status': apt-get did not run"
  fi
done

# Bad usage.
run usage "" --bogus
[ "$rc" -eq 2 ] || fail "--bogus: exit code $rc, expected 2"
[ ! -e "$work/apt.log" ] || fail "--bogus ran apt-get"

echo "install-deps.sh: conflict check, --check-only, clean run and bad usage behave as expected"
