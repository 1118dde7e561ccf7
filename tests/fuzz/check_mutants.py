#!/usr/bin/env python3
"""Mutation fuzz of `forestwind check` (issue 44): each mutant is one of the scenario files given with one
number (a YAML scalar, an item of a list, or a number inside a quoted expression) swapped for an extreme value
(1e30, -1e-30, 2^31, 2^63, 0, .nan, .inf, ...) or scaled by a huge or tiny factor. Each mutant is checked
with a limit on its CPU time; the answer must be exit 0, or exit 2 with a message "FILE:LINE: KEY: ..." on
stderr, and come within the limit. Anything else is a finding: exit 1, a signal, a timeout, an exit 2 whose
message names no line and key. Deterministic: the same --seed and files give the same mutants.

  python3 tests/fuzz/check_mutants.py --forestwind build/forestwind --count 3000 scenarios/*.yaml
  python3 tests/fuzz/check_mutants.py ... --keep DIR   # every finding's mutant written to DIR

It prints the counts (mutants, exit 0, exit 2, findings by kind, answers slower than --slow CPU seconds) and
one line per finding and per slow answer; it exits 1 when there is a finding. `make fuzz-check` runs it on the
example scenarios (docs/fuzzing.md, "The mutation fuzz of check")."""

import argparse
import concurrent.futures
import os
import random
import resource
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# The values a number is swapped for: past any physical range both ways, the edges of the integer types a
# reader may parse into, zero and signs, and the YAML spellings of not-a-number and infinity.
EXTREMES = [
    "1e30", "-1e30", "1e-30", "-1e-30", "1e308", "-1e308", "1e300", "0", "-0", "-1", "1e-9", "1e6", "1e9",
    "1e12", "1e15", "2147483647", "2147483648", "-2147483649", "4294967296", "9223372036854775807",
    "18446744073709551616", ".nan", ".inf", "-.inf", "nan", "inf",
]
# Factors a number is scaled by: a value a slip of the keyboard away (x1000), and far past it.
FACTORS = [1e3, 1e6, 1e-6, -1.0]

# A number in YAML text or in an expression: not part of a word (a key, a name like p2) or of another number.
NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")
# What `forestwind check` prints before a message about the file.
PROGRAM = "forestwind: "


def numbers(text):
    """(start, end) of every number outside comments."""
    spans = []
    offset = 0
    for line in text.splitlines(keepends=True):
        code = line
        quoted = None
        for i, c in enumerate(line):  # a '#' outside quotes starts a comment
            if c in "\"'" and quoted in (None, c):
                quoted = None if quoted else c
            elif c == "#" and quoted is None and (i == 0 or line[i - 1] in " \t"):
                code = line[:i]
                break
        spans += [(offset + m.start(), offset + m.end()) for m in NUMBER.finditer(code)]
        offset += len(line)
    return spans


def mutate(text, rng):
    spans = numbers(text)
    start, end = rng.choice(spans)
    original = text[start:end]
    if rng.random() < 0.75:
        value = rng.choice(EXTREMES)
    else:
        value = repr(float(original) * rng.choice(FACTORS))
    return text[:start] + value + text[end:], start, original, value


def line_of(text, position):
    return text.count("\n", 0, position) + 1


def run(args, mutant, cache):
    """(kind, CPU seconds, stderr) of `forestwind check` on one mutant. The limit is on CPU time
    (RLIMIT_CPU), not wall time, so that a loaded machine does not turn a slow answer into a hang; a wall
    limit ten times as long stops a process that waits without computing."""
    limit = max(1, round(args.timeout))

    def limit_cpu():
        resource.setrlimit(resource.RLIMIT_CPU, (limit, limit + 1))

    env = dict(os.environ, FORESTWIND_CACHE_DIR=cache)
    with tempfile.TemporaryFile() as err:
        process = subprocess.Popen([args.forestwind, "check", str(mutant)], stdout=subprocess.DEVNULL,
                                   stderr=err, env=env, preexec_fn=limit_cpu)
        deadline = time.monotonic() + 10 * limit
        while True:  # os.wait4, not Popen.wait, to read the child's CPU time
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                process.kill()
            time.sleep(0.01)
        process.returncode = code = os.waitstatus_to_exitcode(status)
        err.seek(0)
        message = err.read().decode(errors="replace").strip()
    seconds = usage.ru_utime + usage.ru_stime
    if code in (-signal.SIGXCPU, -signal.SIGKILL):
        return "timeout", seconds, message
    if code == 0:
        return "exit 0", seconds, message
    if code == 2:
        # The message must read "FILE:LINE: KEY: what was expected".
        located = re.match(re.escape(PROGRAM + str(mutant)) + r":\d+: [\w.\[\]]+: .+", message)
        return ("exit 2" if located else "exit 2 without FILE:LINE: KEY"), seconds, message
    if code < 0:
        return f"signal {-code}", seconds, message
    return f"exit {code}", seconds, message


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("--forestwind", default="build/forestwind")
    parser.add_argument("--count", type=int, default=3000)
    parser.add_argument("--seed", type=int, default=44)
    parser.add_argument("--timeout", type=float, default=5.0, help="CPU seconds before a mutant counts as a hang")
    parser.add_argument("--slow", type=float, default=1.0, help="CPU seconds past which an answer counts as slow")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--keep", type=Path, help="folder to copy each finding's mutant into")
    args = parser.parse_args()

    rng = random.Random(args.seed)
    texts = {path: path.read_text() for path in args.files}
    work = Path(tempfile.mkdtemp(prefix="check_mutants."))
    try:
        # Each scenario's folder's other files (a heightmap, a tree) beside the mutants, which name them.
        for path in args.files:
            for sibling in path.parent.iterdir():
                if sibling.is_file() and sibling.suffix not in (".yaml", ".yml"):
                    shutil.copy(sibling, work / sibling.name)
        mutants = []
        for k in range(args.count):
            path = rng.choice(args.files)
            text, at, original, value = mutate(texts[path], rng)
            mutant = work / f"{k:05d}-{path.stem}.yaml"
            mutant.write_text(text)
            mutants.append((mutant, path, line_of(text, at), original, value))
        # One basis cache for all: a basis computed for one mutant is loaded by the next, as a user's would be
        # (the cache takes concurrent processes).
        cache = str(work / "cache")
        counts, findings, slow = {}, [], []
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = pool.map(lambda item: run(args, item[0], cache), mutants)
            for (mutant, path, line, original, value), (kind, seconds, message) in zip(mutants, results):
                counts[kind] = counts.get(kind, 0) + 1
                where = f"{path}:{line}: {original} -> {value}"
                if kind not in ("exit 0", "exit 2"):
                    last = message.splitlines()[-1] if message else ""
                    findings.append(f"{kind} ({seconds:.1f} s): {where}: {last[:160]}")
                    if args.keep:
                        args.keep.mkdir(parents=True, exist_ok=True)
                        shutil.copy(mutant, args.keep / mutant.name)
                elif seconds > args.slow:
                    slow.append(f"{seconds:.1f} s, {kind}: {where}")
    finally:
        shutil.rmtree(work, ignore_errors=True)

    print(f"mutants: {args.count} (seed {args.seed}, limit {args.timeout:g} s)")
    for kind in sorted(counts):
        print(f"  {kind}: {counts[kind]}")
    print(f"  slower than {args.slow:g} s (exit 0 or 2): {len(slow)}")
    for line in findings:
        print("finding: " + line)
    for line in slow:
        print("slow: " + line)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
