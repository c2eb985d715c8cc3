//! The homework check's findings and panel in Simplified Chinese.

/// English -> Chinese, for every finding's explanation.
pub(super) const HOMEWORK: &[(&str, &str)] = &[
    (
        "findBlocker returned NaN or an infinite depth at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. Return a \"no blocker\" value there, and have PCSS treat it as lit.",
        "在 {:.1}% 的着色像素上，findBlocker 返回了 NaN 或无穷大的深度：它用找到的遮挡物个数去除深度之和，而光没有被挡住的地方这个个数是 0。请在那里返回一个“没有遮挡物”的值，并让 PCSS 把它当作受光。",
    ),
    (
        "{:.1}% of the shaded pixels got a visibility that is NaN or infinite. The usual cause: findBlocker divides the blockers' depth sum by their count when no blocker was found (0 / 0).",
        "{:.1}% 的着色像素得到的可见度是 NaN 或无穷大。常见原因：没有找到遮挡物时，findBlocker 仍用遮挡物个数去除深度之和（0 / 0）。",
    ),
    (
        "{:.1}% of the visibilities your shader returned lie outside [0, 1], from {:.2} to {:.2}. Visibility is the share of the light a point sees: a filter must divide its sum of 0/1 tests by the number of tests it summed, not by another count (PCF_NUM_SAMPLES - 8), and not leave it undivided.",
        "你的着色器返回的可见度中有 {:.1}% 超出了 [0, 1]，范围从 {:.2} 到 {:.2}。可见度是一个点能看到的光的比例：滤波器必须用它实际求和的测试次数去除 0/1 测试结果之和，而不是用别的个数（PCF_NUM_SAMPLES - 8），也不能不除。",
    ),
    (
        "Your visibility is shadowlab's times {:.3} (divided once more by {:.1}): a fully lit point reads {:.3}, not 1. Visibility is the share of the light a point sees, so where all of it is seen it must be 1: the sum of the 0/1 tests is divided twice (is {:.1} one of your sample counts?), or by a count other than the number of tests summed (PCF_NUM_SAMPLES * 2), or multiplied by a weight.",
        "你的可见度是 shadowlab 的 {:.3} 倍（多除了一次 {:.1}）：完全受光的点读出来是 {:.3}，而不是 1。可见度是一个点能看到的光的比例，所以能看到全部光的地方必须是 1：0/1 测试结果之和被除了两次（{:.1} 是不是你的某个采样数？），或者除以的不是实际求和的测试次数，而是别的个数（PCF_NUM_SAMPLES * 2），或者乘上了一个权重。",
    ),
    (
        "Where the ground truth is in full shadow, your visibility averages {:.2}: the shadows are missing. The lookups do not meet the blockers: coordinates in the wrong space (NDC in [-1, 1] where the map wants [0, 1]), depths compared in different units, or the wrong matrix.",
        "在真实结果处于全影的地方，你的可见度平均为 {:.2}：阴影不见了。查询没有碰到遮挡物：坐标用错了空间（贴图需要 [0, 1]，却给了 [-1, 1] 的 NDC）、比较的两个深度单位不同，或者用错了矩阵。",
    ),
    (
        "Where no point of the light reaches (the ground truth is 0), your visibility averages {:.2}. A filter that reaches far past the blocker does this: a light size in world units used as a size in uv (or texels).",
        "在光源上没有任何一点能照到的地方（真实结果为 0），你的可见度平均为 {:.2}。滤波范围远远超出遮挡物时就会这样：把以世界单位表示的光源大小当成了 uv（或纹素）大小。",
    ),
    (
        "The ground truth has {} pixels in a penumbra, your shadows {}: the edges are as sharp as a hard shadow. Usually the filter is under a texel wide (a light size or filter radius far too small for the map), or the penumbra estimate is lost before filtering.",
        "真实结果有 {} 个像素处于半影中，你的阴影只有 {} 个：边缘和硬阴影一样锐利。通常是滤波器不到一个纹素宽（光源大小或滤波半径相对贴图太小），或者半影估计在滤波之前就丢失了。",
    ),
    (
        "{:.1}% of the surfaces that face the light and are fully lit in the ground truth are dark in yours: shadow acne, the surface shadowing itself. Compare with a bias (the receiver's depth minus a small amount), or a larger one.",
        "在朝向光源、且在真实结果中完全受光的表面里，有 {:.1}% 在你的结果中是暗的：这是阴影失真（shadow acne），表面遮挡了自己。比较时加上偏移（接收点深度减去一个小量），或者把偏移加大。",
    ),
    (
        "{:.1}% of the picture changes when the shadow map starts white instead of 0. The framework never clears its map: texels no object covers read depth 0, which counts as a blocker. Your lookups land there (outside [0, 1] uv, or far from the pixel).",
        "把阴影贴图的初值从 0 改成白色后，画面有 {:.1}% 发生了变化。作业框架从不清空它的贴图：没有物体覆盖的纹素读出来深度是 0，会被当成遮挡物。你的查询落在了那里（uv 超出 [0, 1]，或离像素太远）。",
    ),
    ("Your homework", "你的作业"),
    (
        "watching the file: save it in your editor and the check runs again ({} reloads)",
        "正在监视这个文件：在编辑器里保存后会重新检查（已重新载入 {} 次）",
    ),
    (
        "handed over, not watched: after an edit, drop the file again",
        "文件是拖进网页的副本，不会被监视：修改后请重新拖入",
    ),
    ("does not compile", "无法编译"),
    ("the picture is the last version that compiled", "画面是最后一个能编译的版本"),
    ("the camera view shows", "相机视图显示"),
    ("your shader", "你的着色器"),
    ("shadowlab's", "shadowlab 的"),
    ("your visibility", "你的可见度"),
    ("difference", "差异"),
    ("checking…", "检查中…"),
    ("checking the new version…", "正在检查新版本…"),
    ("functions that ran", "运行过的函数"),
    ("visibility from", "可见度来自"),
    ("compared with shadowlab's", "对比的 shadowlab 技术"),
    ("mean |difference| to shadowlab's", "与 shadowlab 的平均绝对差"),
    ("mean |difference| to the ground truth", "与真实结果的平均绝对差"),
    ("NaN or infinite visibility", "NaN 或无穷大的可见度"),
    ("mean visibility where fully lit", "完全受光处的平均可见度"),
    ("mean visibility in the umbra", "本影中的平均可见度"),
    ("penumbra pixels (ground truth)", "半影像素数（真实结果）"),
    ("No findings: your shadows match the ground truth.", "没有发现问题：你的阴影与真实结果一致。"),
    ("could not open the shader", "无法打开着色器"),
    ("at the probe (pixel {}, {})", "探针处（像素 {}, {}）"),
    ("not called", "未调用"),
    ("penumbra width (world units)", "半影宽度（世界单位）"),
    ("{:.2}, ground truth {:.2}", "{:.2}，真实结果 {:.2}"),
    ("your shader, map cleared to white", "你的着色器（贴图清成白色）"),
];
