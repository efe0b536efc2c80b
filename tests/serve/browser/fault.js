// A divide by zero in examples/ladder/faults/math_faults.slc: I:1/0 (DO_DIVIDE) divides N7:0 by
// N7:1 = 0, which leaves the overflow trap S:5/0 set at END: major fault 0020h, S:6 = 0020h
// (examples/ladder/faults/math_faults.test, from 1747-RM001 4-8 and 4-10). The page shows the
// fault banner with the code and S:6; clearing the trap and the fault and returning to Run hides it.
'use strict';
const { until, check, write, run } = require('./harness');

run(async (page, outdir) => {
  await until(page, 'rung 0 drawn', () => document.querySelector('svg.rung[data-rung="0"] g.instruction[data-mnemonic="DIV"]'));
  check(await page.$eval('#fault', (e) => e.hidden), 'no fault banner before the divide');
  await write(page, 'N7:1', 0);
  await write(page, 'I:1/0', 1);
  await until(page, 'the fault banner', () => !document.getElementById('fault').hidden);
  check(await page.$eval('#fault-code', (e) => e.textContent) === '0020h', 'banner shows major fault 0020h');
  check(await page.$eval('#fault-s6', (e) => e.textContent) === '0020h', 'banner shows S:6 = 0020h');
  check(await page.$eval('#mode', (e) => e.dataset.mode) === 'faulted', 'mode shows faulted');
  const where = await page.$eval('#fault-where', (e) => e.textContent);
  check(where.length > 0, `banner names where it faulted (${where})`);
  const div = await page.$eval('svg.rung[data-rung="0"] g.instruction[data-mnemonic="DIV"]', (g) => [...g.querySelectorAll('text.value')].map((t) => t.textContent).join(' '));
  check(/32767</.test(div), `the DIV box shows N7:2 = 32767 (${div})`);
  await page.screenshot({ path: `${outdir}/fault_banner.png` });
  // Release DO_DIVIDE and clear the overflow trap S:5/0 (else END faults again), then clear the
  // fault and return to Run.
  await write(page, 'I:1/0', 0);
  await write(page, 'S:5/0', 0);
  await page.click('#btn-clear-fault');
  await page.click('#btn-run');
  await until(page, 'the banner gone after clear fault and Run', () => document.getElementById('fault').hidden && document.getElementById('mode').dataset.mode === 'run');
});
