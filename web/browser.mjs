// Headless Chromium for the page's scripts (check.mjs, test.mjs). Chromium's path: $CHROMIUM,
// else Debian's /usr/lib/chromium/chromium (the /usr/bin/chromium wrapper is a shell script).
// The flags give WebGPU (and WebGL2) on SwiftShader, a CPU rasteriser, so any machine can run
// the page; without --use-vulkan=swiftshader screenshots of a WebGPU canvas come out white.
import { chromium } from "playwright-core";

export const CHROMIUM_FLAGS = [
  "--no-sandbox",
  "--enable-unsafe-webgpu",
  "--enable-features=Vulkan",
  "--use-vulkan=swiftshader",
  "--use-angle=swiftshader",
  "--use-webgpu-adapter=swiftshader",
];

export function launchChromium() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/lib/chromium/chromium",
    args: CHROMIUM_FLAGS,
  });
}

/// `--name value` from the command line, else `fallback`.
export function arg(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
}
