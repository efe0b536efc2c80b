// The online view's page (server/web.h has the protocol). One WebSocket to /ws: the server sends
// the program's outline ("program") once, then an "update" every period and after each request:
// the status, the ladder layout of the rungs in view (the JSON of tools/trace/ladder_layout.h),
// the data-table window and the trend values. The page sends requests: view, table, trend, set,
// force, mode, pause, resume, step, clear_fault.
//
// Virtualized ladder: the outline carries every rung's height in rows, so the scroll space is
// sized once and only the rungs in view (plus a margin) are asked for and kept in the DOM.
'use strict';

const CELL_W = 8, CELL_H = 16, MARGIN_RUNGS = 4, MAX_VIEW = 120, TREND_POINTS = 400;
const ON = '#0a0', OFF = '#222';
const $ = (id) => document.getElementById(id);

const state = {
  ws: null, program: null, file: 2, offsets: [], width: 78, view: null,
  rungs: new Map(),  // rung number -> svg element in the DOM
  table: '', trend: [], trendData: [], lastStatus: null, firstPaint: null,
};

function send(request) {
  if (state.ws && state.ws.readyState === WebSocket.OPEN) state.ws.send(JSON.stringify(request));
}

function esc(s) {
  return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
}

function showMessage(text) {
  const m = $('message');
  m.textContent = text;
  m.hidden = !text;
}

// ---- Ladder drawing (the SVG form of tools/trace/ladder_layout.cpp, one rung per <svg>) ----

function line(x1, y1, x2, y2, colour, width) {
  return `<line x1="${x1}" y1="${y1}" x2="${x2}" y2="${y2}" stroke="${colour}" stroke-width="${width}"/>`;
}

function rungSvg(r, width, fault) {
  const rows = r.top + r.height;
  const W = width * CELL_W, H = rows * CELL_H;
  const cx = (x) => x * CELL_W + CELL_W / 2, cy = (y) => y * CELL_H + CELL_H / 2;
  let o = '';
  for (const x of [5, width - 1]) o += line(cx(x), 0, cx(x), H, OFF, 2);
  o += `<text x="2" y="${r.rail * CELL_H + 12}">${String(r.number).padStart(4, '0')}</text>`;
  r.comment.forEach((c, i) => { o += `<text class="comment" x="${7 * CELL_W}" y="${i * CELL_H + 12}" fill="#555">${esc(c)}</text>`; });
  let energized = false;
  for (const w of r.wires) {
    const colour = w.powered ? ON : OFF, sw = w.powered ? 3 : 1.5;
    if (w.y0 === w.y1) {
      o += line(w.x0 * CELL_W, cy(w.y0), (w.x1 + 1) * CELL_W, cy(w.y0), colour, sw);
      if (w.x1 >= width - 2 && w.powered) energized = true;
    } else {
      o += line(cx(w.x0), cy(w.y0), cx(w.x0), cy(w.y1), colour, sw);
    }
  }
  for (const b of r.blocks) {
    const colour = b.true ? ON : OFF;
    const address = b.shape === 'box' ? '' : (b.above.length ? b.above[b.above.length - 1] : '');
    o += `<g class="instruction" data-mnemonic="${esc(b.mnemonic)}" data-index="${b.index}" data-address="${esc(address)}"` +
         ` data-true="${b.true ? 1 : 0}" data-powered="${b.powered ? 1 : 0}">`;
    if (b.shape === 'box') {
      const x0 = (b.x + 2) * CELL_W, x1 = (b.x + b.w - 2) * CELL_W;
      const y0 = b.y * CELL_H + CELL_H / 2, y1 = (b.y + b.h - 1) * CELL_H + CELL_H / 2;
      o += `<rect x="${x0}" y="${y0}" width="${x1 - x0}" height="${y1 - y0}" fill="${b.true ? '#dfd' : 'white'}" stroke="${colour}" stroke-width="1.5"/>`;
      b.rows.forEach(([label, text], i) => {
        const y = (b.y + 1 + i) * CELL_H + 12;
        o += `<text x="${x0 + 4}" y="${y}"${i === 0 ? ' font-weight="bold"' : ''}>${esc(label)}</text>`;
        if (text) o += `<text class="${text.endsWith('<') ? 'value' : 'operand'}" x="${x1 - 4}" y="${y}" text-anchor="end">${esc(text)}</text>`;
      });
      o += '</g>';
      continue;
    }
    b.above.forEach((t, i) => {
      o += `<text x="${b.x * CELL_W + (b.w * CELL_W) / 2}" y="${(b.y + i) * CELL_H + 12}" text-anchor="middle"${i + 1 === b.above.length ? ' font-weight="bold"' : ''}>${esc(t)}</text>`;
    });
    const gx = (b.index < 0 ? b.x : b.x + Math.floor((b.w - 3) / 2)) * CELL_W, ym = cy(b.rail), gw = b.glyph.length * CELL_W;
    o += `<rect x="${gx}" y="${ym - 7}" width="${gw}" height="14" fill="${b.true ? '#bfb' : 'white'}"/>`;
    if (b.index < 0) {  // the END rung's <END>
      o += `<text x="${gx + gw / 2}" y="${ym + 4}" text-anchor="middle">${esc(b.glyph)}</text>`;
    } else if (b.shape === 'contact') {
      o += line(gx + 4, ym - 7, gx + 4, ym + 7, colour, 2) + line(gx + gw - 4, ym - 7, gx + gw - 4, ym + 7, colour, 2);
      if (b.glyph === ']/[') o += line(gx + 6, ym + 6, gx + gw - 6, ym - 6, colour, 1.5);
      o += line(gx, ym, gx + 4, ym, b.powered ? ON : OFF, 1.5) + line(gx + gw - 4, ym, gx + gw, ym, b.powered && b.true ? ON : OFF, 1.5);
    } else {
      o += `<path d="M${gx + 6},${ym - 7} q-5,7 0,14 M${gx + gw - 6},${ym - 7} q5,7 0,14" fill="none" stroke="${colour}" stroke-width="2"/>`;
      o += line(gx, ym, gx + 3, ym, b.powered ? ON : OFF, 1.5) + line(gx + gw - 3, ym, gx + gw, ym, b.powered ? ON : OFF, 1.5);
      const letter = b.glyph.length === 3 ? b.glyph[1].trim() : '';
      if (letter) o += `<text x="${gx + gw / 2}" y="${ym + 4}" text-anchor="middle" fill="${colour}">${esc(letter)}</text>`;
    }
    o += '</g>';
  }
  const faulted = fault && fault.file === state.file && fault.rung === r.number;
  return { svg: o, W, H, energized, faulted };
}

