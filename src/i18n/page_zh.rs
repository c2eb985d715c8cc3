//! What only the page says (no WebGPU, downloads) in Simplified Chinese.

/// English -> Chinese.
pub(super) const PAGE: &[(&str, &str)] = &[
    ("The camera view and the shadow map need WebGPU", "相机视图和阴影贴图需要 WebGPU"),
    ("The page asked for WebGL2 (?backend=webgl2).", "网页地址要求使用 WebGL2（?backend=webgl2）。"),
    ("This browser has no WebGPU, or has it turned off.", "这个浏览器没有 WebGPU，或者把它关掉了。"),
    (
        "This browser's WebGPU found no GPU it may use (a GPU on its blocklist, or hardware acceleration off).",
        "这个浏览器的 WebGPU 找不到可以使用的 GPU（GPU 在它的黑名单上，或者硬件加速被关掉了）。",
    ),
    (
        "WebGPU needs a secure page: https, or http on localhost.",
        "WebGPU 需要安全的网页：https，或者 localhost 上的 http。",
    ),
    (
        "The page runs on WebGL2 instead, which has no storage buffers or compute shaders, and shadowlab renders the views with both. The lessons, the diagrams and the panels work without them.",
        "于是网页改用 WebGL2，而 WebGL2 没有存储缓冲区和计算着色器，shadowlab 渲染视图正要用到这两样。课程、示意图和各个面板不需要它们，照常可用。",
    ),
    (
        "For the views, open this page in a browser with WebGPU: Chrome or Edge 113 or later, Safari 26 or later, Firefox 141 or later on Windows.",
        "要看视图，请用支持 WebGPU 的浏览器打开本页：Chrome 或 Edge 113 及以上、Safari 26 及以上、Windows 上的 Firefox 141 及以上。",
    ),
    ("downloaded", "已下载"),
    (
        "in the page, screenshots are downloads (PNG files in the browser's download folder)",
        "在网页里，截图以下载的方式保存（PNG 文件，在浏览器的下载文件夹里）",
    ),
];
