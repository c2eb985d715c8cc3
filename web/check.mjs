// Load the built page in headless Chromium and wait for its first finished render.
//   node web/check.mjs [--url http://127.0.0.1:8080/] [--out screenshots/web.png] [--timeout 300]
// Serve dist/ first (python3 -m http.server 8080 --bind 127.0.0.1 --directory dist). Chromium:
// see browser.mjs. `node web/test.mjs` runs the page's tests.
import { arg, launchChromium } from "./browser.mjs";

const url = arg("url", "http://127.0.0.1:8080/");
const out = arg("out", "screenshots/web.png");
const timeoutS = Number(arg("timeout", "300"));

const browser = await launchChromium();
const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
const log = [];
page.on("console", (m) => log.push(`${m.type()}: ${m.text()}`));
page.on("pageerror", (e) => log.push(`pageerror: ${e.message}`));
const started = Date.now();
await page.goto(url);
let frames = 0;
try {
  await page.waitForFunction(() => Number(document.body.dataset.frames || 0) >= 1, null, {
    timeout: timeoutS * 1000,
    polling: 500,
  });
  frames = Number(await page.evaluate(() => document.body.dataset.frames));
  const where = await page.evaluate(() => ({ ...document.body.dataset }));
  log.push(`body: ${JSON.stringify(where)}`);
} catch (e) {
  log.push(`no finished render within ${timeoutS} s`);
}
const seconds = ((Date.now() - started) / 1000).toFixed(1);
// A moment for the frame to be painted after it arrived.
await page.waitForTimeout(1500);
await page.screenshot({ path: out });
// Then the view itself: Escape closes the lesson list a first start shows over it.
if (frames) {
  await page.mouse.click(640, 400);
  await page.keyboard.press("Escape");
  await page.waitForTimeout(4000);
  await page.screenshot({ path: out.replace(/\.png$/, "-view.png") });
}
const adapter = await page.evaluate(async () => {
  if (!navigator.gpu) return "no navigator.gpu";
  const a = await navigator.gpu.requestAdapter();
  if (!a) return "no WebGPU adapter";
  const { vendor, architecture, device, description } = a.info;
  return [vendor, architecture, device, description].filter(Boolean).join(" ");
});
console.log(JSON.stringify({ url, frames, seconds_to_first_frame: frames ? Number(seconds) : null, adapter, screenshot: out }));
for (const line of log) console.log(line);
await browser.close();
process.exit(frames >= 1 ? 0 : 1);
