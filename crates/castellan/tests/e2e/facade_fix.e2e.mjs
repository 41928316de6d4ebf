// End-to-end test of the façade corrections of `castellan serve` (issue 22) in Debian's Chromium
// (headless, via playwright-core), on the demo project: open the façade tree of the near photo,
// drag a floor line, add a window, delete one, mark the ground floor as having no windows, undo
// once — after each, the saved corrections (GET /api/project: the [facade.fix] of PROJECT.toml)
// and the corrected tree's floor and window counts are checked.
// Run by crates/castellan/tests/serve_facade_fix_e2e.rs, which starts the server and passes:
//   CASTELLAN_URL  the server's URL      SCREENSHOTS  folder for the PNGs
//   CHROMIUM       the browser binary
// Prints one JSON line of figures (counts after each step) last.
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

const browser = await chromium.launchPersistentContext(userDataDir, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1400, height: 1000 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--no-first-run', '--disable-sync'],
});
const figures = { steps: [] };
try {
  const page = browser.pages()[0] || await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.setDefaultTimeout(60_000);
  await page.goto(url);
  await page.waitForSelector('body[data-ready=true]');
  check(await page.inputValue('#facade-select') === 'keep_south_near.png', 'the near photo is selected');

  // A canvas position in image pixels → page coordinates.
  const at = async ([x, y]) => {
    const el = page.locator('#fix-canvas');
    await el.scrollIntoViewIfNeeded();
    const b = await el.boundingBox();
    const [w, h] = await el.evaluate((e) => [e.width, e.height]);
    return [b.x + (x * b.width) / w, b.y + (y * b.height) / h];
  };
  const drag = async (from, to) => {
    await page.mouse.move(...(await at(from)));
    await page.mouse.down();
    await page.mouse.move(...(await at(to)), { steps: 8 });
    await page.mouse.up();
  };
  const click = async (pt) => page.mouse.click(...(await at(pt)));
  // The tree the page shows, its counts, and the corrections saved in PROJECT.toml.
  const tree = async () => JSON.parse(await page.getAttribute('#fix-canvas', 'data-tree'))[0];
  const counts = async () => ({
    floors: Number(await page.getAttribute('#fix-info', 'data-floors')),
    windows: Number(await page.getAttribute('#fix-info', 'data-windows')),
  });
  const saved = () => page.evaluate(() => fetch('/api/project').then((r) => r.json())
    .then((p) => p.project.facade.find((f) => f.image === 'keep_south_near.png').fix || {}));
  const afterChange = async (undo, name) => {
    await page.waitForSelector(`#fix-info[data-undo="${undo}"]`);
    const c = await counts();
    const fix = await saved();
    figures.steps.push({ step: name, ...c, fix });
    return { ...c, fix };
  };

  await page.click('#fix-open');
  await page.waitForSelector('#fix-info[data-undo="0"]');
  const start = await counts();
  figures.start = start;
  const t0 = await tree();
  check(start.floors >= 3 && start.floors === t0.floors.length, `floors at the start: ${JSON.stringify(start)}`);
  check(JSON.stringify(await saved()) === '{}', 'no corrections saved at the start');
  const [bx0, , bx1] = t0.bbox;
  const mid = (bx0 + bx1) / 2;

  // 1 drag the first floor line 6 px down.
  const line = t0.floors[1].y0;
  await drag([mid, line], [mid, line + 6]);
  const a = await afterChange(1, 'floor line');
  check(a.fix.floor_lines && a.fix.floor_lines.length === start.floors - 1, `floor_lines saved: ${JSON.stringify(a.fix)}`);
  check(Math.abs(a.fix.floor_lines[0] - (line + 6)) <= 1, `the line moved to ${line + 6}: ${a.fix.floor_lines}`);
  const t1 = await tree();
  check(Math.abs(t1.floors[1].y0 - a.fix.floor_lines[0]) < 1e-6, 'the tree\'s floor follows the line');
  check(a.floors === start.floors, 'as many floors');

  // 2 add a window in the second floor from the top.
  await page.check('input[name=fix-mode][value=add]');
  const f1 = t1.floors[1];
  const box = [bx0 + 2, f1.y0 + 2, bx0 + 10, f1.y0 + 10];
  await drag([box[0], box[1]], [box[2], box[3]]);
  const b = await afterChange(2, 'add window');
  check((b.fix.add_windows || []).length === 1, `add_windows saved: ${JSON.stringify(b.fix)}`);
  check(b.windows === a.windows + 1, `one window more: ${a.windows} → ${b.windows}`);

  // 3 delete a window of the top floor.
  await page.check('input[name=fix-mode][value=delete]');
  const t2 = await tree();
  const w = t2.floors[0].windows[0];
  await click([(w[0] + w[2]) / 2, (w[1] + w[3]) / 2]);
  const c = await afterChange(3, 'delete window');
  check((c.fix.remove_windows || []).length === 1, `remove_windows saved: ${JSON.stringify(c.fix)}`);
  check(c.windows === b.windows - 1, `one window fewer: ${b.windows} → ${c.windows}`);

  // 4 the ground floor has no windows.
  await page.check('input[name=fix-mode][value=blind]');
  const t3 = await tree();
  const ground = t3.floors[t3.floors.length - 1];
  const groundWindows = ground.windows.length;
  check(groundWindows > 0, 'the ground floor had windows');
  await click([mid, (ground.y0 + ground.y1) / 2]);
  const d = await afterChange(4, 'blind floor');
  check(JSON.stringify(d.fix.blind_floors) === '[1]', `blind_floors saved: ${JSON.stringify(d.fix)}`);
  const t4 = await tree();
  check(t4.floors[t4.floors.length - 1].windows.length === 0, 'the ground floor has no windows');
  check(d.windows === c.windows - groundWindows, `the ground floor's windows gone: ${c.windows} → ${d.windows}`);
  await page.locator('#facade-fix').screenshot({ path: path.join(shots, 'facade-fix.png') });

  // 5 undo once: the ground floor's windows come back, the other corrections stay.
  await page.click('#fix-undo');
  const e = await afterChange(3, 'undo');
  check(!e.fix.blind_floors, `blind_floors undone: ${JSON.stringify(e.fix)}`);
  check(e.windows === c.windows, `windows back to ${c.windows}: ${e.windows}`);
  check((e.fix.add_windows || []).length === 1 && (e.fix.remove_windows || []).length === 1, 'the rest stays');
  check(errors.length === 0, `page errors: ${errors.join('; ')}`);
} finally {
  await browser.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(JSON.stringify(figures));
