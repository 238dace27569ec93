// The moorsim monitor's display: the state the monitor sends (server-sent events from
// /api/events), drawn as a plan view and tables; Acknowledge posts to /api/ack/<number>.
'use strict';

const svgNs = 'http://www.w3.org/2000/svg';

function el(name, attributes, text) {
  const e = document.createElementNS(svgNs, name);
  for (const [k, v] of Object.entries(attributes || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function cell(row, text, className) {
  const td = document.createElement('td');
  td.textContent = text;
  if (className) td.className = className;
  row.appendChild(td);
  return td;
}

function utc(unix) {
  return new Date(unix * 1000).toISOString().replace('T', ' ').slice(0, 19);
}

function age(now, last) {
  if (!last) return 'never';
  const s = Math.max(0, now - last);
  return s < 100 ? s.toFixed(1) + ' s' : Math.round(s) + ' s';
}

function kilonewtons(n) {
  return n === null || n === undefined ? '-' : (n / 1000).toFixed(0) + ' kN';
}

// A point of the body frame (x forward, y starboard) at the vessel's pose, in north, east.
function onVessel(pose, x, y) {
  const c = Math.cos(pose.heading), s = Math.sin(pose.heading);
  return [pose.north + c * x - s * y, pose.east + s * x + c * y];
}

// North up, east right: svg x = east, svg y = -north.
function xy(p) {
  return p[1].toFixed(2) + ',' + (-p[0]).toFixed(2);
}

// The lines, the vessel and its track in `svg`, `extent` metres around `centre`.
function drawView(svg, state, centre, extent, labels) {
  svg.replaceChildren();
  svg.setAttribute('viewBox',
                   `${centre[1] - extent} ${-centre[0] - extent} ${2 * extent} ${2 * extent}`);
  const scale = extent / 300;  // marks and text keep their size on screen
  const pose = state.vessel;
  const known = pose.north !== null && pose.east !== null && pose.heading !== null;
  if (state.watch_circle) {
    svg.appendChild(el('circle', {class: 'circle', cx: 0, cy: 0, r: state.watch_circle}));
  }
  for (const line of state.lines) {
    const end = known ? onVessel(pose, line.fairlead_body[0], line.fairlead_body[1]) : [0, 0];
    svg.appendChild(el('line', {
      class: 'line ' + line.state, 'data-line': line.line,
      x1: line.anchor[1], y1: -line.anchor[0], x2: end[1], y2: -end[0]}));
    if (!labels) continue;
    const size = 10 * scale;
    svg.appendChild(el('rect', {class: 'anchor', x: line.anchor[1] - size / 2,
                                y: -line.anchor[0] - size / 2, width: size, height: size}));
    svg.appendChild(el('text', {class: 'label', x: line.anchor[1] + size,
                                y: -line.anchor[0] - size, 'font-size': 16 * scale},
                       String(line.line)));
  }
  if (state.track.length > 1) {
    svg.appendChild(el('polyline', {class: 'track', points: state.track.map(xy).join(' ')}));
  }
  if (known) {
    const half = state.hull.length / 2, beam = state.hull.beam / 2;
    const hull = [[half, 0], [half - beam, beam], [-half, beam], [-half, -beam],
                  [half - beam, -beam]].map((p) => onVessel(pose, p[0], p[1]));
    svg.appendChild(el('polygon', {class: 'hull', points: hull.map(xy).join(' ')}));
    const turret = onVessel(pose, state.turret[0], state.turret[1]);
    svg.appendChild(el('circle', {class: 'turret', cx: turret[1], cy: -turret[0],
                                  r: Math.max(3 * scale, 2)}));
  }
}

function drawPlan(state) {
  const pose = state.vessel;
  const known = pose.north !== null && pose.east !== null;
  let extent = 50;
  for (const l of state.lines) extent = Math.max(extent, Math.abs(l.anchor[0]), Math.abs(l.anchor[1]));
  drawView(document.getElementById('plan'), state, [0, 0], 1.1 * extent, true);
  // Close up: the watch circle, or the hull and its excursion.
  let near = Math.max(state.watch_circle || 0, state.hull.length * 0.75);
  if (known) near = Math.max(near, 1.2 * Math.hypot(pose.north, pose.east) + state.hull.length / 2);
  drawView(document.getElementById('watch'), state, [0, 0], near, false);
  document.getElementById('watch-scale').textContent = Math.round(2 * near) + ' m across';
}

function drawAlarms(state) {
  const body = document.querySelector('#alarms tbody');
  body.replaceChildren();
  for (const a of state.alarms) {
    const row = document.createElement('tr');
    row.className = (a.active ? 'active' : 'rectified') + (a.acknowledged ? '' : ' unacknowledged');
    row.dataset.alarm = a.number;
    cell(row, String(a.number).padStart(3, '0'), 'number');
    cell(row, a.text);
    cell(row, utc(a.raised));
    cell(row, (a.active ? 'active' : 'rectified') + (a.acknowledged ? ', acknowledged' : ''));
    const action = cell(row, '');
    if (!a.acknowledged) {
      const button = document.createElement('button');
      button.textContent = 'Acknowledge';
      button.addEventListener('click', () => {
        fetch('/api/ack/' + a.number,
              {method: 'POST', headers: {'X-Moorsim-Acknowledge': 'yes'}});
      });
      action.appendChild(button);
    }
    body.appendChild(row);
  }
  if (state.alarms.length === 0) {
    const row = document.createElement('tr');
    cell(row, '');
    cell(row, 'No alarm');
    body.appendChild(row);
  }
}

function drawCells(state) {
  const box = document.getElementById('cells');
  box.replaceChildren();
  const cells = state.lines.filter((l) => l.measured !== null || l.expected !== null);
  if (cells.length === 0) {
    box.textContent = 'No load cells fitted.';
    return;
  }
  let top = 1;
  for (const l of cells) top = Math.max(top, l.measured || 0, (l.expected || 0) + (l.band || 0));
  top *= 1.15;
  for (const l of cells) {
    const row = document.createElement('div');
    const out = l.measured !== null && l.expected !== null &&
                Math.abs(l.measured - l.expected) > l.band;
    row.className = 'cell' + (out ? ' out' : '');
    row.dataset.line = l.line;
    const name = document.createElement('span');
    name.textContent = 'Line ' + l.line;
    const bar = document.createElement('div');
    bar.className = 'bar';
    if (l.expected !== null) {
      const band = document.createElement('div');
      band.className = 'band';
      band.style.left = (100 * Math.max(0, l.expected - l.band) / top) + '%';
      band.style.width = (100 * 2 * l.band / top) + '%';
      bar.appendChild(band);
    }
    if (l.measured !== null) {
      const reading = document.createElement('div');
      reading.className = 'reading';
      reading.style.left = (100 * Math.max(0, l.measured) / top) + '%';
      bar.appendChild(reading);
    }
    const value = document.createElement('span');
    value.className = 'value';
    value.textContent = kilonewtons(l.measured) + ' / ' + kilonewtons(l.expected);
    row.append(name, bar, value);
    box.appendChild(row);
  }
}

function drawDetectors(state) {
  const body = document.querySelector('#detectors tbody');
  body.replaceChildren();
  for (const d of state.detectors) {
    const row = document.createElement('tr');
    if (d.alarm) row.className = 'active';
    cell(row, d.label);
    cell(row, d.type);
    cell(row, d.alarm ? 'ALARM' : 'watching');
    cell(row, d.hypothesis);
    cell(row, d.score === null ? '-' : Number(d.score).toPrecision(4), 'number');
    body.appendChild(row);
  }
}

function drawFeeds(state) {
  const feeds = document.querySelector('#feeds tbody');
  feeds.replaceChildren();
  for (const f of state.feeds) {
    const row = document.createElement('tr');
    if (!f.connected) row.className = 'stale';
    cell(row, f.name + ' (' + f.kind + ' ' + f.endpoint + ')');
    cell(row, f.connected ? 'up' : 'down' + (f.problem ? ': ' + f.problem : ''));
    cell(row, String(f.lines), 'number');
    cell(row, String(f.faults), 'number');
    cell(row, age(state.wall, f.last_line));
    feeds.appendChild(row);
  }
  const channels = document.querySelector('#channels tbody');
  channels.replaceChildren();
  for (const c of state.channels) {
    const row = document.createElement('tr');
    if (c.stale) row.className = 'stale';
    row.dataset.channel = c.name;
    cell(row, c.name + (c.stale ? ' (stale)' : '') + (c.detail ? ': ' + c.detail : ''));
    cell(row, c.feed || '-');
    cell(row, String(c.readings), 'number');
    cell(row, String(c.rejected), 'number');
    cell(row, age(state.now, c.last));
    channels.appendChild(row);
  }
}

function draw(state) {
  document.getElementById('vessel').textContent = state.scenario;
  document.getElementById('clock').textContent = utc(state.now) + ' UTC';
  const status = document.getElementById('status');
  const active = state.alarms.some((a) => a.active);
  status.textContent = !state.detecting ? 'detection not running' : active ? 'ALARM' : 'watching';
  status.className = 'status ' + (!state.detecting ? 'stale' : active ? 'alarm' : 'ok');
  drawPlan(state);
  drawAlarms(state);
  drawCells(state);
  drawDetectors(state);
  drawFeeds(state);
  document.body.dataset.updated = String(state.now);
}

function connect() {
  const events = new EventSource('/api/events');
  events.onmessage = (message) => draw(JSON.parse(message.data));
  events.onerror = () => {
    const status = document.getElementById('status');
    status.textContent = 'no connection to the monitor';
    status.className = 'status stale';
  };
}

connect();
