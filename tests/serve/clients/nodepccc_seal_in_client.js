// nodepccc against `softslc serve examples/ladder/seal_in/seal_in.slc`: the field START button
// (I:1/0, the I file's element 0 bit 0) is pressed and released over the network, and the motor
// output (O:2/0, the O file's element 0 bit 0) is read back sealed in (seal_in.slc rung 0), with
// one start counted in C5:0 (rung 4). STOP (I:1/1) drops it out.
//   node nodepccc_seal_in_client.js PORT
'use strict';
const { createHarness } = require('./pccc_harness');

const port = parseInt(process.argv[2], 10);
const h = createHarness();
const { check, sleep } = h;
const read = async (items) => (await h.read(items)).values;
const write = async (item, value) => (await h.write(item, value)).bad;

async function main() {
  await h.connect(port);
  check('MOTOR (O:0/0) off after download', (await read(['O:0/0']))['O:0/0'], false);
  check('press START_PB (I:0/0)', await write('I:0/0', true), false);
  await sleep(200);
  check('release START_PB', await write('I:0/0', false), false);
  await sleep(200);
  const v = await read(['O:0/0', 'C5:0.ACC', 'I:0/0']);
  check('MOTOR sealed in after the button is released', v['O:0/0'], true);
  check('one start counted (C5:0.ACC)', v['C5:0.ACC'], 1);
  check('press STOP_PB (I:0/1)', await write('I:0/1', true), false);
  await sleep(200);
  check('MOTOR dropped out', (await read(['O:0/0']))['O:0/0'], false);
  await h.finish();
}
h.run(main);
