// The page's tests in headless Chromium (WebGPU and WebGL2 on SwiftShader): each named check
// opens the page in a tab of its own and does what a user would, then asserts on what the page
// shows (its screenshots' pixels, its downloads) and on what it tells scripts on <body>
// (data-frames, data-views, data-lang, ...).
//   node web/test.mjs [--url http://127.0.0.1:8080/] [--out DIR] [--only WORD] [--timeout 180]
// `bash web/test.sh` builds dist/, serves it and runs this; by hand, serve dist/ first
// (python3 -m http.server 8080 --bind 127.0.0.1 --directory dist). Screenshots of each check go
// to --out (default /tmp/shadowlab-web-test). Exit code 1 when a check fails.
// The clicks assume the 1280x800 layout of a first start (the top bar on two rows).
import { execFileSync } from "node:child_process";
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join } from "node:path";
import { arg, launchChromium } from "./browser.mjs";
import { brightShare, countNear, decodePng, floorAndShadow, markerYellow } from "./pixels.mjs";

const url = new URL(arg("url", "http://127.0.0.1:8080/"));
const out = arg("out", "/tmp/shadowlab-web-test");
const only = arg("only", "");
const timeoutMs = Number(arg("timeout", "180")) * 1000;
mkdirSync(out, { recursive: true });

/// Where the first start's controls are at 1280x800.
const LANGUAGE_BOX = [207, 35];
const CHINESE_ITEM = [200, 86];
const SCREENSHOT_BUTTON = [48, 35];
/// Below the views' heading: where the no-WebGPU notice is written.
const NOTICE_BOX = { x0: 360, y0: 130, x1: 1270, y1: 300 };

const address = (query) => {
  const u = new URL(url);
  u.search = query;
  return u.toString();
};
const body = (page) => page.evaluate(() => ({ ...document.body.dataset }));
const waitForBody = (page, test, arg) =>
  page.waitForFunction(test, arg, { timeout: timeoutMs, polling: 250 });

/// A tab on `query`, once the app has started (data-views set) and, where it renders, drawn a
/// frame; the lesson list a first start shows is closed (Escape).
async function open(browser, query = "", { withoutWebGpu = false } = {}) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.log = [];
  page.on("console", (m) => page.log.push(`${m.type()}: ${m.text()}`));
  page.on("pageerror", (e) => page.log.push(`pageerror: ${e.message}`));
  if (withoutWebGpu) {
    // A browser without WebGPU: no navigator.gpu at all.
    await page.addInitScript(() => delete Object.getPrototypeOf(navigator).gpu);
  }
  await page.goto(address(query));
  await waitForBody(page, () => document.body.dataset.views);
  if ((await body(page)).views === "webgpu") {
    await waitForBody(page, () => Number(document.body.dataset.frames || 0) >= 1);
  }
  await page.focus("#shadowlab_canvas");
  await page.keyboard.press("Escape");
  await page.waitForTimeout(1500);
  return page;
}

/// The page as the user sees it now, saved as `name` and decoded.
async function look(page, decoder, name) {
  const png = await page.screenshot({ path: join(out, `${name}.png`) });
  return decodePng(decoder, png);
}

/// Wait until a new frame reached the views, then a moment for it to be painted.
async function nextFrame(page) {
  const frames = Number((await body(page)).frames || 0);
  await waitForBody(page, (f) => Number(document.body.dataset.frames) > f, frames);
  await page.waitForTimeout(1500);
}

async function switchToChinese(page) {
  await page.mouse.click(...LANGUAGE_BOX);
  await page.waitForTimeout(500);
  await page.mouse.click(...CHINESE_ITEM);
  await waitForBody(page, () => document.body.dataset.lang === "zh");
  await page.waitForTimeout(1000);
}

function expect(condition, message) {
  if (!condition) throw new Error(message);
}

