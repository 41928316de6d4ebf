// End-to-end test of the Gothic step of `castellan serve` (issue 22) in Debian's Chromium
// (headless, via playwright-core): a synthetic Gothic photo uploaded from the page, its elements
// found, one window's apex dragged up, another window deleted with the Delete key, the deletion
// undone, an element added by dragging its box — with assertions on the elements the server returns and on PROJECT.toml.
// Run by crates/castellan/tests/serve_gothic_fix_e2e.rs, which starts the server and passes:
//   CASTELLAN_URL  the server's URL      SCREENSHOTS  folder for the PNGs
//   CHROMIUM       the browser binary    GOTHIC_PHOTO the photo to upload
//   APEX_DRAG      pixels to drag the apex up
// Prints one JSON line of figures last.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import path from 'node:path';

const url = process.env.CASTELLAN_URL;
const shots = process.env.SCREENSHOTS;
const photo = process.env.GOTHIC_PHOTO;
const apexDrag = Number(process.env.APEX_DRAG || 8);
fs.mkdirSync(shots, { recursive: true });
const userDataDir = fs.mkdtempSync(path.join(process.env.TMPDIR || '/tmp', 'castellan-chromium-'));

function check(ok, message) {
  if (!ok) throw new Error(message);
}

const browser = await chromium.launchPersistentContext(userDataDir, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1400, height: 1000 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--no-first-run', '--disable-sync'],
});
const figures = {};
try {
  const page = browser.pages()[0] || await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.setDefaultTimeout(120_000);
  await page.goto(url);
  await page.waitForSelector('body[data-ready=true]');

  const canvas = '#gothic-canvas';
  // A canvas position in image pixels → page coordinates.
  const at = async ([x, y]) => {
    const el = page.locator(canvas);
    await el.scrollIntoViewIfNeeded();
    const b = await el.boundingBox();
    const [w, h] = await el.evaluate((e) => [e.width, e.height]);
    return [b.x + (x * b.width) / w, b.y + (y * b.height) / h];
  };
  const elements = async () => JSON.parse(await page.getAttribute(canvas, 'data-elements'));
  const saved = (n) => page.waitForFunction((n) => {
    const c = document.getElementById('gothic-canvas');
    return c.dataset.saves === String(n) && c.dataset.state === 'ready';
  }, n);
  const projectToml = () => page.evaluate(() => fetch(`/files/PROJECT.toml?t=${Date.now()}`).then((r) => r.text()));

  // Upload, mark as an elevation, find the elements.
  await page.setInputFiles('#gothic-file', photo);
  await page.waitForFunction(() => document.getElementById('gothic-select').options.length === 1);
  figures.photo = await page.inputValue('#gothic-select');
  await page.check('#gothic-rectified');
  const t = Date.now();
  await page.click('#gothic-run');
  await page.waitForFunction(() => {
    const c = document.getElementById('gothic-canvas');
    return c.dataset.state === 'ready' && c.dataset.elements;
  });
  figures.find_ms = Date.now() - t;
  const found = await elements();
  figures.elements = found.length;
  check(found.length >= 3, `elements found: ${found.length}`);
  check(/rectified = true/.test(await projectToml()), 'the checkbox saved rectified = true');
  const windows = found.filter((e) => e.depth === 1);
  check(windows.length >= 2, `windows inside arches: ${windows.length}`);
  await page.locator('#gothic').screenshot({ path: path.join(shots, 'gothic.png') });

  // Drag the first window's apex handle up.
  const w = windows[0];
  const inside = (e) => [e.centre, (e.springing + e.sill) / 2];
  await page.mouse.click(...await at(inside(w)));
  check(await page.getAttribute(canvas, 'data-selected') === String(w.id), 'a click selects the window');
  const from = await at([w.centre, w.apex]);
  const to = await at([w.centre, w.apex - apexDrag]);
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(...to, { steps: 6 });
  await page.mouse.up();
  await saved(1);
  const afterDrag = await elements();
  const moved = afterDrag.find((e) => e.correction === 0);
  check(moved, 'the dragged element comes back marked as set by the user');
  figures.apex = { detected: w.apex, wanted: w.apex - apexDrag, returned: moved.apex };
  check(Math.abs(moved.apex - (w.apex - apexDrag)) <= 1.5, `apex ${moved.apex} vs ${w.apex - apexDrag}`);
  check(Math.abs(moved.springing - w.springing) <= 0.1 && Math.abs(moved.width - w.width) <= 0.1,
    'the other handles stay');
  check(afterDrag.length === found.length, 'no element lost by a drag');
  const toml1 = await projectToml();
  check(/\[\[gothic\.element\]\]/.test(toml1) && /apex = /.test(toml1), `PROJECT.toml after the drag:\n${toml1}`);

  // Delete another window with the Delete key.
  const other = afterDrag.find((e) => e.depth === 1 && e.id !== moved.id && e.correction === null);
  await page.mouse.click(...await at(inside(other)));
  check(await page.getAttribute(canvas, 'data-selected') === String(other.id), 'the other window is selected');
  await page.keyboard.press('Delete');
  await saved(2);
  const afterDelete = await elements();
  figures.after_delete = afterDelete.length;
  check(afterDelete.length === found.length - 1, `after the deletion: ${afterDelete.length}`);
  check(await page.getAttribute(canvas, 'data-corrections') === '2', 'two corrections');
  check(/delete = true/.test(await projectToml()), 'the deletion is saved');
  await page.locator('#gothic').screenshot({ path: path.join(shots, 'gothic-corrected.png') });

  // Undo the deletion.
  await page.click('#gothic-undo');
  await saved(3);
  const afterUndo = await elements();
  figures.after_undo = afterUndo.length;
  check(afterUndo.length === found.length, `after undo: ${afterUndo.length}`);
  const toml3 = await projectToml();
  check(!/delete = true/.test(toml3) && /apex = /.test(toml3), `PROJECT.toml after undo:\n${toml3}`);
  check((await page.textContent('#gothic-info')).includes('detection kept'), 'corrections do not detect again');

  // Add an element the detector did not find: a box dragged on plain wall, clear of every
  // element found (their bounding boxes grown by 4 px).
  const [cw, ch] = await page.locator(canvas).evaluate((e) => [e.width, e.height]);
  const [bw, bh] = [Math.round(cw / 12), Math.round(ch / 8)];
  const clear = (x, y) => afterUndo.every((e) => x + bw < e.centre - e.width / 2 - 4 || x > e.centre + e.width / 2 + 4
    || y + bh < e.apex - 4 || y > e.sill + 4);
  let spot = null;
  for (let y = 4; y + bh < ch - 4 && !spot; y += 4) {
    for (let x = 4; x + bw < cw - 4 && !spot; x += 4) if (clear(x, y)) spot = [x, y];
  }
  check(spot, 'a patch of plain wall for the new element');
  await page.click('#gothic-add');
  check(await page.getAttribute(canvas, 'data-adding') === 'true', 'add mode is on');
  await page.mouse.move(...await at(spot));
  await page.mouse.down();
  await page.mouse.move(...await at([spot[0] + bw, spot[1] + bh]), { steps: 6 });
  await page.mouse.up();
  await saved(4);
  const afterAdd = await elements();
  figures.after_add = afterAdd.length;
  const made = afterAdd.find((e) => Math.abs(e.centre - (spot[0] + bw / 2)) <= 1.5 && Math.abs(e.apex - spot[1]) <= 1.5);
  figures.added = made ? { centre: made.centre, apex: made.apex, sill: made.sill, width: made.width } : null;
  check(made, `the added element comes back where it was drawn: ${JSON.stringify(afterAdd)}`);
  check(Math.abs(made.sill - (spot[1] + bh)) <= 1.5 && Math.abs(made.width - bw) <= 1.5, 'with the drawn sill and width');
  check(await page.getAttribute(canvas, 'data-adding') === 'false', 'add mode ends with the box');
  check(/add = true/.test(await projectToml()), 'the addition is saved');
  figures.info = await page.textContent('#gothic-info');
  check(errors.length === 0, `page errors: ${errors.join('; ')}`);
} finally {
  await browser.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(JSON.stringify(figures));