// ---- Virtualized scrolling ----

function selectFile(number) {
  const f = state.program.files.find((x) => x.number === number);
  if (!f) return;
  state.file = number;
  state.width = f.width;
  state.offsets = [0];
  for (const h of f.heights) state.offsets.push(state.offsets[state.offsets.length - 1] + h * CELL_H);
  const space = $('ladder-space');
  space.style.height = `${state.offsets[state.offsets.length - 1]}px`;
  space.style.width = `${f.width * CELL_W}px`;
  for (const el of state.rungs.values()) el.remove();
  state.rungs.clear();
  state.view = null;
  document.querySelectorAll('#program-files li').forEach((li) => li.classList.toggle('selected', Number(li.dataset.file) === number));
  $('ladder').scrollTop = 0;
  requestView();
}

// The first rung whose bottom is below `y` (binary search over the rung offsets).
function rungAt(y) {
  let lo = 0, hi = state.offsets.length - 2;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (state.offsets[mid + 1] <= y) lo = mid + 1; else hi = mid;
  }
  return lo;
}

function requestView() {
  if (!state.program) return;
  const pane = $('ladder');
  const count = state.offsets.length - 1;
  const first = Math.max(0, rungAt(pane.scrollTop) - MARGIN_RUNGS);
  let last = Math.min(count - 1, rungAt(pane.scrollTop + pane.clientHeight) + MARGIN_RUNGS);
  last = Math.min(last, first + MAX_VIEW - 1);
  const v = state.view;
  if (v && v.file === state.file && v.first === first && v.last === last) return;
  state.view = { file: state.file, first, last };
  send({ op: 'view', file: state.file, first, last });
}

function scrollToRung(file, rung) {
  if (file !== state.file) selectFile(file);
  $('ladder').scrollTop = state.offsets[Math.min(rung, state.offsets.length - 2)] || 0;
  requestView();
}

