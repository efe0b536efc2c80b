// Load for `softslc serve` (a benchmark, not a test): N clients each register a session and poll
// 100 words (N7:0-99, one 200-byte typed read, as HMI drivers pack contiguous addresses) at a
// fixed rate for a fixed time; every second each client also writes its own counter word
// (N7:50 + client, the values 1, 2, 3 ...). At the end it reads every client's word and checks it
// holds that client's last write, and prints request counts, errors and latency percentiles.
// Raw frames with Node's own net module: the load needs no npm package.
//   node load.js PORT [CLIENTS=50] [HZ=10] [SECONDS=60]
'use strict';
const net = require('net');
const [port, clients = 50, hz = 10, seconds = 60] = process.argv.slice(2).map(Number);

function frame(cmd, session, data) {
  const h = Buffer.alloc(24);
  h.writeUInt16LE(cmd, 0); h.writeUInt16LE(data.length, 2); h.writeUInt32LE(session, 4);
  return Buffer.concat([h, data]);
}
function pcccFrame(session, pccc) {
  const cip = Buffer.concat([Buffer.from([0x4b, 0x02, 0x20, 0x67, 0x24, 0x01, 0x07, 0, 0, 1, 2, 3, 4]), Buffer.from(pccc)]);
  const cpf = Buffer.alloc(16);
  cpf.writeUInt16LE(2, 6); cpf.writeUInt16LE(0xb2, 12); cpf.writeUInt16LE(cip.length, 14);
  cpf.writeUInt16LE(10, 4);
  return frame(0x6f, session, Buffer.concat([cpf, cip]));
}

class Client {
  constructor(id) { this.id = id; this.buf = Buffer.alloc(0); this.pending = []; this.tns = 0; }
  connect() {
    return new Promise((resolve, reject) => {
      this.sock = net.connect(port, '127.0.0.1', resolve);
      this.sock.setNoDelay(true);
      this.sock.on('error', reject);
      this.sock.on('data', (d) => {
        this.buf = Buffer.concat([this.buf, d]);
        while (this.buf.length >= 24 && this.buf.length >= 24 + this.buf.readUInt16LE(2)) {
          const n = 24 + this.buf.readUInt16LE(2);
          const f = this.buf.subarray(0, n); this.buf = this.buf.subarray(n);
          this.pending.shift()(f);
        }
      });
    });
  }
  request(f) { return new Promise((r) => { this.pending.push(r); this.sock.write(f); }); }
  async register() {
    const r = await this.request(frame(0x65, 0, Buffer.from([1, 0, 0, 0])));
    this.session = r.readUInt32LE(4);
  }
  async pccc(cmdBytes) {
    const tns = (this.tns = (this.tns + 1) & 0xffff);
    const r = await this.request(pcccFrame(this.session, [0x0f, 0x00, tns & 0xff, tns >> 8, ...cmdBytes]));
    return r.subarray(51);  // CMD, STS, TNS, data
  }
}

async function main() {
  const all = [];
  for (let i = 0; i < clients; i++) { const c = new Client(i); await c.connect(); await c.register(); all.push(c); }
  const latencies = [];
  let reads = 0, writes = 0, errors = 0;
  const lastWrite = new Array(clients).fill(0);
  const end = Date.now() + seconds * 1000;
  await Promise.all(all.map(async (c) => {
    let next = Date.now(), tick = 0;
    while (Date.now() < end) {
      const t0 = process.hrtime.bigint();
      const r = await c.pccc([0xa2, 200, 0x07, 0x89, 0x00, 0x00]);
      latencies.push(Number(process.hrtime.bigint() - t0) / 1e6);
      reads++;
      if (r[1] !== 0 || r.length !== 4 + 200) errors++;
      if (++tick % hz === 0) {
        const v = tick / hz;
        const w = await c.pccc([0xaa, 2, 0x07, 0x89, 50 + c.id, 0x00, v & 0xff, v >> 8]);
        writes++;
        if (w[1] !== 0) errors++; else lastWrite[c.id] = v;
      }
      next += 1000 / hz;
      await new Promise((res) => setTimeout(res, Math.max(0, next - Date.now())));
    }
  }));
  // Every client's last write is in the final data table.
  const r = await all[0].pccc([0xa2, 200, 0x07, 0x89, 0x00, 0x00]);
  let lost = 0;
  for (let i = 0; i < clients; i++) if (r.readUInt16LE(4 + 2 * (50 + i)) !== lastWrite[i]) lost++;
  for (const c of all) c.sock.end();
  latencies.sort((a, b) => a - b);
  const pct = (p) => latencies[Math.min(latencies.length - 1, Math.floor(latencies.length * p))].toFixed(2);
  console.log(`clients ${clients}, ${hz} Hz, ${seconds} s: ${reads} reads of 100 words (${(reads / seconds).toFixed(0)}/s), ` +
              `${writes} writes, ${errors} errors, ${lost} lost writes`);
  console.log(`read latency ms: p50 ${pct(0.5)}, p99 ${pct(0.99)}, max ${latencies[latencies.length - 1].toFixed(2)}`);
  process.exit(errors || lost ? 1 : 0);
}
main().catch((e) => { console.log(`FAIL ${e.stack || e}`); process.exit(1); });