const checks = [
  {
    name: "webgpu: the default scene renders a shadow",
    async run({ browser, decoder }) {
      const page = await open(browser);
      const where = await body(page);
      expect(where.views === "webgpu", `data-views is ${where.views}, not webgpu`);
      const seen = floorAndShadow(await look(page, decoder, "webgpu-default"));
      const share = (x) => `${(100 * x).toFixed(1)}%`;
      const found = `lit floor ${share(seen.litShare)}, shadow ${share(seen.shadowShare)} of the floor's rows ${JSON.stringify(seen.floor.box)}`;
      expect(seen.litShare > 0.3, `no lit floor in the camera view: ${found}`);
      expect(seen.shadowShare > 0.005, `no shadow on the floor: ${found}`);
      return found;
    },
  },
  {
    name: "webgpu: a click on the camera view pins a probe",
    async run({ browser, decoder }) {
      const page = await open(browser);
      const floor = floorAndShadow(await look(page, decoder, "probe-before")).floor;
      expect(floor.count > 0, "no camera view to click");
      const at = floor.middle;
      const before = countNear(await look(page, decoder, "probe-before"), at, 12, markerYellow);
      await page.mouse.click(...at);
      let after = 0;
      for (let tries = 0; tries < 20 && after < 20; tries++) {
        await page.waitForTimeout(500);
        after = countNear(await look(page, decoder, "probe-after"), at, 12, markerYellow);
      }
      expect(before < 5 && after >= 20, `the probe's marker at ${at}: ${before} yellow pixels before the click, ${after} after`);
      // Where the page names the probed pixel (<body data-probe="x,y">), it names one.
      let named = "";
      if ("probe" in (await body(page))) {
        await waitForBody(page, () => /^\d+,\d+$/.test(document.body.dataset.probe));
        named = `, data-probe=${(await body(page)).probe}`;
      }
      return `marker at ${at}: ${after} yellow pixels (${before} before)${named}`;
    },
  },
  {
    name: "webgpu: the language control switches the page to Chinese",
    async run({ browser, decoder }) {
      const page = await open(browser);
      const english = await look(page, decoder, "language-en");
      await switchToChinese(page);
      const chinese = await look(page, decoder, "language-zh");
      // The top bar's words change (their glyphs drawn from the built-in Chinese font).
      let changed = 0;
      for (let i = 0; i < 1280 * 48 * 4; i += 4) if (english.data[i] !== chinese.data[i]) changed++;
      expect(changed > 2000, `the top bar barely changed (${changed} pixels)`);
      // The glyphs come from the font served beside the wasm, not built into it.
      const font = (await body(page)).cjkFont;
      expect(font === "served", `the Chinese font was ${font}, not served`);
      return `data-lang=zh, data-cjk-font=${font}, ${changed} pixels of the top bar changed`;
    },
  },
  {
    name: "webgpu: the Screenshot button downloads the window and each view as PNGs",
    async run({ browser, decoder }) {
      const page = await open(browser);
      const downloads = [];
      page.on("download", (d) => downloads.push(d));
      await page.mouse.click(...SCREENSHOT_BUTTON);
      for (let waited = 0; downloads.length < 3 && waited < 30000; waited += 250) await page.waitForTimeout(250);
      const names = downloads.map((d) => d.suggestedFilename()).sort();
      const wanted = ["shot-001-camera.png", "shot-001-shadow-map.png", "shot-001-window.png"];
      expect(JSON.stringify(names) === JSON.stringify(wanted), `downloads ${JSON.stringify(names)}, not ${JSON.stringify(wanted)}`);
      const sizes = [];
      for (const d of downloads) {
        const png = readFileSync(await d.path());
        expect(png.subarray(1, 4).toString() === "PNG", `${d.suggestedFilename()} is not a PNG`);
        const { width, height } = await decodePng(decoder, png);
        sizes.push(`${d.suggestedFilename()} ${width}x${height}`);
        if (d.suggestedFilename().endsWith("window.png")) {
          expect(width === 1280 && height === 800, `the window is ${width}x${height}, not 1280x800`);
        }
      }
      return sizes.join(", ");
    },
  },
  {
    name: "webgl2: ?backend=webgl2 says why there are no views, in both languages",
    async run({ browser, decoder }) {
      const page = await open(browser, "?backend=webgl2");
      const where = await body(page);
      expect(where.views === "webgl2-asked", `data-views is ${where.views}, not webgl2-asked`);
      const english = brightShare(await look(page, decoder, "webgl2-en"), NOTICE_BOX);
      expect(english > 0.01, `nothing written where the views would be (${english})`);
      await switchToChinese(page);
      const chinese = brightShare(await look(page, decoder, "webgl2-zh"), NOTICE_BOX);
      expect(chinese > 0.01, `nothing written in Chinese where the views would be (${chinese})`);
      expect(Number((await body(page)).frames || 0) === 0, "a frame reached views WebGL2 cannot render");
      return `notice ink ${(100 * english).toFixed(1)}% (en), ${(100 * chinese).toFixed(1)}% (zh)`;
    },
  },
  {
    name: "no WebGPU: a browser without navigator.gpu says why",
    async run({ browser, decoder }) {
      const page = await open(browser, "", { withoutWebGpu: true });
      const where = await body(page);
      expect(where.views === "webgl2-no-webgpu", `data-views is ${where.views}, not webgl2-no-webgpu`);
      const ink = brightShare(await look(page, decoder, "no-webgpu"), NOTICE_BOX);
      expect(ink > 0.01, `nothing written where the views would be (${ink})`);
      return `notice ink ${(100 * ink).toFixed(1)}%`;
    },
  },
  {
    name: "lesson link: ?lesson=pcss&step=3&lang=zh opens that step, and the address follows",
    async run({ browser, decoder }) {
      const page = await open(browser, "?lesson=pcss&step=3&lang=zh");
      await waitForBody(page, () => document.body.dataset.lesson === "pcss");
      const where = await body(page);
      expect(where.step === "3" && where.lang === "zh", `data-step=${where.step} data-lang=${where.lang}`);
      await look(page, decoder, "lesson-link");
      // The next step (the arrow key, as a student walks on): the address says where they are.
      await page.focus("#shadowlab_canvas");
      await page.keyboard.press("ArrowRight");
      await waitForBody(page, () => document.body.dataset.step === "4");
      const address = await page.evaluate(() => location.search);
      expect(address === "?lesson=pcss&step=4&lang=zh", `the address is ${address}`);
      return `data-lesson=${where.lesson} data-step=${where.step} data-lang=${where.lang}, then ${address}`;
    },
  },
  {
    name: "scene link: ?scene=contact&technique=pcf opens that scene with that technique",
    async run({ browser }) {
      const page = await open(browser, "?scene=contact&technique=pcf");
      await waitForBody(page, () => document.body.dataset.technique === "pcf");
      const where = await body(page);
      expect(where.lesson === "", `a lesson is open: ${where.lesson}`);
      const address = await page.evaluate(() => location.search);
      expect(address.startsWith("?scene=contact&technique=pcf"), `the address is ${address}`);
      return `data-technique=${where.technique}, ${address}`;
    },
  },
  {
    name: "homework: a .glsl dropped on the page is checked, with its findings",
    async run({ browser, decoder }) {
      const page = await open(browser);
      // The example whose light is smaller than a texel: its one finding is no_penumbra.
      const shader = readFileSync(
        new URL("../assets/homework/phongFragment_tiny_light.glsl", import.meta.url),
        "utf8",
      );
      const drop = await page.evaluateHandle((text) => {
        const data = new DataTransfer();
        data.items.add(new File([text], "phongFragment.glsl", { type: "text/plain" }));
        return data;
      }, shader);
      for (const type of ["dragenter", "dragover", "drop"]) {
        await page.dispatchEvent("#shadowlab_canvas", type, { dataTransfer: drop });
      }
      await waitForBody(page, () => ["checked", "error"].includes(document.body.dataset.homework));
      await look(page, decoder, "homework-drop");
      const where = await body(page);
      expect(where.homework === "checked", `the check ended with data-homework=${where.homework}`);
      expect(where.findings === "no_penumbra", `findings: ${where.findings || "none"}`);
      return `data-homework=${where.homework}, findings: ${where.findings}`;
    },
  },
  {
    name: "homework: a .zip of a homework folder dropped on the page is checked with the student's light",
    async run({ browser, decoder }) {
      // The correct shader with a light whose box is only 50 world units wide: one finding.
      const page = await openWith(browser, [
        ["src/shaders/phongShader/phongFragment.glsl", example("phongFragment.glsl")],
        ["src/lights/DirectionalLight.js", example("DirectionalLight_narrow.js")],
      ]);
      await look(page, decoder, "homework-zip-drop");
      const where = await body(page);
      expect(where.homework === "checked", `the check ended with data-homework=${where.homework}`);
      expect(where.findings === "light_frustum_clips", `findings: ${where.findings || "none"}`);
      return `data-homework=${where.homework}, findings: ${where.findings}`;
    },
  },
  {
    name: "homework: a student's page runs in the browser's engine as on the desktop (three.js light, two lights, their uniforms)",
    async run({ browser, decoder }) {
      // Their light is built with three.js; their engine.js moves it and makes a second one.
      const engine = edit(
        readFileSync(new URL("../assets/homework/framework/src/engine.js", import.meta.url), "utf8"),
        "    renderer.addLight(directionLight);",
        "    renderer.addLight(directionLight);\n    renderer.addLight(new DirectionalLight(100, [1, 0, 0], [-50, 60, 40], focalPoint, lightUp, true, renderer.gl));",
      ).replace("const lightPos = [0, 80, 80];", "const lightPos = [20, 90, 70];");
      const files = [
        ["src/shaders/phongShader/phongFragment.glsl", example("phongFragment.glsl")],
        ["src/lights/DirectionalLight.js", example("DirectionalLight_three.js")],
        ["src/engine.js", Buffer.from(engine)],
      ];
      const desktop = desktopCheck(files).light;
      const page = await openWith(browser, files);
      await look(page, decoder, "homework-page-engine");
      const where = await body(page);
      expect(where.homework === "checked", `the check ended with data-homework=${where.homework}`);
      const browserSide = JSON.parse(where.homeworkLight).light;
      expect(browserSide.error === null, `the page's light failed: ${browserSide.error}`);
      expect(browserSide.from === desktop.from, `from ${browserSide.from}, desktop ${desktop.from}`);
      expect(same(browserSide.position, [20, 90, 70]), `position ${browserSide.position}`);
      const far = [
        ["the light's matrix", browserSide.clip_from_world, desktop.clip_from_world],
        ["each object's matrix", browserSide.clip_from_object, desktop.clip_from_object],
        ["the lights the page made", browserSide.lights, desktop.lights],
        ["the calls", browserSide.calls, desktop.calls],
        ["the uniforms their page set", browserSide.page_uniforms, desktop.page_uniforms],
      ].filter(([, a, b]) => !same(a, b));
      expect(far.length === 0, far.map(([what, a, b]) => `${what}: ${JSON.stringify(a)} != ${JSON.stringify(b)}`).join("; "));
      expect(browserSide.lights.length === 2, `${browserSide.lights.length} lights listed`);
      const uniforms = Object.keys(browserSide.page_uniforms.camera.other || {}).length;
      expect(uniforms > 0, "no uniform their page set was read");
      return `matrices, ${browserSide.lights.length} lights, ${browserSide.calls.length} calls and ${uniforms} uniforms as on the desktop`;
    },
  },
  {
    name: "homework: a page that never ends or does not parse ends in one line naming the file, in the browser too",
    async run({ browser }) {
      const light = example("DirectionalLight.js").toString();
      const broken = edit(light, "    mat4.multiply(mvp, projection, view);", "    mat4.multiply(mvp, projection, view;");
      const line = broken.split("\n").findIndex((l) => l.includes("view;")) + 1;
      const engine = "while (true) {}\n";
      const found = [];
      for (const [files, expected] of [
        [[["src/lights/DirectionalLight.js", Buffer.from(broken)]], `homework1/src/lights/DirectionalLight.js:${line}: `],
        [[["src/lights/DirectionalLight.js", Buffer.from(light)], ["src/engine.js", Buffer.from(engine)]], "homework1/src/engine.js: the script ran past its time bound"],
      ]) {
        const shader = ["src/shaders/phongShader/phongFragment.glsl", example("phongFragment.glsl")];
        const page = await openWith(browser, [shader, ...files]);
        const where = await body(page);
        expect(where.homework === "checked", `the check ended with data-homework=${where.homework}`);
        const error = JSON.parse(where.homeworkLight).light.error || "";
        expect(error.startsWith(expected) && !error.includes("\n"), `the light's error is ${JSON.stringify(error)}, not ${expected}...`);
        found.push(error);
        await page.close();
      }
      return found.join(" | ");
    },
  },
];