function drawLadder(ladder, fault) {
  if (!ladder || !ladder.files.length || !state.view) return;
  const f = ladder.files[0];
  if (f.number !== state.file) return;
  const keep = new Set();
  for (const r of f.rungs) {
    if (r.number < state.view.first || r.number > state.view.last) continue;
    keep.add(r.number);
    let el = state.rungs.get(r.number);
    if (!el) {
      el = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
      el.setAttribute('class', 'rung');
      el.setAttribute('font-family', 'monospace');
      el.setAttribute('font-size', '12');
      $('ladder-space').appendChild(el);
      state.rungs.set(r.number, el);
    }
    const d = rungSvg(r, ladder.width, fault);
    el.setAttribute('width', d.W);
    el.setAttribute('height', d.H);
    el.style.top = `${state.offsets[r.number]}px`;
    el.dataset.file = f.number;
    el.dataset.rung = r.number;
    el.dataset.energized = d.energized ? '1' : '0';
    el.classList.toggle('faulted', Boolean(d.faulted));
    el.innerHTML = d.svg;
  }
  for (const [n, el] of state.rungs) {
    if (!keep.has(n)) { el.remove(); state.rungs.delete(n); }
  }
  if (state.firstPaint === null && keep.size) {
    state.firstPaint = performance.now();
    document.body.dataset.firstPaint = String(Math.round(state.firstPaint));
  }
}

// ---- Status, fault banner, forces ----

function drawStatus(s) {
  state.lastStatus = s;
  $('mode').textContent = s.mode + (s.paused ? ' (paused)' : '');
  $('mode').dataset.mode = s.mode;
  $('mode').dataset.paused = s.paused ? '1' : '0';
  $('clock').textContent = `t = ${(s.time / 1e9).toFixed(3)} s, ${s.scans} scans`;
  const banner = $('fault');
  banner.hidden = !s.fault;
  if (s.fault) {
    $('fault-code').textContent = `${s.fault.code}h`;
    $('fault-s6').textContent = `${s.s6}h`;
    $('fault-where').textContent = s.fault.file >= 0 ? `${s.fault.file} rung ${s.fault.rung}` : '(outside the program scan)';
    $('fault-where').dataset.file = s.fault.file;
    $('fault-where').dataset.rung = s.fault.rung;
    $('fault-message').textContent = s.fault.message;
  }
  const forces = $('forces');
  const items = Object.entries(s.forces).map(([a, on]) => `<li data-address="${esc(a)}" data-state="${on ? 'on' : 'off'}">${esc(a)} forced ${on ? 'ON' : 'OFF'}</li>`).join('');
  if (forces.innerHTML !== items) forces.innerHTML = items;
}

// ---- Data tables ----

const BIT_NAMES = {
  T: [[15, 'EN'], [14, 'TT'], [13, 'DN']],
  C: [[15, 'CU'], [14, 'CD'], [13, 'DN'], [12, 'OV'], [11, 'UN']],
  R: [[15, 'EN'], [14, 'EU'], [13, 'DN'], [12, 'EM'], [11, 'ER'], [10, 'UL'], [9, 'IN'], [8, 'FD']],
};

function signed(w) { return w >= 0x8000 ? w - 0x10000 : w; }

function ioWordName(kind, index) {
  let at = 0;
  for (const s of state.program.slots) {
    const n = kind === 'I' ? s.in : s.out;
    if (index < at + n) return `${kind}:${s.slot}.${index - at}`;
    at += n;
  }
  return `${kind}:?${index}`;
}

