// The monitor's display in a real headless browser (Debian's chromium, driven by
// playwright-core; nothing is downloaded). A monitor watches the seed FPSO with load cells
// on a UDP feed; `moorsim stream` plays the thesis case in which line 6 parts at 400 s, 20
// times faster than real time. Checked: the page loads from the monitor in at most 2 s at
// 1280x800; the alarm for line 6 appears on it within 1 s of the monitor raising it, with
// line 6 drawn parted; Acknowledge acknowledges it in the monitor (its alarm line says so,
// by the display); when the ship falls silent the position channel is shown stale.
//
//   node tests/display/display_test.mjs MOORSIM SOURCE_DIR [SCREENSHOT.png]
import { spawn } from 'node:child_process';
import dgram from 'node:dgram';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [moorsim, source, screenshot] = process.argv.slice(2);
if (!moorsim || !source) {
  console.error('usage: display_test.mjs MOORSIM SOURCE_DIR [SCREENSHOT.png]');
  process.exit(2);
}
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'moorsim_display_'));
const children = [];
let browser = null;
let failures = 0;

function check(condition, what) {
  console.log((condition ? 'ok   ' : 'FAIL ') + what);
  if (!condition) failures += 1;
}

async function cleanUp() {
  if (browser) await browser.close().catch(() => {});
  for (const child of children) {
    if (child.exitCode === null) child.kill('SIGKILL');
  }
  fs.rmSync(work, { recursive: true, force: true });
}

// Everything is bounded: a hang fails the test instead of holding CI.
const deadline = setTimeout(async () => {
  console.error('FAIL the display test did not finish in 180 s');
  await cleanUp();
  process.exit(1);
}, 180000);

function freePort(kind) {
  return new Promise((resolve) => {
    if (kind === 'udp') {
      const socket = dgram.createSocket('udp4');
      socket.bind(0, '127.0.0.1', () => {
        const { port } = socket.address();
        socket.close(() => resolve(port));
      });
    } else {
      const server = net.createServer();
      server.listen(0, '127.0.0.1', () => {
        const { port } = server.address();
        server.close(() => resolve(port));
      });
    }
  });
}

function start(args, name) {
  const child = spawn(moorsim, args, { cwd: work, stdio: ['ignore', 'pipe', 'pipe'] });
  child.output = '';
  child.stdout.on('data', (d) => { child.output += d; });
  child.stderr.on('data', (d) => { child.output += d; });
  child.name = name;
  children.push(child);
  return child;
}

async function until(what, test, seconds) {
  const end = Date.now() + seconds * 1000;
  while (Date.now() < end) {
    const value = test();
    if (value) return value;
    await new Promise((r) => setTimeout(r, 20));
  }
  throw new Error(`${what}: not within ${seconds} s`);
}

function alarmLines() {
  const file = path.join(work, 'alarms.jsonl');
  if (!fs.existsSync(file)) return [];
  return fs.readFileSync(file, 'utf8').split('\n').filter((l) => l).map((l) => JSON.parse(l))
    .filter((j) => j.alarm !== undefined);
}

