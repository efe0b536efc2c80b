// nodepccc against `softslc serve examples/ladder/1747-sn/ch4_m1_status.slc --bench ...`: the
// 1747-SN scanner's M0/M1 files over PCCC, and the module's refusal as the client's error.
//
// nodepccc (like every PCCC client we know of) has no M address syntax, and the SLC's own
// typed-read file type code for M files is not in our sources, so softslc uses F0h (M0) and F1h
// (M1) with file = slot and element = word (docs/serve.md). This script addresses "N1:e" with
// nodepccc — file 1 (the slot), element e (the word) — and, for those requests only, changes the
// one file-type byte nodepccc puts on the wire from 89h (N) to F0h/F1h. Everything else — the
// session, the encapsulation, the reply parsing and the error reporting — is nodepccc's own.
//   node nodepccc_m_files_client.js PORT
'use strict';
const { createHarness } = require('./pccc_harness');

const port = parseInt(process.argv[2], 10);
const { conn, check, sleep, read, write, connect, finish, run } = createHarness();

// The M file the next requests address (0xF0 M0, 0xF1 M1), or null for ordinary data files.
let mFileType = null;
let rewritten = 0;
function rewriteMType(buf) {
  if (mFileType === null) return buf;
  const out = Buffer.from(buf);
  // The PCCC command follows the requestor ID: CMD 0F, STS 00, TNS (2), FNC, size, file, type.
  for (let i = 0; i + 7 < out.length; i++) {
    if (out[i] === 0x0f && out[i + 1] === 0x00 && [0xa2, 0xaa, 0xab].includes(out[i + 4]) && out[i + 6] === 1 &&
        out[i + 7] === 0x89) {
      out[i + 7] = mFileType;
      rewritten++;
    }
  }
  return out;
}

async function inM(type, f) {
  mFileType = type;
  try { return await f(); } finally { mFileType = null; }
}

async function main() {
  await connect(port);
  const write0 = conn.isoclient.write.bind(conn.isoclient);
  conn.isoclient.write = (buf, ...rest) => write0(rewriteMType(buf), ...rest);

  // Let the scanner scan the RIO link and the ladder copy its status (ch4_m1_status.test).
  await sleep(600);
  let r = await read(['N7:0']);
  check('N7:0: the ladder\'s copy of M1:1.0', r.values['N7:0'] & 3, 3);
  const copied = r.values['N7:0'];

  // M1:1.0 read directly: the scanner's status word, the same as the ladder's copy.
  r = await inM(0xf1, () => read(['N1:0']));
  check('M1:1.0 read without error', r.bad, false);
  check('M1:1.0 = the ladder\'s copy in N7:0', r.values['N1:0'], copied);

  // M0:1.210 (block-transfer buffer 2, unused by this program) written and read back, then one bit.
  check('write M0:1.210 = 4660', (await inM(0xf0, () => write('N1:210', 4660))).bad, false);
  r = await inM(0xf0, () => read(['N1:210']));
  check('M0:1.210 read back', r.values['N1:210'], 4660);
  check('write M0:1.210/4 = 0 (masked write)', (await inM(0xf0, () => write('N1:210/4', false))).bad, false);
  r = await inM(0xf0, () => read(['N1:210']));
  check('M0:1.210 after the bit write', r.values['N1:210'], 4660 & ~16);

  // The module's refusal: the SLC may not write the scanner's M1 file; nodepccc reports the write bad.
  check('write M1:1.0 is refused', (await inM(0xf1, () => write('N1:0', 0))).bad, true);
  r = await inM(0xf1, () => read(['N1:0']));
  check('M1:1.0 unchanged after the refusal', r.values['N1:0'], copied);
  // No module with M files in slot 5: a bad read.
  r = await inM(0xf0, () => read(['N5:0']));
  check('M0:5.0 (no module) is reported bad', r.bad, true);
  // Ordinary files still work on the same connection.
  r = await read(['N7:0']);
  check('N7:0 still served', r.bad, false);
  check('the M requests were sent as M requests', rewritten, (n) => n >= 7);

  await finish();
}

run(main);