function drawTable(t) {
  const box = $('table');
  if (!t) { box.innerHTML = ''; return; }
  const d = state.program.data.find((x) => x.name === t.name);
  if (!d) return;
  $('table-title').textContent = `Data table ${t.name}${d.module ? ` (${d.module})` : ''}`;
  const forces = state.lastStatus ? state.lastStatus.forces : {};
  const wpe = d.words_per_element;
  let h = '<table>';
  const elementName = (e) => {
    if (d.type === 'M0' || d.type === 'M1') return `${t.name}.${e}`;
    if (d.type === 'I' || d.type === 'O') return ioWordName(d.type, e);
    if (d.type === 'S') return `S:${e}`;
    return `${t.name}:${e}`;
  };
  const bitRow = (name, word) => {
    let r = `<tr><th>${esc(name)}</th>`;
    for (let b = 15; b >= 0; b--) {
      const a = `${name}/${b}`, v = (word >> b) & 1;
      r += `<td class="bit${a in forces ? ' forced' : ''}" data-address="${esc(a)}" data-value="${v}" title="${esc(a)}">${v}</td>`;
    }
    return `${r}</tr>`;
  };
  const first = t.offset / wpe;
  for (let i = 0; i * wpe < t.words.length; i++) {
    const e = first + i, w = t.words.slice(i * wpe, i * wpe + wpe), name = elementName(e);
    if (d.type === 'B' || d.type === 'I' || d.type === 'O') {
      h += bitRow(d.type === 'B' ? `${t.name}:${e}` : name, w[0]);
    } else if (BIT_NAMES[d.type]) {
      const bits = BIT_NAMES[d.type].map(([b, n]) => `<td class="bit" data-address="${esc(name)}/${n}" data-value="${(w[0] >> b) & 1}">${n}</td>`).join('');
      const [p, a] = d.type === 'R' ? ['LEN', 'POS'] : ['PRE', 'ACC'];
      h += `<tr><th>${esc(name)}</th>${bits}<td class="value" data-address="${esc(name)}.${p}">${p} ${signed(w[1])}</td>` +
           `<td class="value" data-address="${esc(name)}.${a}">${a} ${signed(w[2])}</td></tr>`;
    } else if (d.type === 'F' || d.type === 'L') {
      const v = t.values ? t.values[i] : '?';
      h += `<tr><th>${esc(name)}</th><td class="value" data-address="${esc(name)}">${esc(v)}</td></tr>`;
    } else if (d.type === 'ST' || d.type === 'A') {
      const chars = (d.type === 'ST' ? w.slice(1, 1 + Math.ceil(w[0] / 2)) : w).map((x) => String.fromCharCode(x >> 8, x & 255)).join('');
      const text = d.type === 'ST' ? chars.slice(0, w[0]) : chars;
      h += `<tr><th>${esc(name)}</th><td style="text-align:left">${esc(JSON.stringify(text))}</td></tr>`;
    } else {
      h += `<tr><th>${esc(name)}</th><td class="value" data-address="${esc(name)}">${signed(w[0])}</td><td>${w[0].toString(16).toUpperCase().padStart(4, '0')}h</td></tr>`;
    }
  }
  if (t.error) h += `<tr><td colspan="17">${esc(t.error)}</td></tr>`;
  h += '</table>';
  if (box.innerHTML !== h) box.innerHTML = h;
  box.dataset.name = t.name;
}

function selectTable(name) {
  state.table = name;
  document.querySelectorAll('#data-files li').forEach((li) => li.classList.toggle('selected', li.dataset.name === name));
  send({ op: 'table', name, offset: 0 });
}

// ---- Trend ----

const TREND_COLOURS = ['#0a0', '#06c', '#c60', '#a0a', '#c00', '#088', '#660', '#333'];

function drawTrend(values, time) {
  if (!state.trend.length) return;
  state.trendData.push([time, values]);
  if (state.trendData.length > TREND_POINTS) state.trendData.shift();
  const t0 = state.trendData[0][0], t1 = Math.max(time, t0 + 1);
  let lo = Infinity, hi = -Infinity;
  for (const [, vs] of state.trendData) for (const v of vs) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (lo === hi) { lo -= 1; hi += 1; }
  const X = (t) => 4 + ((t - t0) / (t1 - t0)) * 332, Y = (v) => 150 - ((v - lo) / (hi - lo)) * 140;
  let o = '';
  state.trend.forEach((a, i) => {
    const pts = state.trendData.filter(([, vs]) => vs[i] !== null && vs[i] !== undefined).map(([t, vs]) => `${X(t).toFixed(1)},${Y(vs[i]).toFixed(1)}`);
    o += `<polyline data-address="${esc(a)}" points="${pts.join(' ')}" fill="none" stroke="${TREND_COLOURS[i]}" stroke-width="1.5"/>`;
  });
  o += `<text x="4" y="12" font-size="10">${hi}</text><text x="4" y="158" font-size="10">${lo}</text>`;
  $('trend').innerHTML = o;
  const last = state.trendData[state.trendData.length - 1][1];
  $('trend-legend').innerHTML = state.trend.map((a, i) => `<li style="color:${TREND_COLOURS[i]}" data-address="${esc(a)}" data-value="${last[i]}">${esc(a)} = ${last[i]}</li>`).join('');
}

// ---- Messages from the server ----

function onProgram(p) {
  state.program = p;
  p.slots.sort((a, b) => a.slot - b.slot);
  $('title').textContent = p.project || 'softslc';
  $('processor').textContent = `${p.processor} (${p.catalog})${p.read_only ? ', read-only' : ''}`;
  $('program-files').innerHTML = p.files.map((f) => `<li data-file="${f.number}">LAD ${f.number} - ${esc(f.name)} (${f.heights.length - 1})</li>`).join('');
  $('data-files').innerHTML = p.data.map((d) => `<li data-name="${esc(d.name)}">${esc(d.name)}${d.module ? ` ${esc(d.module)}` : ''}</li>`).join('');
  // The chassis: each slot's module; a specialty module's M files open from its line.
  $('chassis').innerHTML = p.slots.map((s) => {
    const m = p.data.find((d) => d.type === 'M1' && d.number === s.slot) || p.data.find((d) => d.type === 'M0' && d.number === s.slot);
    return `<li data-slot="${s.slot}"${m ? ` data-name="${esc(m.name)}"` : ''}>${s.slot}: ${esc(s.catalog)}</li>`;
  }).join('');
  selectFile(p.files.some((f) => f.number === 2) ? 2 : p.files[0].number);
  if (state.table) selectTable(state.table);
  if (state.trend.length) send({ op: 'trend', addresses: state.trend });
}

