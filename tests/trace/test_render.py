"""Golden tests of `softslc render --text` for every example program, and of the drawing with state.

Usage: test_render.py SOFTSLC_BINARY EXAMPLES_DIR GOLDEN_DIR [--update]

The golden files are the oracle: each was reviewed by eye against its ladder source (every
instruction, operand, branch leg, rung comment and symbol in place; outputs against the right
rail). --update rewrites them from the current output (review the diff before committing).
"""

import os
import subprocess
import sys
import tempfile

SOFTSLC, EXAMPLES, GOLDEN = sys.argv[1], sys.argv[2], sys.argv[3]
UPDATE = "--update" in sys.argv[4:]


def render(*args):
    p = subprocess.run([SOFTSLC, "render", *args], capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit("softslc render %s exited %d:\n%s" % (" ".join(args), p.returncode, p.stderr))
    return p.stdout


def cases():
    ladder = os.path.join(EXAMPLES, "ladder")
    for root, _, files in sorted(os.walk(ladder)):
        for f in sorted(files):
            if f.endswith(".slc"):
                path = os.path.join(root, f)
                rel = os.path.relpath(path, ladder)
                yield rel.replace(os.sep, "__")[:-4] + ".txt", lambda path=path: render(path, "--text")
    seal = os.path.join(ladder, "seal_in", "seal_in.slc")

    def seal_state():
        # START pressed for three scans: MOTOR sealed in, the counter's CU set (no count on the
        # first pass), the timer idle.
        with tempfile.TemporaryDirectory() as tmp:
            state = os.path.join(tmp, "s.state")
            subprocess.run([SOFTSLC, "run", seal, "--set", "START_PB=1", "--scans", "3", "--state", state],
                           check=True, capture_output=True)
            return render(seal, "--state", state)
    yield "state__seal_in_started.txt", seal_state
    sn = os.path.join(ladder, "1747-sn")
    yield "state__d_btr_control_logic_after_3_scans.txt", lambda: render(
        os.path.join(sn, "d_btr_control_logic.slc"), "--bench", os.path.join(sn, "d_btr_control_logic.bench"),
        "--after-scans", "3", "--rung", "0..2")


failures = 0
seen = 0
for name, produce in cases():
    seen += 1
    text = produce()
    golden = os.path.join(GOLDEN, name)
    if UPDATE:
        with open(golden, "w") as f:
            f.write(text)
        continue
    if not os.path.exists(golden):
        print("MISSING %s (run with --update and review it)" % golden)
        failures += 1
        continue
    with open(golden) as f:
        expected = f.read()
    if expected != text:
        failures += 1
        print("DIFF %s" % name)
        for i, (a, b) in enumerate(zip(expected.splitlines(), text.splitlines())):
            if a != b:
                print("  line %d\n  expected: %s\n  actual:   %s" % (i + 1, a, b))
                break
        else:
            print("  the outputs differ in length")
# The JSON form is the same layout as data: rung 0 of seal_in.slc is
# BST XIC START_PB NXB XIC MOTOR BND XIO STOP_PB XIO OL_TRIPPED OTE MOTOR, in that (code) order,
# the OTE against the right rail; after START was pressed every instruction of it is true.
import json  # noqa: E402

if not UPDATE:
    seal = os.path.join(EXAMPLES, "ladder", "seal_in", "seal_in.slc")
    with tempfile.TemporaryDirectory() as tmp:
        state = os.path.join(tmp, "s.state")
        subprocess.run([SOFTSLC, "run", seal, "--set", "START_PB=1", "--scans", "3", "--state", state],
                       check=True, capture_output=True)
        layout = json.loads(render(seal, "--rung", "0", "--state", state, "--json"))
    blocks = layout["files"][0]["rungs"][0]["blocks"]
    got = [(b["mnemonic"], b["above"][-2], b["index"], b["true"]) for b in blocks]
    want = [("XIC", "START_PB", 0, True), ("XIC", "MOTOR", 1, True), ("XIO", "STOP_PB", 2, True),
            ("XIO", "OL_TRIPPED", 3, True), ("OTE", "MOTOR", 4, True)]
    if got != want or blocks[-1]["x"] + blocks[-1]["w"] != layout["width"] - 1:
        failures += 1
        print("JSON layout of seal_in rung 0: got %s" % got)
print("%d golden files, %d differ" % (seen, failures))
sys.exit(1 if failures else 0)
