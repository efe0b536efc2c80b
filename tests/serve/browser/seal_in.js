// The scenario on examples/ladder/seal_in/seal_in.slc: press START by writing I:1/0 (the
// START_PB symbol's address in the example), see the MOTOR coil and its rung turn true and stay
// sealed in after START is released; force STOP_PB (I:1/1) on and see the motor drop out; change
// mode; pause and single-step; trend C5:0.ACC; show the T4 and I data tables. Structural checks
// on the screenshot's elements (which rungs, instructions and states), not on pixels.
'use strict';
const { until, check, write, force, truth, scans, run } = require('./harness');

run(async (page, outdir) => {
  // Rung 0: XIC START_PB (0), XIC MOTOR (1), XIO STOP_PB (2), XIO OL_TRIPPED (3), OTE MOTOR (4).
  await until(page, 'rung 0 drawn', () => document.querySelector('svg.rung[data-rung="0"] g.instruction[data-index="4"]'));
  const mnemonics = await page.$$eval('svg.rung[data-rung="0"] g.instruction', (gs) => gs.map((g) => g.dataset.mnemonic).join(' '));
  check(mnemonics === 'XIC XIC XIO XIO OTE', `rung 0 holds XIC XIC XIO XIO OTE (${mnemonics})`);
  const rungs = await page.$$eval('svg.rung', (s) => s.map((e) => e.dataset.rung).join(','));
  check(rungs === '0,1,2,3,4,5,6', `rungs 0-5 and END drawn (${rungs})`);
  check(await truth(page, 0, 4) === '0', 'MOTOR coil false before START');
  check(await truth(page, 0, 2) === '1', 'XIO STOP_PB true (not pressed)');

  await write(page, 'I:1/0', 1);
  await until(page, 'MOTOR coil true', () => document.querySelector('svg.rung[data-rung="0"] g.instruction[data-index="4"]').dataset.true === '1');
  await until(page, 'rung 0 energized', () => document.querySelector('svg.rung[data-rung="0"]').dataset.energized === '1');
  check(await truth(page, 0, 0) === '1', 'XIC START_PB true while pressed');
  await page.screenshot({ path: `${outdir}/seal_in_motor_on.png` });

  await write(page, 'START_PB', 0);
  await until(page, 'START_PB released', () => document.querySelector('svg.rung[data-rung="0"] g.instruction[data-index="0"]').dataset.true === '0');
  check(await truth(page, 0, 4) === '1', 'MOTOR stays on, sealed in through XIC MOTOR');
  check(await truth(page, 0, 1) === '1', 'the seal-in contact XIC MOTOR is true');

  // Rung 4 counts motor starts: its CTU box shows the live accumulator.
  const acc = await page.$eval('svg.rung[data-rung="4"] g.instruction[data-mnemonic="CTU"]', (g) => [...g.querySelectorAll('text')].map((t) => t.textContent).join(' '));
  check(/Accum 1\b/.test(acc), `CTU C5:0 shows Accum 1 (${acc})`);

  await force(page, 'I:1/1', 'on');
  await until(page, 'the force listed', () => document.querySelector('#forces li[data-state="on"]'));
  await until(page, 'MOTOR dropped out by the forced STOP_PB', () => document.querySelector('svg.rung[data-rung="0"] g.instruction[data-index="4"]').dataset.true === '0');
  check(await truth(page, 0, 2) === '0', 'XIO STOP_PB false while forced on');
  await force(page, 'I:1/1', 'remove');
  await until(page, 'the force removed', () => !document.querySelector('#forces li'));

  await page.click('#btn-program');
  await until(page, 'Program mode', () => document.getElementById('mode').dataset.mode === 'program');
  await page.click('#btn-run');
  await until(page, 'Run mode', () => document.getElementById('mode').dataset.mode === 'run');

  await page.click('#btn-pause');
  await until(page, 'paused', () => document.getElementById('mode').dataset.paused === '1');
  const before = await scans(page);
  await page.click('#btn-step');
  await until(page, 'one scan stepped', (n) => new RegExp(` ${n + 1} scans`).test(document.getElementById('clock').textContent), before);
  check(await scans(page) === before + 1, `Step runs exactly one scan (${before} -> ${before + 1})`);
  await page.click('#btn-resume');
  await until(page, 'running again', () => document.getElementById('mode').dataset.paused === '0');

  await page.fill('#trend-address', 'C5:0.ACC');
  await page.click('#btn-trend-add');
  await until(page, 'a trend line with points', () => {
    const p = document.querySelector('#trend polyline[data-address="C5:0.ACC"]');
    return p && p.getAttribute('points').split(' ').length >= 3;
  });
  check(await page.$eval('#trend-legend li', (li) => li.dataset.value) === '1', 'trend legend shows C5:0.ACC = 1');

  await page.click('#data-files li[data-name="T4"]');
  await until(page, 'T4 table', () => document.querySelector('#table td[data-address="T4:0.PRE"]'));
  check(/PRE 100/.test(await page.$eval('#table td[data-address="T4:0.PRE"]', (td) => td.textContent)), 'T4:0.PRE shows 100');
  await page.click('#data-files li[data-name="O"]');
  await until(page, 'O table with MOTOR off', () => document.querySelector('#table td[data-address="O:2.0/0"][data-value="0"]'));
  // Start again for the picture (docs/images/online-view.png): motor on, its output bit in the O table.
  await write(page, 'START_PB', 1);
  await until(page, 'O:2.0/0 on in the O table', () => document.querySelector('#table td[data-address="O:2.0/0"][data-value="1"]'));
  await write(page, 'START_PB', 0);
  await page.screenshot({ path: `${outdir}/seal_in_online.png` });
});