function onUpdate(u) {
  const t0 = performance.now();
  drawStatus(u.status);
  drawLadder(u.ladder, u.status.fault);
  drawTable(u.table);
  drawTrend(u.trend, u.status.time);
  // For the scale test (docs/performance.md): updates seen and the last one's handling time.
  document.body.dataset.updates = String(Number(document.body.dataset.updates || 0) + 1);
  document.body.dataset.updateMs = (performance.now() - t0).toFixed(2);
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/ws`);
  state.ws = ws;
  ws.onopen = () => { $('connection').textContent = 'online'; $('connection').dataset.state = 'open'; };
  ws.onclose = () => {
    $('connection').textContent = 'offline'; $('connection').dataset.state = 'closed';
    setTimeout(connect, 2000);
  };
  ws.onmessage = (ev) => {
    const m = JSON.parse(ev.data);
    if (m.type === 'program') onProgram(m);
    else if (m.type === 'update') onUpdate(m);
    else if (m.type === 'error') showMessage(m.message);
  };
}

// ---- Controls ----

function wire() {
  for (const id of ['btn-run', 'btn-program', 'btn-test']) $(id).onclick = () => send({ op: 'mode', mode: $(id).dataset.mode });
  $('btn-pause').onclick = () => send({ op: 'pause' });
  $('btn-resume').onclick = () => send({ op: 'resume' });
  $('btn-step').onclick = () => send({ op: 'step', scans: 1 });
  $('btn-clear-fault').onclick = () => send({ op: 'clear_fault' });
  $('fault-where').onclick = (e) => { e.preventDefault(); scrollToRung(Number(e.target.dataset.file), Number(e.target.dataset.rung)); };
  $('write-form').onsubmit = (e) => {
    e.preventDefault();
    showMessage('');
    send({ op: 'set', address: $('write-address').value.trim(), value: $('write-value').value.trim() });
  };
  for (const id of ['btn-force-on', 'btn-force-off', 'btn-force-remove'])
    $(id).onclick = () => { showMessage(''); send({ op: 'force', address: $('force-address').value.trim(), state: $(id).dataset.state }); };
  $('trend-form').onsubmit = (e) => {
    e.preventDefault();
    const a = $('trend-address').value.trim();
    if (!a || state.trend.includes(a) || state.trend.length >= 8) return;
    state.trend.push(a);
    state.trendData = [];
    send({ op: 'trend', addresses: state.trend });
  };
  $('btn-trend-clear').onclick = () => { state.trend = []; state.trendData = []; $('trend').innerHTML = ''; $('trend-legend').innerHTML = ''; send({ op: 'trend', addresses: [] }); };
  $('program-files').onclick = (e) => { const li = e.target.closest('li'); if (li) selectFile(Number(li.dataset.file)); };
  $('data-files').onclick = (e) => { const li = e.target.closest('li'); if (li) selectTable(li.dataset.name); };
  $('chassis').onclick = (e) => { const li = e.target.closest('li'); if (li && li.dataset.name) selectTable(li.dataset.name); };
  // Clicking an operand or a table cell names it in the write and force forms.
  const pick = (address, value) => {
    if (!address) return;
    $('write-address').value = address;
    $('force-address').value = address;
    if (value !== undefined) $('write-value').value = value;
  };
  $('ladder').addEventListener('click', (e) => { const g = e.target.closest('g.instruction'); if (g) pick(g.dataset.address); });
  $('table').addEventListener('click', (e) => {
    const td = e.target.closest('td[data-address]');
    if (!td) return;
    // A bit cell toggles the bit (an I bit: the field input, as `run --set` does).
    if (td.classList.contains('bit')) send({ op: 'set', address: td.dataset.address, value: td.dataset.value === '1' ? '0' : '1' });
    pick(td.dataset.address);
  });
  let pending = false;
  $('ladder').addEventListener('scroll', () => {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; requestView(); });
  });
  window.addEventListener('resize', () => requestView());
}

window.softslcView = state;  // for tests and the browser console
wire();
connect();
