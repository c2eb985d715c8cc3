//! The homework check's findings and panel in Simplified Chinese.

/// English -> Chinese, for every finding's explanation.
pub(super) const HOMEWORK: &[(&str, &str)] = &[
    (
        "findBlocker returned NaN or an infinite depth at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. Return a \"no blocker\" value there, and have PCSS treat it as lit.",
        "在 {:.1}% 的着色像素上，findBlocker 返回了 NaN 或无穷大的深度：它用找到的遮挡物个数去除深度之和，而光没有被挡住的地方这个个数是 0。请在那里返回一个“没有遮挡物”的值，并让 PCSS 把它当作受光。",
    ),
    (
        "{} returned NaN or infinity at {:.1}% of the shaded pixels, and the visibility with it: it divides by something that is 0 there (a count of taps, a sum of weights, a depth). Count what the division means, and give the case where it is 0 a value of its own.",
        "{} 在 {:.1}% 的着色像素上返回了 NaN 或无穷大，可见度也随之如此：它除以的量在那里为 0（采样点的计数、权重之和或某个深度）。想清楚这个除法的含义，并为除数为 0 的情况单独给出一个值。",
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
    (
        "findBlocker's search radius is wrong: it is not a finite number at {:.1}% of the receivers and under half a texel at {:.1}%. On an orthographic map similar triangles make it nearly the same for every receiver, w_light (z_r - z_near) / z_r: a near plane in world units mixed with a depth in [0, 1], or a clip-space depth taken for a distance, makes it negative, zero or infinite, and the search reads anywhere.",
        "findBlocker 的搜索半径是错的：在 {:.1}% 的接收点上它不是有限的数，在 {:.1}% 的接收点上不到半个纹素。在正交贴图上，相似三角形使它对每个接收点都几乎相同，即 w_light (z_r - z_near) / z_r：把以世界单位表示的近平面和 [0, 1] 的深度混在一起，或把裁剪空间的深度当成距离，会使它变成负数、零或无穷大，搜索就会读到任意位置。",
    ),
    (
        "findBlocker's search radius swings with the receiver's depth, from {:.1} to {:.1} texels over this scene (10th to 90th percentile), where similar triangles on an orthographic map keep it nearly the same, w_light (z_r - z_near) / z_r with z_near the near plane's depth, 0. A near plane in world units mixed with a depth in [0, 1], or a perspective formula (near / z), does this.",
        "findBlocker 的搜索半径随接收点的深度大幅变化，在这个场景中从 {:.1} 到 {:.1} 个纹素（第 10 到第 90 百分位）；而在正交贴图上，相似三角形使它几乎不变，即 w_light (z_r - z_near) / z_r，其中近平面的深度 z_near 为 0。把以世界单位表示的近平面和 [0, 1] 的深度混在一起，或使用透视的公式（near / z），就会这样。",
    ),
    (
        "Hidden today by this scene: the search still reaches the blockers that shape each penumbra, and the penumbrae follow similar triangles; another scene or light shows it:",
        "在这个场景中暂时看不出来：搜索仍能找到决定每个半影的遮挡物，半影也符合相似三角形；换一个场景或光源就会显现：",
    ),
    (
        "PCSS filters over a radius that is not a number at {:.1}% of the pixels it filters: the penumbra estimate (z_r - z_blocker) / z_blocker is infinite where the blocker depth is 0, and the taps read texels nobody chose. Where findBlocker finds no blocker, return a value PCSS recognises (-1, or 1 with a test) and return full light before estimating.",
        "在 PCSS 滤波的像素中，有 {:.1}% 的滤波半径不是一个数：遮挡物深度为 0 时，半影估计 (z_r - z_blocker) / z_blocker 是无穷大，采样会读到谁也没有选定的纹素。findBlocker 找不到遮挡物时，请返回一个 PCSS 能识别的值（-1，或者 1 并加以判断），并在估计半影之前直接返回完全受光。",
    ),
    (
        "Test blockers as nearer than the receiver by more than a bias (depth + bias < z_receiver): a bias the other way, or none, lets the receiver's own texels in, and the penumbra shrinks.",
        "判断遮挡物时，应要求它比接收点近出一个偏移量以上（depth + bias < z_receiver）：偏移方向反了或没有偏移，接收点自己的纹素就会被算进来，半影随之变窄。",
    ),
    (
        "Depth does not come back from the map as it went in: even with every bit kept, the depth unpacked where a lit surface looks itself up differs from its own by {:.4} (typical) to {:.4} in [0, 1] depth, at {:.0}% of them. Your pack (shadowFragment.glsl) must take each channel's carry out of the one before (rgbaDepth -= rgbaDepth.gbaa * bitMask), in the same base as your unpack.",
        "从贴图读回的深度与写入的不一致：即使保留每一位，受光表面查询自己时解包出的深度也与它自身的深度相差 {:.4}（典型值）到 {:.4}（[0, 1] 深度），这样的表面占 {:.0}%。你的 pack（shadowFragment.glsl）必须从前一个通道中减去后一个通道的进位（rgbaDepth -= rgbaDepth.gbaa * bitMask），并且与 unpack 使用相同的基数。",
    ),
    (
        "{}'s taps are not spread over a disk around the receiver: their mean lies {:.0}% of their spread away from it, and they stretch along one line, the same at every pixel, {:.0}% of the way from a disk to a line. Offsets added to the previous tap's position walk away from the receiver or back and forth along a line, and a fixed seed turns every pixel's pattern the same way (the template's 20 samples in 10 rings lie on one line): offset the receiver's own uv by each sample, with a seed that changes from pixel to pixel.",
        "{} 的采样点没有分布在以接收点为中心的圆盘上：它们的均值偏离接收点，距离为其分布范围的 {:.0}%；而且它们沿同一条直线拉长，每个像素都一样，从圆盘到直线的程度为 {:.0}%。把偏移加到上一个采样点的位置上，采样就会离接收点越走越远，或沿一条直线来回；固定的随机种子又让每个像素的图案朝同一方向转（模板的 20 个样本、10 圈正好落在一条直线上）：应该用每个样本偏移接收点自己的 uv，并让种子随像素变化。",
    ),
    (
        "findBlocker returns NaN at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. PCSS catches it before it reaches the picture, so nothing shows today; return a \"no blocker\" value there all the same.",
        "在 {:.1}% 的着色像素上，findBlocker 返回了 NaN：它用找到的遮挡物个数去除，而光没有被挡住的地方这个个数是 0。PCSS 在它影响画面之前拦住了它，所以现在看不出来；但仍应在那里返回一个“没有遮挡物”的值。",
    ),
    (
        "Your PCSS draws hard shadows: even the {}'s penumbra is {:.2} world units wide, under the {:.2} a texel or a pixel covers here. The filter is under a texel wide: a light size or filter radius far too small for the map, or the penumbra estimate lost before filtering.",
        "你的 PCSS 画出的是硬阴影：即使是 {} 的半影也只有 {:.2} 个世界单位宽，小于这里一个纹素或一个像素覆盖的 {:.2}。滤波范围不到一个纹素：光源大小或滤波半径对这张贴图来说太小了，或者半影估计在滤波之前就丢失了。",
    ),
    (
        "Your penumbrae do not widen with the distance from blocker to receiver as similar triangles say (w = w_light (d_r - d_b) / d_b): under the slabs they are {} world units wide (where a light's disk explains their shape at all), and no one light width fits them. Contact hardening is what PCSS is for: check the blocker search (its radius, and what it counts as a blocker) and the penumbra's formula.",
        "你的半影没有像相似三角形所说的那样随遮挡物到接收点的距离变宽（w = w_light (d_r - d_b) / d_b）：几块板下面的半影宽度分别为 {} 个世界单位（仅在光源圆盘能解释其形状的地方），没有一个光源宽度能同时符合它们。接触硬化正是 PCSS 的目的：请检查遮挡物搜索（它的半径，以及它把什么算作遮挡物）和半影的公式。",
    ),
    (
        "Hidden today by the framework's packing (its 256-vs-255 rounding reads every depth a little too far, a bias of its own); it shows as soon as depth is kept exactly:",
        "目前被框架的深度打包掩盖了（它 256 对 255 的舍入让每个深度都读得稍远一点，相当于自带了一个偏移）；一旦深度被精确保存，它就会显现：",
    ),
    (
        "The {} casts no shadow: a blocker {:.1} world units above the floor (along the light) does not shadow it, while one {:.1} above does. Your depth bias is that large: shadows come loose from what casts them (peter panning).",
        "{} 没有投下阴影：（沿光线方向）离地面 {:.1} 个世界单位的遮挡物没有在地面上留下阴影，而离地面 {:.1} 的却有。你的深度偏移就有这么大：阴影与投射它的物体脱开了（彼得潘现象，悬浮）。",
    ),
    (
        "Your light's depth runs over {:.0} world units, so that is a bias of {:.4} to {:.4} in [0, 1] depth.",
        "你的光源深度范围是 {:.0} 个世界单位，所以这相当于 [0, 1] 深度中 {:.4} 到 {:.4} 的偏移。",
    ),
    ("`{}` (line {}{}: {:.1} world units)", "`{}`（第 {} 行{}：{:.1} 个世界单位）"),
    (
        "No constant in your depth tests is that large (the largest, `{}` on line {}, is {:.1} world units): look for a bias your code computes, or for what else loses the shadow (a filter much wider than the blocker dilutes it).",
        "你的深度测试里没有这么大的常数（最大的 `{}` 在第 {} 行，为 {:.1} 个世界单位）：去找代码计算出来的偏移，或者别的让阴影消失的原因（比遮挡物宽得多的滤波会把它冲淡）。",
    ),
    (
        "In your shader: {}. A bias of a texel's depth slope or two is enough; with this light that is far under 1 world unit.",
        "在你的着色器中：{}。偏移取一两个纹素的深度斜率就够了；对这个光源而言远小于 1 个世界单位。",
    ),
    (
        "{:.1}% of the surfaces that face the light and are fully lit in the ground truth are dark in yours: shadow acne, the surface shadowing itself. Compare with a bias (the receiver's depth minus a small amount), or a larger one; a bias that is 0 where a surface faces the light squarely (max(c (1 - N.L), 0)) leaves acne there.",
        "在真实结果中朝向光源且完全受光的表面里，有 {:.1}% 在你的画面中是暗的：这是阴影失真（shadow acne），表面遮挡了自己。比较时请加上偏移（接收点的深度减去一个小量），或把偏移加大；在表面正对光源的地方为 0 的偏移（max(c (1 - N.L), 0)）会在那里留下失真。",
    ),
    (
        "Your CalcLightMVP does not place the objects as the framework does: {}. The light pass and the lookups both use that matrix, so the shadows fall where the objects are not.",
        "你的 CalcLightMVP 放置物体的方式与框架不同：{}。光源的渲染和阴影查询都使用这个矩阵，所以阴影落在了物体不在的地方。",
    ),
    (
        "{:.1}% of what the camera sees lies outside your light's frustum, most of it on the {} ({:.0}% of it): the map has nothing there, and its lookups read outside [0, 1]. Make the orthographic box wide and deep enough for the scene (left/right/bottom/top, near and far).",
        "相机看到的内容中有 {:.1}% 位于光源视锥之外，大部分在 {} 上（占它的 {:.0}%）：阴影贴图在那里什么也没有，查询读到的是 [0, 1] 之外。请把正交盒子设得足够宽、足够深，能容下整个场景（left/right/bottom/top，以及 near 和 far）。",
    ),
    (
        "the objects' translation and scale are never applied: every object is drawn into the map where its model file puts it, at the origin and unscaled",
        "物体的平移和缩放从未被应用：每个物体都按它模型文件中的位置画进贴图，位于原点且没有缩放",
    ),
    (
        "the scale is applied after the translation, so the translation is scaled too: mat4.translate, then mat4.scale, on the same matrix (or T * S)",
        "缩放是在平移之后应用的，所以平移也被缩放了：应在同一个矩阵上先 mat4.translate，再 mat4.scale（即 T * S）",
    ),
    (
        "the objects are translated by the light's position (this.lightPos) instead of their own translation: the template's own line, kept",
        "物体被光源的位置（this.lightPos）平移，而不是它们自己的平移：这是模板里原有的那一行，没有改掉",
    ),
    (
        "the matrix is not projection * view * translate * scale",
        "这个矩阵不是 projection * view * translate * scale",
    ),
    (
        "findBlocker reads the map only at the receiver's own texel at {:.0}% of the pixels (every read within half a texel of it), while PCSS's filter then reaches up to {:.1} texels: the search sees no blocker beside the receiver, so the penumbra starts only where the receiver's own texel is blocked.",
        "在 {:.0}% 的像素上，findBlocker 只在接收点自己的纹素上读取阴影图（每次读取都在半个纹素之内），而 PCSS 随后的滤波可达 {:.1} 个纹素：搜索看不到接收点旁边的遮挡物，半影只从接收点自己的纹素被遮挡处才开始。",
    ),
    (
        "Line {} reads `{}` before anything fills it (nothing that writes it runs before findBlocker): every offset is 0. Fill the samples at the start of findBlocker.",
        "第 {} 行在任何代码填充 `{}` 之前就读取了它（在 findBlocker 之前没有运行写它的函数）：每个偏移都是 0。请在 findBlocker 开头生成采样点。",
    ),
    (
        "findBlocker searches {:.1} texels around the receiver, but at {:.0}% of the points under a blocker the blockers that shade the receiver lie farther, up to {:.1} texels away: the light PCSS's filter behaves as ({:.1} texels wide: its radius r = (w_light / 2) (d_r - d_b) / d_b solved with findBlocker's own d_b) reaches the blockers' plane within (w_light / 2) (d_r - d_b) / d_r of the receiver. Search the light's half width (in the map's uv), which covers every blocker depth.",
        "findBlocker 在接收点周围搜索 {:.1} 个纹素，但在遮挡物下 {:.0}% 的点上，遮住接收点的遮挡物离得更远，最远 {:.1} 个纹素：PCSS 的滤波所相当的光源（宽 {:.1} 个纹素：由半径 r = (w_light / 2) (d_r - d_b) / d_b 和 findBlocker 自己的 d_b 解出）在遮挡物平面上覆盖到离接收点 (w_light / 2) (d_r - d_b) / d_r 的范围。请搜索光源的半宽（以阴影图的 uv 计），它能覆盖任何遮挡深度。",
    ),
    (
        "That light is {:.1} world units wide. The blockers the search misses are the ones that shade the outer penumbra: it ends too soon, hard, where the search stops.",
        "这个光源宽 {:.1} 个世界单位。搜索漏掉的遮挡物正是遮住外侧半影的那些：半影在搜索停止处过早地、生硬地结束。",
    ),
    (
        "findBlocker returns {:.3} (the median) at {:.0}% of the points where most of the disk it searched is blocked, where the blockers' average depth is {:.3} (the median, in [0, 1] depth, from shadowlab's map over the same disk).",
        "findBlocker 返回 {:.3}（中位数），这发生在其搜索圆盘大部分被遮挡的点中的 {:.0}%，而那里遮挡物的平均深度是 {:.3}（中位数，[0, 1] 深度，取自 shadowlab 阴影图上的同一个圆盘）。",
    ),
    (
        "That is the return on line {}, taken whenever the test on line {} holds: it holds where it should not.",
        "那是第 {} 行的 return，只要第 {} 行的条件成立就会执行：它在不该成立的地方成立了。",
    ),
    ("That is the return on line {}.", "那是第 {} 行的 return。"),
    (
        "PCSS then sizes the penumbra from a depth that is no blocker's: it no longer widens with the distance from blocker to receiver.",
        "于是 PCSS 用一个不属于任何遮挡物的深度来估计半影：半影不再随遮挡物到接收点的距离变宽。",
    ),
    (
        "PCSS hands its filter a radius that collapses at {:.0}% of the points under a blocker (findBlocker's own blockers in front of the receiver): there it is under a texel where the same light (r d_b / (d_r - d_b), the light's half width, {:.1} texels at the 90th percentile) asks for two or more. By similar triangles r = (w_light / 2) (d_r - d_b) / d_b with d_r the receiver's own depth: it is small only where the blocker touches the receiver.",
        "在遮挡物下 {:.0}% 的点上（findBlocker 自己找到了接收点前方的遮挡物），PCSS 交给滤波的半径塌缩了：同一光源（r d_b / (d_r - d_b)，即光源半宽，第 90 百分位为 {:.1} 个纹素）要求两个纹素以上的地方，它不到一个纹素。按相似三角形 r = (w_light / 2) (d_r - d_b) / d_b，其中 d_r 是接收点自己的深度：只有遮挡物贴着接收点时它才小。",
    ),
    (
        "PCSS reads the map itself on line {}: a depth read at the receiver's uv is the nearest occluder's, not the receiver's; use the receiver's own depth (coords.z).",
        "PCSS 在第 {} 行自己读取了阴影图：在接收点 uv 处读到的深度是最近遮挡物的，不是接收点的；请用接收点自己的深度（coords.z）。",
    ),
    (
        "On screen, the part of each penumbra inside the hard shadow's edge is dark and hard.",
        "画面上，每个半影在硬阴影边缘以内的部分又黑又硬。",
    ),
    (
        "Your PCSS filters as a light {:.3} wide in the map's uv ({:.1} world units; the whole map is 1, {:.0} world units).",
        "你的 PCSS 的滤波相当于一个在阴影图 uv 中宽 {:.3} 的光源（{:.1} 个世界单位；整张图为 1，即 {:.0} 个世界单位）。",
    ),
    (
        "Your PCSS filters as a light {:.3} wide in the map's uv (the whole map is 1).",
        "你的 PCSS 的滤波相当于一个在阴影图 uv 中宽 {:.3} 的光源（整张图为 1）。",
    ),
    ("That is `{}` on line {}.", "那就是 `{}`（第 {} 行）。"),
    (
        "Your depth tests use a bias your code computes: `{} = {}` (line {}, {}). It comes to at least {:.4} in [0, 1] depth here; a bias of a texel's depth slope or two is enough, far under 1 world unit with this light.",
        "你的深度测试用了代码计算出来的偏移：`{} = {}`（第 {} 行，{}）。在这里它至少是 [0, 1] 深度中的 {:.4}；偏移取一两个纹素的深度斜率就够了，对这个光源而言远小于 1 个世界单位。",
    ),
    (
        "it lies beyond your far plane, so its own depth is over 1 and every texel is in front of it",
        "它在你的远平面之外，自身深度大于 1，任何纹素都在它前面",
    ),
    (
        "it lies outside your box's sides, and its lookups wrap (REPEAT) to texels the floor never wrote, which read 0: a blocker at the light",
        "它在你的正交盒侧面之外，查找时环绕（REPEAT）到地面从未写入的纹素，读出 0：相当于光源处的遮挡物",
    ),
    (
        "On the framework's own scene your light leaves {:.0}% of the floor dark: the band from z = {:.0} to {:.0} (x {:.0} to {:.0} world units; the floor spans z -142 to 82 and x -112 to 112, as the framework's engine.js lays it out). There {}. shadowlab's check scene fits inside your frustum, so nothing else shows it; in your own page it is a black band across the floor. Make the box wide and deep enough for the framework's floor (left/right/bottom/top, near and far).",
        "在框架自己的场景中，你的光源让 {:.0}% 的地面变黑：z 从 {:.0} 到 {:.0} 的一条带（x 从 {:.0} 到 {:.0} 个世界单位；按框架 engine.js 的布置，地面范围是 z -142 到 82、x -112 到 112）。那里{}。shadowlab 的检查场景完全在你的视锥内，所以别处看不出来；在你自己的页面里，它是横跨地面的一条黑带。请把正交盒做得足够宽、足够深，盖住框架的地面（left/right/bottom/top，以及 near 和 far）。",
    ),
    (
        "On the framework's own floor your light puts the far end (z = {:.0} to {:.0} world units, {:.0}% of the floor) at depth {:.3} and over. There the framework's pack, stored in 8-bit channels (k/255) and read back with 1/256 steps, reads every depth up to {:.4} too near, more than your bias of {:.4}: the floor shadows itself (acne) in your page, though shadowlab's check scene, nearer the light, shows nothing. A bias of {:.4} or more, a far plane nearer the scene (depths under 0.5 read a little too far instead), or a pack and unpack in base 255 remove it.",
        "在框架自己的地面上，你的光源把远端（z 从 {:.0} 到 {:.0} 个世界单位，占地面的 {:.0}%）放在 {:.3} 及以上的深度。在那里，框架的 pack 存进 8 位通道（k/255）、再按 1/256 的步长读回，会把每个深度读近最多 {:.4}，超过了你的偏移 {:.4}：在你的页面里地面会自己遮挡自己（阴影痤疮），而离光源更近的 shadowlab 检查场景看不出来。偏移取 {:.4} 或更大、把远平面移近场景（深度小于 0.5 时反而读得稍远），或者 pack 和 unpack 都用 255 为基数，就能消除它。",
    ),
    (
        "Your `{}`{} does not give back the depth your pack stored: from a map that keeps every bit, findBlocker returns the blockers' depth {:.4} {} (the median, in [0, 1] depth; up to {:.4}) where the whole disk it searched is blocked. Unpack every channel with the weights your pack used (dot(rgbaDepth, vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0)) for the framework's pack). A receiver reads its own depth off by as much: with a smaller bias it shadows itself.",
        "你的 `{}`{} 没有还原出 pack 存进去的深度：即使阴影图保留了每一位，在搜索圆盘整个被遮挡的地方，findBlocker 返回的遮挡物深度也偏了 {:.4}，{}（中位数，[0, 1] 深度；最多 {:.4}）。请用与 pack 相同的权重解包每个通道（对框架的 pack 是 dot(rgbaDepth, vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0))）。接收点读自己的深度也会偏这么多：偏移再小一点它就会遮挡自己。",
    ),
    (" (line {})", "（第 {} 行）"),
    ("too near", "偏近"),
    ("too far", "偏远"),
    (
        "Hidden today by your bias (it shows as soon as the bias is smaller):",
        "今天被你的偏移掩盖了（偏移再小一点就会显现）：",
    ),
    (
        "On the framework's own scene {:.0}% of the floor lies outside your light's frustum (z = {:.0} to {:.0}, x {:.0} to {:.0} world units; the floor spans z -142 to 82 and x -112 to 112, as the framework's engine.js lays it out). Your line {} takes whatever lies outside the map as lit, so there is no black band, but no shadow can fall there: an object standing there casts none. Make the frustum wide and deep enough for the framework's floor.",
        "在框架自己的场景中，{:.0}% 的地面落在你的光源视锥之外（z 从 {:.0} 到 {:.0}、x 从 {:.0} 到 {:.0} 个世界单位；按框架 engine.js 的布置，地面范围是 z -142 到 82、x -112 到 112）。你的第 {} 行把阴影贴图之外的一切当作被照亮，所以不会出现黑带，但那里也不会落下任何阴影：站在那里的物体不投影。请把视锥做得足够宽、足够深，盖住框架的地面。",
    ),
    ("your page never calls CalcLightMVP itself", "你的页面自己从不调用 CalcLightMVP"),
    (
        "your page calls CalcLightMVP only while it loads ({}), never in a frame",
        "你的页面只在加载时调用 CalcLightMVP（{}），从不在某一帧里调用",
    ),
    (
        "your page calls CalcLightMVP at {}, but not for these draws",
        "你的页面在 {} 调用 CalcLightMVP，但不是为这些绘制调用的",
    ),
    (
        "your page calls CalcLightMVP at {}, for another light",
        "你的页面在 {} 调用 CalcLightMVP，算的是另一盏光源",
    ),
    (
        "From {:.1} s of your page's animation the light has moved, but the uLightMVP its draws get is the one of where it was when the page loaded: {}. The light pass and the lookups keep the old light while the shading follows the new one, so the shadows do not move with it.",
        "从你页面动画的第 {:.1} 秒起，光源已经移动了，但绘制时拿到的 uLightMVP 仍是页面加载时它所在位置的矩阵：{}。光源 pass 和查询还停在旧的光源，着色却跟着新的光源，所以阴影不会随它移动。",
    ),
    (
        "From {:.1} s of your page's animation {} moves (its uModelMatrix changes), but its uLightMVP still places it where it was loaded: {}. Its shadow stays where it was, and it shadows itself as if it had not moved.",
        "从你页面动画的第 {:.1} 秒起，{} 在移动（它的 uModelMatrix 在变），但它的 uLightMVP 仍把它放在加载时的位置：{}。它的阴影停在原处，它对自己的遮挡也像没有动过一样。",
    ),
    (
        "Compute uLightMVP again each frame, after the light or the object moves, for both passes.",
        "请在光源或物体移动之后，每一帧为两个 pass 重新计算 uLightMVP。",
    ),
    (
        "Your page never draws with this light's matrix: no uniform of any draw holds its CalcLightMVP ({}). Its shadow map is drawn with another light's matrix, or not at all, so the shadows your page shows for it are another light's. Give each light its own materials (or uniforms) with its own uLightMVP and its own map, for both passes. What shadowlab shows for this light is what your shaders would do if it were drawn.",
        "你的页面从未用这盏光源的矩阵绘制：没有任何一次绘制的 uniform 里有它的 CalcLightMVP（{}）。它的阴影贴图是用另一盏光源的矩阵画的，或者根本没画，所以你的页面为它显示的阴影其实是另一盏光源的。请为每盏光源准备自己的材质（或 uniform），带上它自己的 uLightMVP 和自己的阴影贴图，两个 pass 都要。shadowlab 为这盏光源显示的，是假如它被画出来时你的着色器会给出的结果。",
    ),
    (" (the framework's)", "（框架自带的）"),
    (
        "PCSS's filter radius r does not follow similar triangles: the light's half width it implies under blockers, r d_b / (d_r - d_b), is no one light's. It goes from {:.1} to {:.1} texels (10th to 90th percentile) and follows d_r^{:.2} d_b^{:.2} (R^2 {:.2}; receivers' depths {:.3} to {:.3}), where a light's is the same everywhere.",
        "PCSS 的滤波半径 r 不符合相似三角形：它在遮挡物下隐含的光源半宽 r d_b / (d_r - d_b) 不属于任何一盏光源。它从 {:.1} 变到 {:.1} 个纹素（第 10 到第 90 百分位），随 d_r^{:.2} d_b^{:.2} 变化（R^2 {:.2}；接收点深度 {:.3} 到 {:.3}），而一盏光源的半宽处处相同。",
    ),
    (
        "It is divided by the receiver's depth as well: r = (w/2) (d_r - d_b) / (d_b d_r). That is the perspective light's near / z_r of the NVIDIA sample; an orthographic light's [0, 1] depth is a distance along the light, and its map's uv does not shrink with it.",
        "它还多除了一次接收点深度：r = (w/2) (d_r - d_b) / (d_b d_r)。这是 NVIDIA 示例里透视光源的 near / z_r；正交光源的 [0, 1] 深度就是沿光线方向的距离，它的贴图 uv 不会随深度缩小。",
    ),
    (
        "It is divided by the receiver's depth instead of the blocker's: r = (w/2) (d_r - d_b) / d_r, the right radius times d_b / d_r: right where a blocker touches its receiver, too narrow the higher the blocker.",
        "它除的是接收点深度而不是遮挡物深度：r = (w/2) (d_r - d_b) / d_r，即正确半径乘以 d_b / d_r：遮挡物贴着接收点时正确，遮挡物越高就越窄。",
    ),
    (
        "It is not divided by the blocker's depth: r = (w/2) (d_r - d_b).",
        "它没有除以遮挡物深度：r = (w/2) (d_r - d_b)。",
    ),
    ("Line {} divides by the receiver's depth: `{}`.", "第 {} 行除以了接收点深度：`{}`。"),
    (
        "By similar triangles r = (w_light / 2) (d_r - d_b) / d_b, nothing more; on screen the penumbrae are not those of one light, wider or narrower with the receiver's distance.",
        "按相似三角形 r = (w_light / 2) (d_r - d_b) / d_b，别无其他因子；屏幕上的半影不是同一盏光源投下的，会随接收点的距离变宽或变窄。",
    ),
    (
        "The slabs' penumbrae are those of a light about {:.1} world units wide, where your {} on line {} is {}.",
        "平板下的半影相当于一盏约 {:.1} 个世界单位宽的光源投下的，而你的 {}（第 {} 行）是 {}。",
    ),
    (
        "Where no point of the light reaches (the ground truth is 0), your visibility is {:.2} at {:.0}% of the points: a tap (or a point) that finds a blocker counts {:.2} there, not 0.",
        "在光源任何一点都照不到的地方（真实结果为 0），你的可见度是 {:.2}（占这些点的 {:.0}%）：找到遮挡物的采样（或点）在那里算作 {:.2}，而不是 0。",
    ),
    ("That is `{}` on line {}, in {}.", "即 `{}`（第 {} 行，在 {} 中）。"),
    (
        "A shadow is where the light's direct light does not arrive: visibility 0. Light that still reaches a shadowed point (ambient) belongs in the shading, where it lights the umbra of every light alike.",
        "阴影就是光源的直接光照不到的地方：可见度为 0。仍能照到阴影中点的光（环境光）应放在着色里，在那里它对每盏光源的本影一视同仁。",
    ),
    (
        "PCSS filters with one radius whatever the blocker: {:.1} texels at {:.0}% of the points under blockers, where (d_r - d_b) / d_b goes from {:.2} to {:.2}.",
        "无论遮挡物如何，PCSS 都用同一个半径滤波：{:.1} 个纹素，在遮挡物下 {:.0}% 的点上都是如此，而 (d_r - d_b) / d_b 从 {:.2} 变到 {:.2}。",
    ),
    (
        "PCSS's filter radius does not follow the blocker: under blockers, where (d_r - d_b) / d_b goes from {:.2} to {:.2}, the radius goes as its power {:.2}, where similar triangles make it 1.",
        "PCSS 的滤波半径不随遮挡物变化：在遮挡物下，(d_r - d_b) / d_b 从 {:.2} 变到 {:.2}，半径与它的 {:.2} 次方成正比，而相似三角形要求是 1 次方。",
    ),
    ("It follows the receiver's depth alone (R^2 {:.2}).", "它只随接收点深度变化（R^2 {:.2}）。"),
    (
        "Line {} computes `{}` from the blocker's depth, but nothing reads it: the filter is sized without it.",
        "第 {} 行用遮挡物深度算出了 `{}`，但之后没有任何地方读取它：滤波半径与它无关。",
    ),
    (
        "By similar triangles the filter radius is (w_light / 2) (d_r - d_b) / d_b: it is what makes a shadow hard where its blocker touches the receiver and soft where the blocker is high. Without it PCSS is PCF with a radius of its own.",
        "按相似三角形，滤波半径是 (w_light / 2) (d_r - d_b) / d_b：正是它让阴影在遮挡物贴着接收面处变硬、在遮挡物高处变软。没有它，PCSS 就只是用自定半径的 PCF。",
    ),
    (
        "findBlocker searches {:.1} texels around the receiver, a light's half width, but PCSS's filter behaves as a light {:.1} times narrower: its radius r = (w_light / 2) (d_r - d_b) / d_b, solved with findBlocker's own d_b, gives a half width of {:.1} texels. One light has one size in uv; the penumbrae come out {:.1} times narrower than the light the search looks for.",
        "findBlocker 在接收点周围 {:.1} 个纹素内搜索，这是一盏光源的半宽；但 PCSS 的滤波相当于一盏窄 {:.1} 倍的光源：用 findBlocker 自己返回的 d_b 解 r = (w_light / 2) (d_r - d_b) / d_b，得到的半宽是 {:.1} 个纹素。一盏光源在 uv 中只有一个大小；半影比搜索所针对的光源窄了 {:.1} 倍。",
    ),
    (
        "In world units: a light {:.1} wide for the search, {:.1} for the filter.",
        "换成世界单位：搜索按 {:.1} 宽的光源，滤波按 {:.1} 宽的光源。",
    ),
    (
        "Line {} turns the search's radius into uv with `/ {}`, line {} the filter's with `/ {}`: `{}`. Use the one that matches the unit the radius is in.",
        "第 {} 行用 `/ {}` 把搜索半径换成 uv，第 {} 行却用 `/ {}` 换算滤波半径：`{}`。应按半径本身的单位选用换算。",
    ),
    (
        "findBlocker counts the receiver as its own blocker: where nothing blocks the disk it searched, it returns the receiver's own depth at {:.0}% of the points, and where part of the disk is blocked its average lies {:.0}% of the way from the blockers' depth to the receiver's.",
        "findBlocker 把接收点自己算成了遮挡物：在搜索的圆盘内没有任何遮挡的地方，它在 {:.0}% 的点上返回了接收点自己的深度；在圆盘被部分遮挡的地方，它的平均值从遮挡物的深度向接收点的深度偏移了 {:.0}%。",
    ),
    (
        "It compares nothing: every tap it reads goes into the average, the receiver's own surface with the blockers. Count a tap only where its depth is nearer than the receiver's by more than a bias.",
        "它没有做任何比较：读到的每个采样都计入平均值，接收点自己的表面和遮挡物混在一起。只有当采样深度比接收点近出一个偏移以上时才应计入。",
    ),
    (
        "Its bias, `{}` on line {} ({:.4} in [0, 1] depth), is far under how much the receiver's own surface, sloped to the light, moves in depth across the disk it searches: {:.4} (median). The nearer part of that surface passes the test as a blocker. A bias that grows with the slope and the search radius, or each tap compared with the receiver plane's depth there, keeps it out.",
        "它的偏移 `{}`（第 {} 行，[0, 1] 深度中为 {:.4}）远小于接收点自身表面（相对光源倾斜）在搜索圆盘内的深度变化：{:.4}（中位数）。这个表面中较近的部分就会作为遮挡物通过测试。让偏移随斜率和搜索半径增大，或者把每个采样与接收平面在该处的深度比较，就能把它排除。",
    ),
    (
        "Its bias, `{}` (line {}), is the wrong way round in line {}'s test, `{}`: it lets texels up to {:.4} behind the receiver count as blockers, so the receiver's own texels always do. Test depth + bias < z_receiver.",
        "它的偏移 `{}`（第 {} 行）在第 {} 行的测试 `{}` 中方向反了：比接收点还远 {:.4} 以内的纹素也被算作遮挡物，于是接收点自己的纹素总会被算进来。应判断 depth + bias < z_receiver。",
    ),
    (
        "Your light's map projects the scene along ({:.2}, {:.2}, {:.2}), {:.1} degrees from where the light looks, from its position to its focal point: ({:.2}, {:.2}, {:.2}). Shadows fall along the first while the shading is lit along the second. A view matrix is a rotation and a translation, and yours ({}) is not: a product summed into a matrix that starts as mat4.create(), the identity, instead of zeros has the identity added, for one.",
        "你的光源贴图沿 ({:.2}, {:.2}, {:.2}) 投影场景，与光源的朝向（从光源位置指向焦点）相差 {:.1} 度：({:.2}, {:.2}, {:.2})。阴影沿前者投下，着色却按后者照亮。视图矩阵应当是一个旋转加一个平移，而你的（{}）不是：例如把乘积累加进一个由 mat4.create() 创建的矩阵（它是单位矩阵而不是零矩阵），结果就多加了一个单位矩阵。",
    ),
    (
        "Hidden today by this scene: the blockers that shape each penumbra lie within the part it reads; a wider light or a higher blocker shows it:",
        "在这个场景里暂时看不出来：决定各个半影的遮挡物都落在它读到的那部分之内；更宽的光源或更高的遮挡物就会暴露它：",
    ),
    (
        "findBlocker's loop on line {} reads only the first {} of the {} samples in `{}`. The disk orders them from the centre out, so those reach {:.0}% of its radius: the search reads {:.1} texels around the receiver, where the light its filter behaves as is {:.1} texels wide (half). Loop over every sample the disk holds (BLOCKER_SEARCH_NUM_SAMPLES, and a disk of that many).",
        "findBlocker 第 {} 行的循环只读取了前 {} 个采样（共 {} 个，在 `{}` 中）。圆盘中的采样由中心向外排列，所以这些采样只达到半径的 {:.0}%：搜索只读取了接收点周围 {:.1} 个纹素，而它的滤波所对应的光源半宽是 {:.1} 个纹素。应遍历圆盘中的所有采样（BLOCKER_SEARCH_NUM_SAMPLES，并让圆盘有同样多的采样）。",
    ),
    (
        "The disk is that wide because line {} sizes it with `{}`, a sample count ({}), as if it were a radius in texels.",
        "圆盘之所以这么宽，是因为第 {} 行用 `{}` 来确定它的大小：这是一个采样数（{}），却被当成了以纹素为单位的半径。",
    ),
];
