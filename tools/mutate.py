#!/usr/bin/env python3
"""Mutation run: hostile and careless inputs through every softslc command.

    tools/mutate.py SOFTSLC [--count N] [--seed S] [--timeout CPU_SECONDS] [--wall-timeout SECONDS] [--keep DIR]
                            [--shard K/N]

Takes the example programs (*.slc), test files (*.test) and bench files (*.bench) under
examples/, mutates copies of them (bytes flipped, lines dropped, duplicated or shuffled, structure
keywords and hostile tokens inserted, deep nesting, huge numbers, a UTF-8 byte-order mark, UTF-16,
truncation) and runs each mutant through the commands that read it: check, fmt, disasm, scantime,
run (with --set/--print/--state) for programs; test for test files; run --bench and test for
benches. SOFTSLC should be a build with AddressSanitizer and UndefinedBehaviorSanitizer (the fuzz
build, tools/fuzz.sh, has one). A run fails the mutation run when it ends by a signal, prints a
sanitizer report, exits with a status softslc never uses (anything but 0-3 and 128+SIGINT/TERM),
or runs over the timeout (CPU seconds; a run stuck without using CPU is caught by
--wall-timeout). Each failing input is kept in --keep (default build-mutate/) with the
command line, and the run ends with a table of figures for docs/robustness.md.

--shard K/N runs only the mutants whose number is K modulo N (every process still generates all of
them, so the mutants are those of the unsharded run): N processes with K = 0..N-1 together run
exactly the unsharded run, one per core.

Deterministic for a given --seed. Python 3 standard library only (Debian's python3).
"""
import argparse
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HOSTILE_TOKENS = [
    "BST", "NXB", "BND", "SOR", "EOR", "XIC", "OTE", "MOV", "JSR", "LBL", "SBR", "RET", "END",
    "1e309", "-1e309", "99999999999999999999", "0x", "0xFFFFFFFFFFFFFFFFF", "#N7:0", "N7:[N7:[N7:0]]",
    "I:1/32", "O:2/16", "N7:999", "T4:0.ACC", "B3/4096", "%", '"', "(", ")", "{", "}", "[", "]", "=",
    "\x00", "\xff\xfe", "\t", "\r", "==", "..", "N7:0..65535", "scan 1000000000", "for 100000h",
]


def mutate(data: bytes, rng: random.Random) -> bytes:
    lines = data.split(b"\n")
    kind = rng.randrange(14)
    if kind == 0 and data:  # flip bytes
        b = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b)
    if kind == 1 and len(lines) > 1:  # drop lines
        for _ in range(rng.randint(1, 3)):
            if len(lines) > 1:
                del lines[rng.randrange(len(lines))]
        return b"\n".join(lines)
    if kind == 2:  # duplicate a line many times (size, error counts)
        i = rng.randrange(len(lines))
        lines[i:i + 1] = [lines[i]] * rng.choice([2, 50, 5000, 40000])
        return b"\n".join(lines)
    if kind == 3 and len(lines) > 2:  # shuffle a few lines
        for _ in range(rng.randint(1, 4)):
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    if kind == 4:  # insert hostile tokens between words
        words = data.split(b" ")
        for _ in range(rng.randint(1, 6)):
            words.insert(rng.randrange(len(words) + 1), rng.choice(HOSTILE_TOKENS).encode("latin-1"))
        return b" ".join(words)
    if kind == 5:  # deep branch nesting in a rung
        depth = rng.choice([17, 200, 5000])
        rung = b"SOR " + b"BST XIC B3:0/0 " * depth + b"OTE B3:0/1 " + b"NXB XIC B3:0/2 BND " * depth + b"EOR"
        i = rng.randrange(len(lines) + 1)
        lines.insert(i, rung)
        return b"\n".join(lines)
    if kind == 6:  # deep nesting of brackets/parentheses/braces anywhere
        opener, closer = rng.choice([(b"(", b")"), (b"{", b"}"), (b"[", b"]")])
        depth = rng.choice([65, 1000, 40000])
        pos = rng.randrange(len(data) + 1)
        return data[:pos] + opener * depth + b"1" + closer * rng.choice([0, depth]) + data[pos:]
    if kind == 7 and data:  # truncate
        return data[:rng.randrange(len(data))]
    if kind == 8:  # byte-order marks and UTF-16
        choice = rng.randrange(3)
        if choice == 0:
            return b"\xef\xbb\xbf" + data
        if choice == 1:
            return b"\xff\xfe" + data.decode("latin-1").encode("utf-16-le")
        return data.decode("latin-1").encode("utf-16-le")
    if kind == 9:  # huge and odd numbers in place of numbers
        out = bytearray()
        for tok in data.split(b" "):
            if tok.strip(b"\n").isdigit() and rng.random() < 0.3:
                tok = rng.choice([b"1e309", b"99999", b"-99999", b"65536", b"4294967296", b"1.5", b"0x10000"])
            out += tok + b" "
        return bytes(out[:-1])
    if kind == 10:  # a very long line
        i = rng.randrange(len(lines))
        lines[i] = lines[i] + b" XIC" * rng.choice([1000, 50000])
        return b"\n".join(lines)
    if kind == 11:  # non-UTF-8 bytes in names and strings
        pos = rng.randrange(len(data) + 1)
        return data[:pos] + bytes(rng.randrange(128, 256) for _ in range(rng.randint(1, 8))) + data[pos:]
    if kind == 12:  # empty or whitespace only
        return rng.choice([b"", b"\n", b" " * 100, b"\x00" * 100])
    # several mutations at once
    for _ in range(rng.randint(2, 4)):
        data = mutate(data, rng)
        if len(data) > 4 * 1024 * 1024:
            break
    return data