try {
  const library = path.join(source, 'scenarios', 'library');
  const cells = 'sensors:\n  tension_cells: {rate_hz: 1, noise: {std_dev: 1.0e4}}\n';
  fs.writeFileSync(path.join(work, 'seed_fpso.yaml'),
                   `base: ${path.join(library, 'thesis_no_failure.yaml')}\n${cells}`);
  fs.writeFileSync(path.join(work, 'trial.yaml'),
                   `base: ${path.join(library, 'thesis_line6.yaml')}\n${cells}`);
  const feed = await freePort('udp');
  const port = await freePort('tcp');
  const transducers = [1, 2, 3, 4, 5, 6, 7, 8]
    .map((k) => `  - {transducer: LC${k}, line: ${k}}`).join('\n');
  fs.writeFileSync(path.join(work, 'monitor.yaml'), `scenario: seed_fpso.yaml
origin: {latitude_deg: 61.25, longitude_deg: 1.75}
antenna: [40, -5, -30]
feeds:
  - {name: ship, udp: {address: 127.0.0.1, port: ${feed}}, timing: tags}
cells:
${transducers}
thrust: {feed: ship, transducers: [TX, TY, TN]}
stale_after: 3
store: store
alarms: alarms.jsonl
display: {address: 127.0.0.1, port: ${port}, watch_circle: 30}
`);
  const monitor = start(['monitor', 'monitor.yaml'], 'monitor');
  await until('the monitor serving its display', () => monitor.output.includes('display: http'), 60);
  const url = `http://127.0.0.1:${port}/`;

  browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
           '--disable-component-update', '--disable-default-apps', '--disable-sync',
           '--no-first-run', '--disable-breakpad'],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const requests = [];
  page.on('request', (r) => requests.push(r.url()));
  const loading = Date.now();
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => document.body.dataset.updated !== undefined, null,
                             { timeout: 5000 });
  const loaded = (Date.now() - loading) / 1000;
  check(loaded <= 2.0, `the page loads and shows the monitor's state in ${loaded.toFixed(2)} s (at most 2 s)`);
  check(requests.every((r) => r.startsWith(url)),
        'every file the page asks for comes from the monitor (' + requests.length + ' requests)');

  const stream = start(['stream', 'trial.yaml', '--to', 'monitor.yaml', '--speed', '20', '--set',
                        'simulation.duration=560'], 'stream');
  const raised = await until('the monitor raising the line 6 alarm', () => {
    const line = alarmLines().find((j) => j.alarm === 6 && j.state === 'raised');
    return line ? Date.now() : 0;
  }, 90);
  await page.waitForSelector('#alarms tr[data-alarm="6"]', { timeout: 5000 });
  const shown = (Date.now() - raised) / 1000;
  check(shown <= 1.0, `the alarm is on the page ${shown.toFixed(2)} s after the monitor raised it (at most 1 s)`);
  check(await page.locator('#plan line[data-line="6"].parted').count() === 1,
        'line 6 is drawn parted in the plan view');
  check(await page.locator('#plan line.intact').count() === 7, 'the other seven lines are drawn intact');
  check(await page.locator('#cells .cell').count() === 8, 'the eight load cells are shown');
  if (screenshot) await page.screenshot({ path: screenshot });

  const forged = await fetch(url + 'api/ack/6', { method: 'POST' });
  check(forged.status === 403,
        `an acknowledgement without the page's header is refused (${forged.status})`);
  await page.locator('#alarms tr[data-alarm="6"] button').click();
  await until('the acknowledgement reaching the monitor', () => alarmLines().find(
    (j) => j.alarm === 6 && j.state === 'acknowledged' && j.by === 'display'), 5);
  check(true, 'Acknowledge acknowledges the alarm in the monitor (by the display)');
  await page.waitForFunction(() => {
    const row = document.querySelector('#alarms tr[data-alarm="6"]');
    return row === null || !row.classList.contains('unacknowledged');
  }, null, { timeout: 5000 });
  check(true, 'the page shows it acknowledged');

  stream.kill('SIGTERM');
  await page.waitForSelector('#channels tr[data-channel="position"].stale', { timeout: 15000 });
  check(true, 'the position channel is shown stale when the ship falls silent');
  await page.waitForSelector('#alarms tr[data-alarm="100"]', { timeout: 5000 });
  check(true, 'and its stale alarm is listed');

  monitor.kill('SIGTERM');
  const code = await new Promise((r) => monitor.on('exit', (c, s) => r(c ?? s)));
  check(code === 143, `the monitor stops on SIGTERM (exit ${code})`);
} catch (error) {
  failures += 1;
  console.error('FAIL ' + error.message);
  for (const child of children) console.error(`--- ${child.name} ---\n${child.output}`);
}
clearTimeout(deadline);
await cleanUp();
process.exit(failures === 0 ? 0 : 1);
