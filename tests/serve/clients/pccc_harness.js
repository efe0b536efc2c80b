// What the nodepccc client scripts share: connecting, reading and writing as promises, and the
// ok/FAIL lines with a summary and exit status that run_client.sh reports.
'use strict';
const NodePCCC = require('nodepccc');

function createHarness() {
  const conn = new NodePCCC({ silent: true });
  let passed = 0, failed = 0;
  const h = {
    conn,
    check(what, actual, expected) {
      const ok = typeof expected === 'function' ? expected(actual) : JSON.stringify(actual) === JSON.stringify(expected);
      if (ok) { passed++; console.log(`ok   ${what}: ${JSON.stringify(actual)}`); }
      else { failed++; console.log(`FAIL ${what}: got ${JSON.stringify(actual)}, expected ${typeof expected === 'function' ? expected.toString() : JSON.stringify(expected)}`); }
    },
    sleep: (ms) => new Promise((r) => setTimeout(r, ms)),
    connect(port) {
      return new Promise((resolve, reject) =>
        conn.initiateConnection({ port, host: '127.0.0.1' }, (err) => (err ? reject(err) : resolve())))
        .then(() => conn.setTranslationCB((t) => t));
    },
    read(items) {
      return new Promise((resolve) => {
        conn.removeItems();
        conn.addItems(items);
        conn.readAllItems((bad, values) => resolve({ bad, values }));
      });
    },
    write(items, values) {
      return new Promise((resolve) => conn.writeItems(items, values, (bad, which) => resolve({ bad, which })));
    },
    async finish() {
      await new Promise((resolve) => conn.dropConnection(resolve));
      console.log(`${passed} passed, ${failed} failed`);
      process.exit(failed ? 1 : 0);
    },
    // Runs main with a 30 s limit; an exception is a failure.
    run(main) {
      setTimeout(() => { console.log('FAIL timed out'); process.exit(1); }, 30000).unref();
      main().catch((e) => { console.log(`FAIL ${e}`); process.exit(1); });
    },
  };
  return h;
}

module.exports = { createHarness };
