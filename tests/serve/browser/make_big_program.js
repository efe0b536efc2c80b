// Writes a 10,000-rung program for the online view's scale test (big_program.js): blocks of five
// rungs — contacts in a branch driving a coil, a timer, a compare, a math box, a counter — over
// B3, N7, T4 and C5, so every shape the page draws (contacts, coils, boxes, branches, comments)
// appears throughout the file.
//   node make_big_program.js OUT.slc [RUNGS]
'use strict';
const fs = require('fs');
const [out, rungsArg] = process.argv.slice(2);
const rungs = Number(rungsArg || 10000);
const lines = ['START 1747-L552', 'SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0', 'SLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1',
  'PROJECT "BIG"', 'LADDER 2 MAIN'];
for (let r = 0; r < rungs; r++) {
  const b = r % 200, t = r % 100, n = r % 200;
  lines.push(`% Rung: ${r} %`);
  switch (r % 5) {
    case 0:
      lines.push(`% Block ${r / 5}: a seal-in on B3:${b}. %`);
      lines.push(`SOR BST XIC I:1/${r % 16} NXB XIC B3:${b}/0 BND XIO B3:${b}/1 OTE B3:${b}/0 EOR `);
      break;
    case 1: lines.push(`SOR XIC B3:${b}/0 TON T4:${t} 0.01 50 0 EOR `); break;
    case 2: lines.push(`SOR GRT N7:${n} 10 OTE B3:${b}/2 EOR `); break;
    case 3: lines.push(`SOR XIC T4:${t}/DN ADD N7:${n} 1 N7:${n} EOR `); break;
    default: lines.push(`SOR XIC B3:${b}/2 CTU C5:${t} 1000 0 OTE O:2/${r % 16} EOR `); break;
  }
}
lines.push('');
fs.writeFileSync(out, lines.join('\n'));