const example = (name) => readFileSync(new URL(`../assets/homework/${name}`, import.meta.url));

/** `text` with `from` replaced by `to`, which must be in it. */
function edit(text, from, to) {
  expect(text.includes(from), `${JSON.stringify(from)} is not in the text`);
  return text.replace(from, to);
}

/** Whether two of the report's values agree, numbers to 1e-6 of their size. */
function same(a, b) {
  if (typeof a === "number" && typeof b === "number") return Math.abs(a - b) <= 1e-6 * Math.max(1, Math.abs(a), Math.abs(b));
  if (Array.isArray(a) && Array.isArray(b)) return a.length === b.length && a.every((x, i) => same(x, b[i]));
  if (a && b && typeof a === "object" && typeof b === "object") {
    const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
    return [...keys].every((k) => same(a[k], b[k]));
  }
  return a === b;
}

/** The desktop's report of the submission `files` ([path in homework1/, bytes]): `shadowlab
 *  homework` run as a process (built by cargo where it is not). */
function desktopCheck(files) {
  const root = mkdtempSync(join(tmpdir(), "shadowlab-web-"));
  for (const [path, bytes] of files) {
    const to = join(root, "alice/homework1", path);
    mkdirSync(dirname(to), { recursive: true });
    writeFileSync(to, bytes);
  }
  const manifest = new URL("../Cargo.toml", import.meta.url).pathname;
  const stdout = execFileSync(
    "cargo",
    ["run", "--release", "--quiet", "--manifest-path", manifest, "--", "homework", join(root, "alice"),
      "--size", "480x270", "--out", join(root, "out"), "--json"],
    { encoding: "utf8", maxBuffer: 64 << 20, stdio: ["ignore", "pipe", "inherit"] },
  );
  return JSON.parse(stdout);
}

