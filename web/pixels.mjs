// Pixels of a screenshot, and what the page's tests look for in them. PNGs are decoded by the
// browser itself (a blank tab), so the tests need no image library.

/// `{ width, height, data }` (RGBA bytes) of a PNG, decoded in `tab` (a blank page).
export async function decodePng(tab, png) {
  const { width, height, rgba } = await tab.evaluate(async (b64) => {
    const blob = await (await fetch(`data:image/png;base64,${b64}`)).blob();
    const bitmap = await createImageBitmap(blob);
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const context = canvas.getContext("2d");
    context.drawImage(bitmap, 0, 0);
    const bytes = context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    let binary = "";
    for (let i = 0; i < bytes.length; i += 0x8000) {
      binary += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    }
    return { width: bitmap.width, height: bitmap.height, rgba: btoa(binary) };
  }, png.toString("base64"));
  return { width, height, data: Buffer.from(rgba, "base64") };
}

const at = (img, x, y) => {
  const i = (y * img.width + x) * 4;
  return [img.data[i], img.data[i + 1], img.data[i + 2]];
};
const lum = ([r, g, b]) => (r + g + b) / 3;
const grey = ([r, g, b]) => Math.max(r, g, b) - Math.min(r, g, b) <= 16;

/// The largest 4-connected region of pixels for which `keep(rgb)` holds: its pixel count,
/// bounding box, the span of columns it covers on each row (`rows[y] = [first, last]`) and a
/// pixel of it near its middle.
export function largestRegion(img, keep) {
  const { width, height } = img;
  const label = new Int32Array(width * height);
  let best = { count: 0, id: 0 };
  const stack = [];
  let id = 0;
  for (let start = 0; start < width * height; start++) {
    if (label[start] || !keep(at(img, start % width, Math.floor(start / width)))) continue;
    label[start] = ++id;
    stack.push(start);
    let count = 0;
    while (stack.length) {
      const p = stack.pop();
      const x = p % width, y = Math.floor(p / width);
      count++;
      for (const [nx, ny] of [[x + 1, y], [x - 1, y], [x, y + 1], [x, y - 1]]) {
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        const q = ny * width + nx;
        if (!label[q] && keep(at(img, nx, ny))) {
          label[q] = id;
          stack.push(q);
        }
      }
    }
    if (count > best.count) best = { count, id };
  }
  if (!best.count) return { count: 0 };
  const rows = {};
  let sx = 0, sy = 0;
  for (let p = 0; p < width * height; p++) {
    if (label[p] !== best.id) continue;
    const x = p % width, y = Math.floor(p / width);
    rows[y] = rows[y] ? [Math.min(rows[y][0], x), Math.max(rows[y][1], x)] : [x, x];
    sx += x;
    sy += y;
  }
  const ys = Object.keys(rows).map(Number);
  const box = {
    x0: Math.min(...ys.map((y) => rows[y][0])), y0: Math.min(...ys),
    x1: Math.max(...ys.map((y) => rows[y][1])), y1: Math.max(...ys),
  };
  // The member pixel nearest the centroid (a concave region's centroid may lie outside it).
  const [mx, my] = [sx / best.count, sy / best.count];
  let middle = null, nearest = Infinity;
  for (let p = 0; p < width * height; p++) {
    if (label[p] !== best.id) continue;
    const d = (p % width - mx) ** 2 + (Math.floor(p / width) - my) ** 2;
    if (d < nearest) [nearest, middle] = [d, [p % width, Math.floor(p / width)]];
  }
  return { count: best.count, box, rows, middle };
}

/// The lit floor of the default scene and the shadows on it. The floor is a grey checkerboard:
/// its lit part is the largest region of light greys on screen (the panels are darker, the
/// diagrams whiter, the shadow map coloured). Along each row of it, between its first and last
/// pixel, a shadow is grey at under 60% of the lit floor's median brightness (the objects are
/// coloured, the background beside the floor is outside the span).
export function floorAndShadow(img) {
  const litFloor = (rgb) => grey(rgb) && lum(rgb) >= 110 && lum(rgb) <= 240;
  const floor = largestRegion(img, litFloor);
  if (!floor.count) return { floor, litShare: 0, shadowShare: 0 };
  const lit = [];
  let total = 0;
  for (const [y, [first, last]] of Object.entries(floor.rows)) {
    for (let x = first; x <= last; x++) {
      total++;
      const rgb = at(img, x, Number(y));
      if (litFloor(rgb)) lit.push(lum(rgb));
    }
  }
  lit.sort((a, b) => a - b);
  const median = lit[Math.floor(lit.length / 2)];
  let shadowed = 0;
  for (const [y, [first, last]] of Object.entries(floor.rows)) {
    for (let x = first; x <= last; x++) {
      const rgb = at(img, x, Number(y));
      if (grey(rgb) && lum(rgb) >= 25 && lum(rgb) < 0.6 * median) shadowed++;
    }
  }
  const { rows, ...region } = floor;
  return { floor: region, median, litShare: lit.length / total, shadowShare: shadowed / total };
}

/// Pixels within `radius` of `[x, y]` for which `keep(rgb)` holds.
export function countNear(img, [cx, cy], radius, keep) {
  let n = 0;
  for (let y = Math.max(0, cy - radius); y <= Math.min(img.height - 1, cy + radius); y++) {
    for (let x = Math.max(0, cx - radius); x <= Math.min(img.width - 1, cx + radius); x++) {
      if ((x - cx) ** 2 + (y - cy) ** 2 <= radius * radius && keep(at(img, x, y))) n++;
    }
  }
  return n;
}

/// The probe's marker: a ring of rgb(255, 210, 0).
export const markerYellow = ([r, g, b]) => r > 225 && g > 180 && g < 235 && b < 60;

/// Text on the dark panels: the share of pixels in `box` well above the panel's grey.
export function brightShare(img, { x0, y0, x1, y1 }) {
  let n = 0, total = 0;
  for (let y = y0; y <= y1; y++) {
    for (let x = x0; x <= x1; x++) {
      total++;
      if (lum(at(img, x, y)) > 90) n++;
    }
  }
  return n / total;
}