SANITIZER_MARKS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:", "UndefinedBehaviorSanitizer",
                   "terminate called", "internal error")


def run_one(cmd, cwd, timeout, wall_timeout):
    """Runs one command; returns (verdict or None, wall seconds, CPU seconds, stderr).

    The time limit is on CPU (RLIMIT_CPU: SIGXCPU after `timeout` seconds), not on the wall clock:
    on a 2-core machine shared with other sessions (some at a higher priority) a run under `nice`
    can spend 19 s of wall time on 0.4 s of CPU. A run that makes no progress without using CPU
    (waiting on a lock, a pipe) is caught by the wall-clock limit `wall_timeout`."""
    env = dict(os.environ)
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0")
    env.setdefault("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1")
    limit = int(timeout + 0.999)

    def limit_cpu():
        resource.setrlimit(resource.RLIMIT_CPU, (limit, limit + 1))

    start = time.monotonic()
    # CPU seconds of the run: the children's rusage, reaped by subprocess.run even when killed.
    before = resource.getrusage(resource.RUSAGE_CHILDREN)

    def cpu():
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    try:
        p = subprocess.run(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, timeout=wall_timeout, env=env, preexec_fn=limit_cpu)
    except subprocess.TimeoutExpired:
        return "no progress in %.0f s of wall time (%.1f s of CPU)" % (wall_timeout, cpu()), \
            time.monotonic() - start, cpu(), b""
    elapsed = time.monotonic() - start
    used = cpu()
    err = p.stderr.decode("utf-8", "replace")
    if p.returncode == -signal.SIGXCPU or used > timeout:
        return "over %.0f s of CPU" % timeout, elapsed, used, p.stderr
    if p.returncode < 0:
        return "signal %d" % -p.returncode, elapsed, used, p.stderr
    if any(m in err for m in SANITIZER_MARKS):
        return "sanitizer", elapsed, used, p.stderr
    if p.returncode not in (0, 1, 2, 3):
        return "exit %d" % p.returncode, elapsed, used, p.stderr
    return None, elapsed, used, p.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("softslc")
    ap.add_argument("--count", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=10.0, help="CPU seconds one run may take")
    ap.add_argument("--wall-timeout", type=float, default=120.0,
                    help="wall-clock seconds after which a run that is not finishing counts as stuck")
    ap.add_argument("--keep", default=str(ROOT / "build-mutate"))
    ap.add_argument("--shard", default="0/1", help="K/N: run only the mutants numbered K modulo N")
    args = ap.parse_args()
    try:
        shard, shards = (int(x) for x in args.shard.split("/"))
        if not 0 <= shard < shards:
            raise ValueError
    except ValueError:
        ap.error("--shard: write K/N with 0 <= K < N, for example 0/2")
    softslc = str(Path(args.softslc).resolve())
    rng = random.Random(args.seed)
    examples = ROOT / "examples"
    sources = {kind: sorted(examples.rglob("*." + kind)) for kind in ("slc", "test", "bench")}
    keep = Path(args.keep)
    keep.mkdir(parents=True, exist_ok=True)
    figures = {"slc": 0, "test": 0, "bench": 0}
    runs = 0
    failures = []
    slowest = (0.0, "")
    most_cpu = (0.0, "")
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="softslc-mutate-") as tmp:
        tmp = Path(tmp)
        for n in range(args.count):
            kind = ("slc", "test", "bench")[n % 3]
            original = rng.choice(sources[kind])
            mutant = mutate(original.read_bytes(), rng)
            if n % shards != shard:
                continue
            # Work in a copy of the example's directory, so a mutated test file finds its program
            # and bench, and nothing in the tree is ever written.
            work = tmp / ("m%05d" % n)
            shutil.copytree(original.parent, work)
            target = work / original.name
            target.write_bytes(mutant)
            figures[kind] += 1
            if kind == "slc":
                p = str(target)
                cmds = [["check", p], ["fmt", p], ["disasm", p], ["scantime", p, "--json"],
                        ["run", p, "--scans", "5", "--set", "N7:0=5", "--print", "S:1", "--state", str(work / "s.bin")],
                        ["run", p, "--for", "50ms", "--json"]]
            elif kind == "test":
                cmds = [["test", str(target), "--junit", str(work / "j.xml"), "--coverage-json", str(work / "c.json")]]
            else:
                programs = sorted(work.glob("*.slc"))
                cmds = [["test", str(work)]]
                if programs:
                    cmds.append(["run", str(programs[0]), "--bench", str(target), "--for", "100ms"])
            for c in cmds:
                runs += 1
                verdict, elapsed, used, err = run_one([softslc] + c, work, args.timeout, args.wall_timeout)
                if elapsed > slowest[0]:
                    slowest = (elapsed, " ".join(c[:1]) + " " + original.name)
                if used > most_cpu[0]:
                    most_cpu = (used, " ".join(c[:1]) + " " + original.name)
                if verdict:
                    name = "fail-%05d-%s" % (n, original.name)
                    (keep / name).write_bytes(mutant)
                    (keep / (name + ".txt")).write_text(
                        "softslc " + " ".join(c).replace(str(work), "DIR") + "\nverdict: " + verdict + "\n\n" +
                        err.decode("utf-8", "replace")[-4000:])
                    failures.append((verdict, c[0], original.name, name))
                    print("FAIL %s: softslc %s on a mutant of %s (kept as %s)" % (verdict, c[0], original.name, name),
                          flush=True)
            shutil.rmtree(work, ignore_errors=True)
            if sum(figures.values()) % 50 == 0:
                print("%d mutants (up to number %d), %d runs, %d failures, %.0f s, most CPU in one run %.1f s (%s)" % (
                    sum(figures.values()), n, runs, len(failures), time.monotonic() - started, most_cpu[0], most_cpu[1]), flush=True)
    total = time.monotonic() - started
    print()
    print("| mutants | programs | test files | benches | command runs | failures | most CPU in one run | "
          "slowest run (wall) | wall time |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    print("| %d | %d | %d | %d | %d | %d | %.1f s (%s) | %.1f s (%s) | %.0f s |" % (
        sum(figures.values()), figures["slc"], figures["test"], figures["bench"], runs, len(failures), most_cpu[0], most_cpu[1],
        slowest[0], slowest[1], total))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
