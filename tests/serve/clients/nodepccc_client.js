// nodepccc (the npm driver many Node-RED and HMI projects use for SLC/MicroLogix over
// EtherNet/IP) against `softslc serve examples/ladder/serve/hmi_panel.slc`: reads and writes
// every file type it addresses (O, I, S, B, T, C, R, N, F, ST) and checks that the ladder reacted.
// The expected values come from the program's DATA blocks and rungs (see hmi_panel.test).
//   node nodepccc_client.js PORT
'use strict';
const { createHarness } = require('./pccc_harness');

const port = parseInt(process.argv[2], 10);
const { check, sleep, read, write, connect, finish, run } = createHarness();

async function main() {
  await connect(port);

  // Download values (DATA blocks) and the ladder's first scans.
  let r = await read(['N7:0', 'F8:0', 'ST9:0', 'R6:0.LEN', 'T4:0.PRE', 'O:0/0', 'S:1/5']);
  check('read without error', r.bad, false);
  check('N7:0 (DATA 500)', r.values['N7:0'], 500);
  check('F8:0 = N7:0 / 10.0', r.values['F8:0'], 50);
  check('ST9:0 (DATA "READY")', r.values['ST9:0'], 'READY');
  check('R6:0.LEN (DATA 10)', r.values['R6:0.LEN'], 10);
  check('T4:0.PRE (TON preset 1000)', r.values['T4:0.PRE'], 1000);
  check('O:0/0 MOTOR off after download', r.values['O:0/0'], false);

  // B: the HMI start bit seals the motor in (rung 0); the output image shows it.
  check('write B3:0/1 (HMI_START) = 1', (await write('B3:0/1', true)).bad, false);
  await sleep(200);
  check('write B3:0/1 = 0', (await write('B3:0/1', false)).bad, false);
  await sleep(200);
  r = await read(['O:0/0', 'O:0/1', 'C5:0.ACC', 'T4:0/TT', 'B3:0']);
  check('O:0/0 MOTOR sealed in', r.values['O:0/0'], true);
  check('O:0/1 RUN_LAMP', r.values['O:0/1'], true);
  check('C5:0.ACC counted one start', r.values['C5:0.ACC'], 1);
  check('B3:0 word: both HMI bits off again', r.values['B3:0'], 0);

  // N: the set-point is copied to N7:1 while running and scaled into F8:0.
  check('write N7:0 = 777', (await write('N7:0', 777)).bad, false);
  await sleep(150);
  r = await read(['N7:1', 'F8:0']);
  check('N7:1 follows N7:0', r.values['N7:1'], 777);
  check('F8:0 = 77.7', r.values['F8:0'], (v) => Math.abs(v - 77.7) < 1e-4);

  // F: a float written whole and read back.
  check('write F8:2 = 12.5', (await write('F8:2', 12.5)).bad, false);
  r = await read(['F8:2']);
  check('F8:2 read back', r.values['F8:2'], 12.5);

  // T: a shorter preset, then the timer's ACC and DN bit (0.01 s base, so 50 = 0.5 s).
  check('write T4:0.PRE = 50', (await write('T4:0.PRE', 50)).bad, false);
  await sleep(800);
  r = await read(['T4:0.ACC', 'T4:0/DN', 'T4:0/EN']);
  check('T4:0.ACC reached the preset', r.values['T4:0.ACC'], (v) => v >= 50);
  check('T4:0/DN', r.values['T4:0/DN'], true);
  check('T4:0/EN', r.values['T4:0/EN'], true);

  // C: a preset written and read back.
  check('write C5:0.PRE = 7', (await write('C5:0.PRE', 7)).bad, false);
  r = await read(['C5:0.PRE', 'C5:0/DN']);
  check('C5:0.PRE read back', r.values['C5:0.PRE'], 7);
  check('C5:0/DN (1 start < 7)', r.values['C5:0/DN'], false);

  // ST: a new message string.
  check('write ST9:1 = "HELLO HMI"', (await write('ST9:1', 'HELLO HMI')).bad, false);
  r = await read(['ST9:1']);
  check('ST9:1 read back', r.values['ST9:1'], 'HELLO HMI');

  // I: the field STOP input (I:1/1, the I file's element 0 bit 1) drops the motor out.
  check('write I:0/1 (STOP_PB) = 1', (await write('I:0/1', true)).bad, false);
  await sleep(200);
  r = await read(['O:0/0', 'I:0/1', 'I:0']);
  check('O:0/0 MOTOR dropped out', r.values['O:0/0'], false);
  check('I:0/1 read back', r.values['I:0/1'], true);
  check('I:0 word', r.values['I:0'], 2);
  check('write I:0/1 = 0', (await write('I:0/1', false)).bad, false);

  // S: the mode bits of S:1 say Run (S:1/0-4 = 6, RM table: remote Run), written bits are refused
  // nowhere in softslc (docs/serve.md), so only a read is checked here.
  r = await read(['S:1']);
  check('S:1 mode bits = remote Run (6)', r.values['S:1'] & 0x1f, 6);

  // Errors: a file that does not exist reads with bad quality, the connection stays up.
  r = await read(['N42:0']);
  check('N42:0 (no such file) is reported bad', r.bad, true);
  r = await read(['N7:0']);
  check('the connection still serves after an error', r.values['N7:0'], 777);

  await finish();
}

run(main);
