// End-to-end test of the plan and structure corrections of `castellan serve` (issue 22) in
// Debian's Chromium (headless, via playwright-core), on the demo project: a region relabelled,
// a tower removed and the removal undone, a tower added by dragging its radius, the scale set by
// two clicks, a structure made the keep with its height and roof, two regions merged, the plan
// settings saved; each checked on the page and in what the server saved, and the corrections
// shown again after a reload.
// Run by crates/castellan/tests/serve_plan_fix_e2e.rs, which starts the server and passes
//   CASTELLAN_URL, SCREENSHOTS, CHROMIUM (as serve.e2e.mjs). Prints one JSON line of figures last.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import path from 'node:path';

const url = process.env.CASTELLAN_URL;
const shots = process.env.SCREENSHOTS;
fs.mkdirSync(shots, { recursive: true });
const userDataDir = fs.mkdtempSync(path.join(process.env.TMPDIR || '/tmp', 'castellan-chromium-'));

function check(ok, message) {
  if (!ok) throw new Error(message);
}

// Demo plan points (examples/demo/plan.png, 640 × 480): the ward, a tower, the keep.
const WARD = [320, 380];
const TOWER = [530, 100];
const KEEP = [320, 270];

const browser = await chromium.launchPersistentContext(userDataDir, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1400, height: 1000 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--no-first-run', '--disable-sync',
    '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
const figures = {};
try {
  const page = browser.pages()[0] || await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('dialog', (d) => d.accept('20'));
  page.setDefaultTimeout(60_000);
  await page.goto(url);
  await page.waitForSelector('body[data-ready=true]');
  const token = new URL(url).searchParams.get('token');
  const apiGet = (u) => page.evaluate(([u, t]) => fetch(u, { headers: { 'x-castellan-token': t } }).then((r) => r.json()), [u, token]);
  const at = async ([x, y]) => {
    const el = page.locator('#planfix-canvas');
    await el.scrollIntoViewIfNeeded();
    const b = await el.boundingBox();
    const [w, h] = await el.evaluate((e) => [e.width, e.height]);
    return [b.x + (x * b.width) / w, b.y + (y * b.height) / h];
  };
  const click = async (pt) => { const [x, y] = await at(pt); await page.mouse.click(x, y); };
  const count = async () => Number(await page.getAttribute('#planfix-info', 'data-count'));
  const towers = async () => Number(await page.getAttribute('#planfix-info', 'data-towers'));
  // Waits for the answer of a correction: the count of corrections becomes n.
  const saved = async (n) => {
    try {
      await page.waitForSelector(`#planfix-info[data-count="${n}"]`, { timeout: 30_000 });
    } catch (e) {
      throw new Error(`no correction saved (${n} expected); the page says: ${await page.textContent('#status')}`);
    }
  };
  const roundTrips = [];
  const roundTrip = async () => roundTrips.push(Number(await page.getAttribute('#planfix-info', 'data-round-trip-ms')));

  await page.click('#plan-run');
  await page.waitForSelector('#planfix-canvas[data-loaded=true]');
  const parsedTowers = Number(await page.getAttribute('#plan-info', 'data-towers'));
  check(parsedTowers === 2, `the demo plan has 2 towers, the page says ${parsedTowers}`);
  check(/2 towers/.test(await page.textContent('#plan-info')), 'the plan step says how many towers it found');
  const legend = await page.$$eval('#label-legend li', (l) => l.length);
  check(legend === 11, `a legend of the eleven labels (${legend})`);

  // A region relabelled: the ward is a chapel.
  await page.check('input[name=fix][value=label]');
  await page.selectOption('#planfix-label', 'chapel');
  await click(WARD);
  await saved(1);
  await roundTrip();
  let c = await apiGet('/api/corrections');
  check(c.label.length === 1 && c.label[0].label === 'chapel', `saved label ${JSON.stringify(c.label)}`);
  let at_ward = await apiGet(`/api/plan/at?x=${WARD[0]}&y=${WARD[1]}`);
  check(at_ward.label === 'chapel', `the plan has ${at_ward.label} at the ward`);

  // A tower the parser found is no tower; then undone.
  await page.check('input[name=fix][value=notower]');
  await click(TOWER);
  await saved(2);
  await roundTrip();
  check(await towers() === 1, `one tower left (${await towers()})`);
  await page.click('#planfix-undo');
  await saved(1);
  check(await towers() === 2, 'undo brings the tower back');

  // A tower added by dragging its radius from its centre, in the ward (solid: no room there).
  await page.check('input[name=fix][value=tower]');
  const [cx, cy] = await at([200, 400]);
  const [ex, ey] = await at([220, 400]);
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  await page.mouse.move(ex, ey, { steps: 5 });
  await page.mouse.up();
  await saved(2);
  check(await towers() === 3, `a third tower (${await towers()})`);
  c = await apiGet('/api/corrections');
  check(c.tower[0].radius >= 18 && c.tower[0].radius <= 22, `its radius ${c.tower[0].radius}`);
  await page.locator('#plan').screenshot({ path: path.join(shots, 'plan-fix.png') });
  await page.click('#planfix-undo');
  await saved(1);

  // The scale from two clicks and a typed length (the dialog answers 20 m).
  await page.check('input[name=fix][value=scale]');
  await click([100, 460]);
  await click([300, 460]);
  await saved(2);
  c = await apiGet('/api/corrections');
  check(c.scale_line && c.scale_line.metres === 20, `scale line ${JSON.stringify(c.scale_line)}`);
  await page.click('#planfix-undo');
  await saved(1);

  // A model, then a structure made the keep, 40 m high under a pyramid.
  await page.click('#reconstruct');
  await page.waitForFunction(() => /structures/.test(document.getElementById('reconstruct-info').textContent));
  await page.check('input[name=fix][value=structure]');
  await click(TOWER);
  await page.waitForSelector('#structure-panel:not([hidden])');
  check(await page.getAttribute('#structure-panel', 'data-role') === 'tower', 'the panel shows the tower');
  await page.fill('#structure-height', '40');
  await page.selectOption('#structure-roof', 'pyramid');
  await page.check('#structure-keep');
  await page.click('#structure-save');
  await saved(2);
  await page.$eval('#reconstruct-info', (e) => { e.textContent = ''; });
  await page.click('#planfix-rebuild');
  await page.waitForFunction(() => /structures/.test(document.getElementById('reconstruct-info').textContent));
  const estimate = await apiGet('/files/out/estimate.json');
  const keeps = estimate.structures.filter((s) => s.role === 'keep');
  check(keeps.length === 1 && keeps[0].height === 40 && keeps[0].roof === 'pyramid', `the keep ${JSON.stringify(keeps.map((k) => [k.id, k.height, k.roof]))}`);
  check(keeps[0].provenance.height.image === 'user', 'its height is the user\'s');
  const tallest = estimate.structures.reduce((a, b) => (a.height >= b.height ? a : b));
  check(tallest.id === keeps[0].id, `the tallest is ${tallest.id}`);
  await page.locator('#plan').screenshot({ path: path.join(shots, 'plan-fix-structure.png') });

  // Two regions merged: the keep's room and the ward.
  const faces = (await apiGet('/api/corrections'), await page.textContent('#planfix-info'));
  await page.check('input[name=fix][value=merge]');
  await click(KEEP);
  await click(WARD);
  await saved(3);
  const merged = await page.textContent('#planfix-info');
  check(faces !== merged, `the regions changed: ${faces} → ${merged}`);
  await page.click('#planfix-undo');
  await saved(2);

  // Plan settings: a scale in metres per pixel, saved and parsed.
  await page.fill('#set-scale', '0.12');
  await page.click('#settings-save');
  await page.waitForFunction(() => /Parsing the plan: done/.test(document.getElementById('status').textContent));
  const project = await apiGet('/api/project');
  check(project.project.scale === 0.12, `scale ${project.project.scale}`);

  // After a reload the corrections and the last overlay are there.
  await page.reload();
  await page.waitForSelector('body[data-ready=true]');
  await page.waitForSelector('#plan-overlay[data-loaded=true]');
  const listed = await page.$$eval('#planfix-list li', (l) => l.length);
  check(listed === 2, `the two corrections listed after a reload (${listed})`);
  figures.relabel_round_trip_ms = roundTrips;
  check(errors.length === 0, `page errors: ${errors}`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(figures));
