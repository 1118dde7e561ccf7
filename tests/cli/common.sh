# Sourced by the command-line test scripts (tests/cli/*.sh) after they read FORESTWIND and WORK: a fresh
# scratch folder, and fail(), which stops the test with a message.
set -u
rm -rf "$work"
mkdir -p "$work"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# The temporaries of atomic writes under folder $1 ("<file>.tmp-<pid>"), one per line.
temporaries() {
  find "$1" -name '*.tmp-*' 2>/dev/null
}
# Fails unless run.json in folder $1 says "status":"$2".
expect_status() {
  grep -q "\"status\":\"$2\"" "$1/run.json" 2>/dev/null || fail "$1/run.json does not say $2: $(cat "$1/run.json" 2>&1)"
}
# expect_texts WHAT MESSAGE TEXT...: fails unless MESSAGE holds every TEXT, naming WHAT.
expect_texts() {
  local what=$1 message=$2 text
  shift 2
  for text in "$@"; do
    case "$message" in
      *"$text"*) ;;
      *) fail "$what: the message does not say '$text': $message" ;;
    esac
  done
}
