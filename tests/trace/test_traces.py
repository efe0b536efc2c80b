"""Signal traces end to end: `softslc run --trace` and `softslc test --trace-dir`, read back with the
independent VCD reader in vcd_reader.py.

Usage: test_traces.py SOFTSLC_BINARY EXAMPLES_DIR

Expected values come from the ladder and the manuals, as in the examples' .test files:
  seal_in.slc (see seal_in.test): MOTOR = (START_PB or MOTOR) and not STOP_PB and not OL_TRIPPED;
    T4:0 is a TON with a 0.01 s time base and preset 100, accuracy -0.01..0 s (1747-RM001 p. 2-8),
    so DN, and with it the OTL of OL_TRIPPED (rung 2), comes in the scan that crosses 1.000 s;
    rung 0 runs before rung 2, so MOTOR drops one scan later; a CTU does not count on the first
    scan after entering Run (docs/semantics.md, "CU is set").
  d_btr_control_logic.slc (1747-SN user manual appendix D, see d_btr_control_logic.test): the
    scanner shows ST (M1 status bit 14) within 41 ms of the enable, DN (bit 13) within 67 ms of ST
    (appendix A's block-transfer throughput), the status words 0xC484 (EN echo, ST, EW, RW,
    address) and 0xE484; the ladder then buffers the data (N10:1 = 200 from the bench) and drops
    EN, and the scanner frees the status within 41 ms.
  pid_level.slc (see pid_level.test): a PI level loop on a tank with a 0.5 s dead time and a 5 s
    lag; the trace shows the valve (the PID's CV) open at once and the level (its PV) start after
    the dead time and settle at the setpoint.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vcd_reader import Vcd, first_time, signed  # noqa: E402

SOFTSLC = None
EXAMPLES = None


def softslc(*args, ok=(0,)):
    p = subprocess.run([SOFTSLC, *args], capture_output=True, text=True)
    if p.returncode not in ok:
        raise AssertionError("softslc %s exited %d:\n%s%s" % (" ".join(args), p.returncode, p.stdout, p.stderr))
    return p


class SealIn(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.path = os.path.join(cls.dir.name, "seal_in.vcd")
        cls.program = os.path.join(EXAMPLES, "ladder", "seal_in", "seal_in.slc")
        cls.args = [cls.program, "--set", "START_PB=1", "--set", "OL_CONTACT=1", "--for", "1.5s"]
        softslc("run", *cls.args, "--trace", cls.path)
        with open(cls.path) as f:
            cls.text = f.read()
        cls.vcd = Vcd(cls.text)

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def test_header(self):
        self.assertEqual(self.vcd.timescale, "1us")
        self.assertEqual(self.vcd["MOTOR"].kind, "wire")
        self.assertEqual(self.vcd["MOTOR"].size, 1)
        self.assertEqual(self.vcd["T4:0.ACC"].size, 16)
        self.assertEqual(self.vcd["scan"].size, 32)

    def test_start_seals_in_on_the_first_scan(self):
        motor, scan = self.vcd["MOTOR"], self.vcd["scan"]
        self.assertEqual(motor.at(0), 0)
        first_scan_end = scan.times[1]
        self.assertEqual(scan.at(first_scan_end), 1)
        self.assertEqual(motor.at(first_scan_end), 1)
        self.assertEqual(self.vcd["T4:0/EN"].at(first_scan_end), 1)

    def test_timer_half_way(self):
        self.assertIn(self.vcd["T4:0.ACC"].at(500_000), (49, 50))

    def test_overload_trips_in_the_scan_that_crosses_one_second(self):
        tripped = first_time(self.vcd["OL_TRIPPED"], lambda v: v == 1)
        self.assertIsNotNone(tripped)
        scan = self.vcd["scan"]
        # seal_in.test's window: the first execution of rung 1 at or after 1.000 s, and a scan
        # of this program takes about 1 ms on a 5/03 (the trace stamps the end of that scan).
        self.assertGreaterEqual(tripped, 1_000_000)
        self.assertLessEqual(tripped, 1_003_000)
        self.assertEqual(first_time(self.vcd["T4:0/DN"], lambda v: v == 1), tripped)
        self.assertEqual(self.vcd["T4:0.ACC"].at(tripped), 100)
        self.assertEqual(self.vcd["TRIP_LAMP"].at(tripped), 1)
        # MOTOR drops at the next scan boundary: rung 0 runs before rung 2.
        next_scan = [t for t in scan.times if t > tripped][0]
        self.assertEqual(self.vcd["MOTOR"].at(tripped), 1)
        self.assertEqual(first_time(self.vcd["MOTOR"], lambda v: v == 0, after=0), next_scan)

    def test_counter_does_not_count_the_first_pass(self):
        self.assertEqual(self.vcd["C5:0.ACC"].at(1_500_000), 0)

    def test_scan_marker_counts_every_scan(self):
        scan = self.vcd["scan"]
        self.assertEqual([v for _, v in scan.changes()], list(range(len(scan.times))))
        self.assertGreaterEqual(scan.times[-1], 1_500_000)
        self.assertEqual(scan.times, self.vcd.times)  # every timestamp is a scan boundary

    def test_byte_identical_across_runs(self):
        again = os.path.join(self.dir.name, "again.vcd")
        softslc("run", *self.args, "--trace", again)
        with open(again) as f:
            self.assertEqual(f.read(), self.text)
        svg1, svg2 = (os.path.join(self.dir.name, n) for n in ("a.svg", "b.svg"))
        softslc("run", *self.args, "--trace", svg1, "--signals", "START_PB,MOTOR,T4:0.ACC")
        softslc("run", *self.args, "--trace", svg2, "--signals", "START_PB,MOTOR,T4:0.ACC")
        with open(svg1) as a, open(svg2) as b:
            self.assertEqual(a.read(), b.read())

    def test_svg_timing_diagram(self):
        svg = os.path.join(self.dir.name, "t.svg")
        softslc("run", *self.args, "--trace", svg, "--signals", "START_PB,MOTOR,T4:0")
        root = ET.parse(svg).getroot()
        self.assertEqual(root.tag, "{http://www.w3.org/2000/svg}svg")
        names = [g.get("data-name") for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "signal"]
        # A whole timer is traced as its EN and DN bits and its accumulator.
        self.assertEqual(names, ["START_PB", "MOTOR", "T4:0/EN", "T4:0/DN", "T4:0.ACC"])

    def test_limit_truncates_and_says_so(self):
        small = os.path.join(self.dir.name, "small.vcd")
        p = softslc("run", *self.args, "--trace", small, "--trace-limit", "2k")
        self.assertIn("--trace-limit 2k reached", p.stderr)
        with open(small) as f:
            text = f.read()
        vcd = Vcd(text)
        self.assertTrue(any("trace limit" in c for c in vcd.comments))
        body = text[text.index("$enddefinitions"):]
        self.assertLess(len(body), 2048 + 400)  # the value changes, plus the closing comment
        self.assertLess(vcd["scan"].times[-1], 1_000_000)

    def test_bad_signal_is_a_usage_error(self):
        p = softslc("run", self.program, "--trace", os.path.join(self.dir.name, "x.vcd"), "--signals", "NOPE",
                    ok=(2,))
        self.assertIn("NOPE", p.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.dir.name, "x.vcd")))


    def test_gtkwave_reads_it(self):
        # GTKWave's own VCD loader (vcd2fst, Debian package gtkwave) converts the file to FST and
        # fst2vcd writes it back: the values GTKWave sees are the ones the trace holds.
        if not shutil.which("vcd2fst") or not shutil.which("fst2vcd"):
            self.skipTest("gtkwave (vcd2fst, fst2vcd) is not installed")
        fst = os.path.join(self.dir.name, "seal_in.fst")
        subprocess.run(["vcd2fst", self.path, fst], check=True, capture_output=True)
        back = subprocess.run(["fst2vcd", fst], check=True, capture_output=True, text=True).stdout
        vcd = Vcd(back)
        for name in ("MOTOR", "OL_TRIPPED", "T4:0.ACC", "scan"):
            self.assertEqual(vcd[name].changes(), self.vcd[name].changes(), name)


class BlockTransfer(unittest.TestCase):
    def test_btr_handshake(self):
        d = os.path.join(EXAMPLES, "ladder", "1747-sn")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bt.vcd")
            softslc("run", os.path.join(d, "d_btr_control_logic.slc"), "--bench",
                    os.path.join(d, "d_btr_control_logic.bench"), "--set", "BTR_REQUEST=1", "--for", "250ms",
                    "--signals", "VIRTUAL_ENABLE,BT_PENDING,CHECK_STATUS,M0:1.100,M1:1.100,N10:0,N10:1",
                    "--trace", path)
            with open(path) as f:
                vcd = Vcd(f.read())
        en, status, m0 = vcd["VIRTUAL_ENABLE"], vcd["M1:1.100"], vcd["M0:1.100"]
        self.assertEqual(status.size, 16)
        # The first scan configures the read and enables it (rungs 2:0, 2:5, 2:6).
        enabled = first_time(en, lambda v: v == 1)
        self.assertEqual(enabled, vcd["scan"].times[1])
        self.assertEqual(m0.at(enabled), 0x8084)
        self.assertEqual(vcd["BT_PENDING"].at(enabled), 1)
        st = first_time(status, lambda v: v & 0x4000)
        self.assertIsNotNone(st)
        self.assertLessEqual(st - enabled, 41_000)
        self.assertEqual(status.at(st), 0xC484)
        dn = first_time(status, lambda v: v & 0x2000)
        self.assertIsNotNone(dn)
        self.assertLessEqual(dn - st, 67_000)
        self.assertEqual(status.at(dn), 0xE484)
        # The ladder sees DN in its next scan: EN drops, data buffered, the disable sent.
        dropped = first_time(en, lambda v: v == 0, after=enabled)
        self.assertIsNotNone(dropped)
        self.assertLessEqual(dropped - dn, 25_000)  # T_ps <= 25 ms on this 5/02 (the .test's bound)
        self.assertEqual(vcd["N10:1"].at(dropped), 200)
        self.assertIn(vcd["N10:0"].at(dropped), range(100, 104))
        self.assertEqual(m0.at(dropped), 0x0084)
        self.assertEqual(vcd["CHECK_STATUS"].at(dropped), 1)
        # The scanner frees the status; rung 2:2 ends the cycle.
        freed = first_time(status, lambda v: v == 0, after=dn)
        self.assertIsNotNone(freed)
        self.assertLessEqual(freed - dropped, 41_000)
        self.assertEqual(first_time(vcd["CHECK_STATUS"], lambda v: v == 0, after=dropped) is not None, True)
        self.assertEqual(signed(m0.at(enabled), 16), -32636)


class PidStepResponse(unittest.TestCase):
    """examples/ladder/pid: the level loop's step response as `softslc run --trace` records it. The
    tank (pid_level.bench) has a 0.5 s dead time and a 5 s lag; the loop starts from an empty tank
    with the setpoint at 50.0 % (8191.5 counts)."""

    def test_the_trace_shows_the_step_response(self):
        d = os.path.join(EXAMPLES, "ladder", "pid")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "pid.vcd")
            softslc("run", os.path.join(d, "pid_level.slc"), "--bench", os.path.join(d, "pid_level.bench"),
                    "--for", "30s", "--trace", path)
            with open(path) as f:
                vcd = Vcd(f.read())
        pv, cv = vcd["LEVEL"], vcd["VALVE"]
        self.assertEqual(pv.size, 16)
        # The valve opens fully in the first scan (the error is the whole setpoint).
        self.assertEqual(cv.at(vcd["scan"].times[1]), 16383)
        # Nothing reaches the level before the dead time (within one 10 ms plant period after it).
        rises = first_time(pv, lambda v: signed(v, 16) > 0)
        self.assertIsNotNone(rises)
        self.assertGreaterEqual(rises, 500_000)
        self.assertLessEqual(rises, 520_000)
        # It settles within 1 % of 8191.5 and does not overshoot by more than 10 %.
        self.assertLessEqual(max(signed(v, 16) for _, v in pv.changes()), 9011)
        settled = 20_000_000
        for t, v in pv.changes():
            if t >= settled:
                self.assertTrue(8109 <= signed(v, 16) <= 8274, (t, v))
        self.assertTrue(8109 <= signed(pv.at(30_000_000), 16) <= 8274)


class TestTraceDir(unittest.TestCase):
    def test_one_vcd_per_failing_test(self):
        seal = os.path.join(EXAMPLES, "ladder", "seal_in", "seal_in.slc")
        with tempfile.TemporaryDirectory() as tmp:
            test = os.path.join(tmp, "wrong.test")
            with open(test, "w") as f:
                f.write('program %s\n\ntest "passes"\n  scan 1\n  expect MOTOR == 0\n\n'
                        'test "start: wrong on purpose"\n  set START_PB = 1\n  scan 3\n  expect MOTOR == 0\n'
                        % os.path.relpath(seal, tmp))
            out = os.path.join(tmp, "traces")
            p = softslc("test", test, "--trace-dir", out, "-j", "1", ok=(1,))
            self.assertIn("1 passed, 1 failed", p.stdout)
            self.assertEqual(sorted(os.listdir(out)), ["wrong.start__wrong_on_purpose.vcd"])
            with open(os.path.join(out, "wrong.start__wrong_on_purpose.vcd")) as f:
                vcd = Vcd(f.read())
            scan = vcd["scan"]
            self.assertEqual(scan.at(scan.times[-1]), 3)
            self.assertEqual(vcd["MOTOR"].at(scan.times[-1]), 1)
            softslc("test", test, "--trace-dir", out, "--trace-all", "-j", "1", ok=(1,))
            self.assertEqual(sorted(os.listdir(out)), ["wrong.passes.vcd", "wrong.start__wrong_on_purpose.vcd"])


class Plot(unittest.TestCase):
    """`softslc plot` draws a VCD written by `run --trace` as the timing diagram `run --trace OUT.svg`
    draws from the same run: the same waveforms (checked point for point), valid XML."""

    def test_plot_of_a_vcd_draws_the_same_waveforms_as_run_trace_svg(self):
        seal = os.path.join(EXAMPLES, "ladder", "seal_in", "seal_in.slc")
        args = [seal, "--set", "START_PB=1", "--set", "OL_CONTACT=1", "--for", "1.5s",
                "--signals", "START_PB,MOTOR,T4:0,OL_TRIPPED,N7:0"]
        with tempfile.TemporaryDirectory() as tmp:
            vcd, direct, plotted = (os.path.join(tmp, n) for n in ("t.vcd", "direct.svg", "plotted.svg"))
            softslc("run", *args, "--trace", vcd)
            softslc("run", *args, "--trace", direct)
            softslc("plot", vcd, "-o", plotted)
            ns = {"s": "http://www.w3.org/2000/svg"}
            a, b = ET.parse(direct).getroot(), ET.parse(plotted).getroot()
            names = [g.get("data-name") for g in b.findall("s:g[@class='signal']", ns)]
            with open(vcd) as f:
                self.assertEqual(names, [n for n in Vcd(f.read()).vars if n != "scan"])
            self.assertEqual(names, [g.get("data-name") for g in a.findall("s:g[@class='signal']", ns)])

            def shapes(root):
                return [(e.tag, e.get("points")) for g in root.findall("s:g[@class='signal']", ns)
                        for e in g if e.get("points")]
            self.assertEqual(shapes(a), shapes(b))
            self.assertGreater(len(shapes(b)), len(names))  # waveforms and bus segments were drawn
            # A subset, in the order asked for.
            softslc("plot", vcd, "-o", plotted, "--signals", "MOTOR,START_PB", "--title", "two")
            root = ET.parse(plotted).getroot()
            self.assertEqual([g.get("data-name") for g in root.findall("s:g[@class='signal']", ns)], ["MOTOR", "START_PB"])

    def test_bad_input_is_a_positioned_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "bad.vcd")
            with open(bad, "w") as f:
                f.write("$timescale 1us $end\n$var wire 1 \" MOTOR $end\n$enddefinitions $end\n#0\n1\"\n#5\n1?\n")
            p = softslc("plot", bad, "-o", os.path.join(tmp, "x.svg"), ok=(1,))
            self.assertIn("bad.vcd:7: error: unknown identifier '?'", p.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "x.svg")))
            with open(bad, "w") as f:
                f.write("$timescale 1us $end\n$var wire 1 \" MOTOR $end\n$enddefinitions $end\n#0\n1\"\n")
            p = softslc("plot", bad, "-o", os.path.join(tmp, "x.svg"), "--signals", "NOPE", ok=(1,))
            self.assertIn("no signal named NOPE", p.stderr)


if __name__ == "__main__":
    SOFTSLC, EXAMPLES = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=2)
