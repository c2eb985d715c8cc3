// Load the built page in headless Chromium and wait for its first finished render.
//   node web/check.mjs [--url http://127.0.0.1:8080/] [--out screenshots/web.png] [--timeout 300]
// Serve dist/ first (python3 -m http.server 8080 --bind 127.0.0.1 --directory dist). Chromium's
// path: $CHROMIUM, else Debian's /usr/lib/chromium/chromium. The flags give WebGPU (and WebGL2)
// on SwiftShader, a CPU rasteriser, so any machine can run this; screenshots include the canvas.
import { chromium } from "playwright-core";

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const url = arg("url", "http://127.0.0.1:8080/");
const out = arg("out", "screenshots/web.png");
const timeoutS = Number(arg("timeout", "300"));

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/lib/chromium/chromium",
  args: [
    "--no-sandbox",
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan",
    "--use-vulkan=swiftshader",
    "--use-angle=swiftshader",
    "--use-webgpu-adapter=swiftshader",
  ],
});
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
