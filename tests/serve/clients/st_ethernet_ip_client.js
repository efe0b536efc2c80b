// A second, independent EtherNet/IP implementation against `softslc serve`: st-ethernet-ip's own
// encapsulation and CIP encoders and parsers (not nodepccc's). It asks for ListIdentity over UDP
// and over TCP, parses the identity with st-ethernet-ip's ListIdentity parser, registers a
// session, sends Execute PCCC (4Bh to class 67h instance 1) through its SendRRData builder,
// writes and reads N7:5, and unregisters.
//   node st_ethernet_ip_client.js PORT
'use strict';
const dgram = require('dgram');
const net = require('net');
const { encapsulation, CIP } = require('st-ethernet-ip/dist/enip');
const Browser = require('st-ethernet-ip/dist/browser').default;

const port = parseInt(process.argv[2], 10);
let passed = 0, failed = 0;
function check(what, actual, expected) {
  const ok = JSON.stringify(actual) === JSON.stringify(expected);
  if (ok) { passed++; console.log(`ok   ${what}: ${JSON.stringify(actual)}`); }
  else { failed++; console.log(`FAIL ${what}: got ${JSON.stringify(actual)}, expected ${JSON.stringify(expected)}`); }
}

function udpListIdentity() {
  return new Promise((resolve, reject) => {
    const sock = dgram.createSocket('udp4');
    sock.on('message', (msg) => { sock.close(); resolve(msg); });
    sock.on('error', reject);
    sock.send(encapsulation.header.build(encapsulation.commands.ListIdentity), port, '127.0.0.1');
  });
}

// One request, one reply, on a TCP socket (frames are read whole by their length field).
function tcpClient() {
  const sock = net.connect(port, '127.0.0.1');
  let buf = Buffer.alloc(0);
  let waiting = null;
  sock.on('data', (d) => {
    buf = Buffer.concat([buf, d]);
    if (waiting && buf.length >= 24 && buf.length >= 24 + buf.readUInt16LE(2)) {
      const n = 24 + buf.readUInt16LE(2);
      const frame = buf.subarray(0, n);
      buf = buf.subarray(n);
      const w = waiting;
      waiting = null;
      w(frame);
    }
  });
  return {
    ready: new Promise((r) => sock.on('connect', r)),
    request: (frame) => new Promise((resolve) => { waiting = resolve; sock.write(frame); }),
    closed: new Promise((r) => sock.on('close', r)),
    end: () => sock.end(),
  };
}

// Execute PCCC through st-ethernet-ip's message router and logical-segment builders.
function executePccc(pccc) {
  const { LOGICAL } = CIP.EPATH.segments;
  const path = Buffer.concat([LOGICAL.build(LOGICAL.types.ClassID, 0x67), LOGICAL.build(LOGICAL.types.InstanceID, 1)]);
  const requestor = Buffer.from([0x07, 0x01, 0x00, 0x78, 0x56, 0x34, 0x12]);
  return CIP.MessageRouter.build(0x4b, path, Buffer.concat([requestor, Buffer.from(pccc)]));
}

async function main() {
  const identity = Browser.prototype._parseListIdentityResponse.call({}, await udpListIdentity());
  check('UDP ListIdentity vendor (1 = Rockwell Automation)', identity.vendorID, 1);
  check('UDP ListIdentity device type (14 = PLC)', identity.deviceType, 14);
  check('UDP ListIdentity product name', identity.productName.startsWith('1747-L552'), true);
  check('UDP ListIdentity port', identity.socketAddress.sin_port, port);

  const c = tcpClient();
  await c.ready;
  const tcpIdentity = Browser.prototype._parseListIdentityResponse.call(
    {}, await c.request(encapsulation.header.build(encapsulation.commands.ListIdentity)));
  check('TCP ListIdentity serial matches UDP', tcpIdentity.serialNumber, identity.serialNumber);

  const reg = encapsulation.header.parse(await c.request(encapsulation.registerSession()));
  check('RegisterSession status', reg.statusCode, 0);
  const session = reg.session;

  const send = async (pccc) => {
    const reply = encapsulation.header.parse(await c.request(encapsulation.sendRRData(session, executePccc(pccc), 10)));
    const cpf = encapsulation.CPF.parse(reply.data.subarray(6));
    const mr = CIP.MessageRouter.parse(cpf[1].data);
    return { status: reply.statusCode, service: mr.service, general: mr.generalStatusCode, pccc: mr.data.subarray(7) };
  };
  // N7:5 = 4321 (10E1h) with FNC AA, then read back with FNC A2 (1770-6.5.16 chapter 7).
  let r = await send([0x0f, 0x00, 0x01, 0x00, 0xaa, 0x02, 0x07, 0x89, 0x05, 0x00, 0xe1, 0x10]);
  check('write reply: encapsulation status, CIP reply service, general status', [r.status, r.service, r.general], [0, 0xcb, 0]);
  check('write reply PCCC (CMD 4Fh, STS 0, TNS 1)', [...r.pccc], [0x4f, 0x00, 0x01, 0x00]);
  r = await send([0x0f, 0x00, 0x02, 0x00, 0xa2, 0x02, 0x07, 0x89, 0x05, 0x00]);
  check('read N7:5 back', r.pccc.readUInt16LE(4), 4321);
  // A type mismatch (N7 read as a float file): STS F0h, EXT STS 11h.
  r = await send([0x0f, 0x00, 0x03, 0x00, 0xa2, 0x04, 0x07, 0x8a, 0x00, 0x00]);
  check('N7 read as F: STS F0h EXT STS 11h', [...r.pccc], [0x4f, 0xf0, 0x03, 0x00, 0x11]);

  c.request(encapsulation.unregisterSession(session));
  await c.closed;
  check('UnRegisterSession closes the connection', true, true);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

setTimeout(() => { console.log('FAIL timed out'); process.exit(1); }, 20000).unref();
main().catch((e) => { console.log(`FAIL ${e.stack || e}`); process.exit(1); });
