# Sourced by the command-line test scripts (tests/cli/*.sh) after they read FORESTWIND and WORK: a fresh
# scratch folder, and fail(), which stops the test with a message.
set -u
rm -rf "$work"
mkdir -p "$work"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