/** A tab with the submission `files` dropped on it as a zip, once its check has ended. */
async function openWith(browser, files) {
  const page = await open(browser);
  // Named inside the zip as the desktop names them in the folder alice/: homework1/src/...
  const zip = storedZip(files.map(([path, bytes]) => [`homework1/${path}`, bytes]));
  const drop = await page.evaluateHandle((bytes) => {
    const data = new DataTransfer();
    data.items.add(new File([new Uint8Array(bytes)], "alice.zip", { type: "application/zip" }));
    return data;
  }, Array.from(zip));
  for (const type of ["dragenter", "dragover", "drop"]) {
    await page.dispatchEvent("#shadowlab_canvas", type, { dataTransfer: drop });
  }
  await waitForBody(page, () => ["checked", "error"].includes(document.body.dataset.homework));
  return page;
}

/** CRC-32 (IEEE), as a zip's headers carry it. */
function crc32(bytes) {
  let crc = 0xffffffff;
  for (const byte of bytes) {
    crc ^= byte;
    for (let k = 0; k < 8; k++) crc = (crc >>> 1) ^ (0xedb88320 & -(crc & 1));
  }
  return (crc ^ 0xffffffff) >>> 0;
}

/** A zip of [name, bytes] entries, stored without compression. */
function storedZip(entries) {
  const parts = [];
  const central = [];
  let offset = 0;
  const header = (fields) => {
    const out = Buffer.alloc(fields.reduce((n, [size]) => n + size, 0));
    let at = 0;
    for (const [size, value] of fields) {
      if (size === 2) out.writeUInt16LE(value, at);
      else out.writeUInt32LE(value, at);
      at += size;
    }
    return out;
  };
  for (const [name, data] of entries) {
    const nameBytes = Buffer.from(name, "utf8");
    const crc = crc32(data);
    const local = header([[4, 0x04034b50], [2, 20], [2, 0], [2, 0], [2, 0], [2, 0], [4, crc],
      [4, data.length], [4, data.length], [2, nameBytes.length], [2, 0]]);
    parts.push(local, nameBytes, data);
    central.push(header([[4, 0x02014b50], [2, 20], [2, 20], [2, 0], [2, 0], [2, 0], [2, 0], [4, crc],
      [4, data.length], [4, data.length], [2, nameBytes.length], [2, 0], [2, 0], [2, 0], [2, 0],
      [4, 0], [4, offset]]), nameBytes);
    offset += local.length + nameBytes.length + data.length;
  }
  const directory = Buffer.concat(central);
  const end = header([[4, 0x06054b50], [2, 0], [2, 0], [2, entries.length], [2, entries.length],
    [4, directory.length], [4, offset], [2, 0]]);
  return Buffer.concat([...parts, directory, end]);
}

const browser = await launchChromium();
const decoder = await browser.newPage();
let failed = 0;
const started = Date.now();
for (const check of checks) {
  if (only && !check.name.includes(only)) continue;
  const t = Date.now();
  const seconds = () => ((Date.now() - t) / 1000).toFixed(1);
  let passed = false;
  try {
    const why = check.skip && (await check.skip({ browser, decoder }));
    if (why) {
      console.log(`SKIP ${check.name}: ${why}`);
      passed = true;
      continue;
    }
    const detail = await check.run({ browser, decoder });
    console.log(`ok   ${check.name} (${seconds()} s): ${detail}`);
    passed = true;
  } catch (e) {
    failed++;
    console.log(`FAIL ${check.name} (${seconds()} s): ${e.message}`);
  } finally {
    for (const page of browser.contexts().flatMap((c) => c.pages())) {
      if (page !== decoder) {
        // What the page logged, where the check failed.
        for (const line of passed ? [] : page.log || []) console.log(`    ${line}`);
        await page.close();
      }
    }
  }
}
await browser.close();
console.log(`${failed ? "FAILED" : "passed"}: ${failed} failed, in ${((Date.now() - started) / 1000).toFixed(0)} s; screenshots in ${out}`);
process.exit(failed ? 1 : 0);
