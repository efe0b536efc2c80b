// Shared by the browser scenarios: launches Debian's chromium through playwright-core, opens the
// online view and offers the page's own controls (the forms a user types into), so a scenario
// reads as the steps a user takes. Every wait is bounded; a failed check throws with what the
// page showed.
'use strict';
const { chromium } = require('playwright-core');

async function open(url) {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM,
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'],
  });
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('pageerror', (e) => { console.error('page error:', e.message); process.exitCode = 1; });
  await page.goto(url);
  await page.waitForSelector('#connection[data-state="open"]', { timeout: 10000 });
  return { browser, page };
}

// Waits until `fn` (run in the page) returns true; fails with `what` after `ms`.
async function until(page, what, fn, arg, ms = 5000) {
  try {
    await page.waitForFunction(fn, arg, { timeout: ms, polling: 50 });
  } catch (e) {
    throw new Error(`timed out waiting for ${what}`);
  }
}

function check(ok, what) {
  if (!ok) throw new Error(`check failed: ${what}`);
  console.log(`ok: ${what}`);
}

async function write(page, address, value) {
  await page.fill('#write-address', address);
  await page.fill('#write-value', String(value));
  await page.click('#btn-write');
}

async function force(page, address, state) {
  await page.fill('#force-address', address);
  await page.click(`#force-form button[data-state="${state}"]`);
}

// The truth the page shows for instruction `index` of rung `rung` ("1", "0" or null if absent).
async function truth(page, rung, index) {
  return page.evaluate(([r, i]) => {
    const g = document.querySelector(`svg.rung[data-rung="${r}"] g.instruction[data-index="${i}"]`);
    return g ? g.dataset.true : null;
  }, [rung, index]);
}

async function scans(page) {
  return page.evaluate(() => Number(/([0-9]+) scans/.exec(document.getElementById('clock').textContent)[1]));
}

async function run(main) {
  const [url, outdir] = process.argv.slice(2);
  let browser;
  try {
    const opened = await open(url);
    browser = opened.browser;
    await main(opened.page, outdir);
  } catch (e) {
    console.error(e.message);
    process.exitCode = 1;
  } finally {
    if (browser) await browser.close();
  }
}

module.exports = { until, check, write, force, truth, scans, run };
