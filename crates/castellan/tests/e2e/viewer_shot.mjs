// Pictures of the report's model viewer as a browser draws it (issue 25: moiré on tiled
// wall textures is only seen on the GPU path, not in the preview castellan renders itself).
// A tool, not a test: run by hand after `npm ci` here, on a report `castellan demo` or
// `castellan reconstruct` wrote:
//   node viewer_shot.mjs OUT/index.html PREFIX
// writes PREFIX.png (the viewer at its default size and view) and PREFIX-near.png (zoomed in
// with the mouse wheel, where walls fill the view). CHROMIUM names the browser
// (default /usr/bin/chromium); it draws with SwiftShader, as the e2e test does.
import { chromium } from 'playwright-core';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [report, prefix] = process.argv.slice(2);
if (!report || !prefix) {
  console.error('usage: node viewer_shot.mjs REPORT.html PREFIX');
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(pathToFileURL(path.resolve(report)).href);
  const viewer = page.locator('#viewer');
  await page.waitForSelector('#viewer[data-ready=true]', { timeout: 120_000 });
  await viewer.scrollIntoViewIfNeeded();
  // Textures decode asynchronously after the model is shown; the next frames draw them.
  await page.waitForTimeout(1500);
  await viewer.hover();
  await page.mouse.wheel(0, 1);
  await page.waitForTimeout(300);
  await viewer.screenshot({ path: `${prefix}.png` });
  for (let i = 0; i < 6; i++) {
    await page.mouse.wheel(0, -300);
    await page.waitForTimeout(100);
  }
  await page.waitForTimeout(500);
  await viewer.screenshot({ path: `${prefix}-near.png` });
  if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
} finally {
  await browser.close();
}
