//! The class report's page (`shadowlab homework --class`) in Simplified Chinese, and the one-line
//! description of every finding it shows in place of the English explanations.

pub(super) const CLASS: &[(&str, &str)] = &[
    ("Class report", "班级作业报告"),
    // The app's class panel.
    ("Class", "班级"),
    ("could not open the class", "无法打开班级"),
    ("{} of {} checked", "已检查 {} / {} 份"),
    ("each submission is checked as a process of its own", "每份作业在独立的进程中检查"),
    ("class report:", "班级报告："),
    ("{} students", "{} 名学生"),
    ("no findings", "没有发现问题"),
    ("The lights their page made:", "其页面创建的光源："),
    ("not checked (a point light, or a light without matrices)", "未检查（点光源，或没有矩阵的光源）"),
    (
        "Submissions with several or moving lights (the bonus): {}; of their {} light checks, {} without a finding",
        "多光源或动态光源作业（加分项）：{} 份；共检查光源 {} 次，{} 次没有发现问题",
    ),
    ("at {} s", "第 {} 秒"),
    ("← class {} ({} submissions)", "← 班级 {}（{} 份作业）"),
    ("{} submissions", "共 {} 份作业"),
    ("checked@class", "已检查"),
    ("did not compile@class", "未能编译"),
    ("refused@class", "被拒绝"),
    ("failed@class", "检查失败"),
    ("timed out@class", "超时"),
    ("mistake@class", "错误"),
    ("latent@class", "潜在"),
    ("lesson {}, step {}", "课程 {}，第 {} 步"),
    ("Findings across the class", "全班的问题（按人数排序）"),
    ("No student has a finding.", "没有学生的作业被发现问题。"),
    ("finding", "问题"),
    ("kind@class", "类别"),
    ("students", "人数"),
    ("share of the class", "占全班"),
    ("what it is", "说明"),
    ("taught in", "讲解它的课程"),
    ("who", "哪些学生"),
    ("Students", "学生"),
    ("name@class", "名字"),
    ("status@class", "状态"),
    ("mistakes", "错误数"),
    ("latent findings", "潜在问题数"),
    ("message@class", "信息"),
    ("light from {}", "光源来自 {}"),
    ("orthographic frustum {} wide, depth range {}", "正交视锥，宽 {}，深度范围 {}"),
    ("perspective frustum of {}°, depth range {}", "透视视锥，视场角 {}°，深度范围 {}"),
    ("{} frustum, depth range {}", "{} 视锥，深度范围 {}"),
    ("their penumbrae imply a light {} wide", "其半影对应的光源宽度为 {}"),
    ("no light width implied", "无法从半影推出光源宽度"),
    (
        "their penumbrae imply a light narrower than {}, too narrow for this map",
        "其半影对应的光源窄于 {}，这张贴图分辨不出",
    ),
    ("their light was not used: {}", "未使用学生的光源：{}"),
    ("their picture", "学生的画面"),
    ("their picture over a lossless map", "无损贴图下学生的画面"),
    ("difference to the ground truth", "与真实结果之差"),
    ("No findings.", "没有发现问题。"),
    // One line per finding (src/export/class_report.rs, DESCRIPTIONS).
    (
        "findBlocker divides by zero blockers where nothing blocks the light (NaN depth).",
        "光没有被挡住的地方，findBlocker 用 0 个遮挡物去除（深度为 NaN）。",
    ),
    ("The visibility is NaN or infinite on some pixels.", "部分像素的可见度是 NaN 或无穷大。"),
    (
        "The visibility leaves [0, 1]: a sum of tests divided by the wrong count, or not at all.",
        "可见度超出 [0, 1]：测试结果之和除错了个数，或者没有除。",
    ),
    (
        "The visibility is scaled by a constant: lit points do not reach 1.",
        "可见度被乘上了一个常数：受光的点达不到 1。",
    ),
    (
        "CalcLightMVP places the objects differently from the framework's model matrix.",
        "CalcLightMVP 放置物体的方式与框架的模型矩阵不同。",
    ),
    (
        "The light's frustum leaves part of the scene outside the shadow map.",
        "光源视锥没有包住场景，部分场景落在阴影贴图之外。",
    ),
    (
        "The page never draws with this light's matrix: its shadows are another light's.",
        "页面从未用这盏光源的矩阵绘制：它的阴影其实是另一盏光源的。",
    ),
    (
        "A light or an object moves, but the uLightMVP its draws get stays where it was.",
        "光源或物体在动，但绘制时拿到的 uLightMVP 还停留在原来的位置。",
    ),
    (
        "Shadows are missing: the lookups never meet the blockers (wrong space or units).",
        "阴影不见了：查询碰不到遮挡物（坐标空间或单位用错）。",
    ),
    (
        "A bias so large that shadows come loose from what casts them (peter panning).",
        "偏移太大，阴影与投射它的物体脱开（彼得潘现象，悬浮）。",
    ),
    (
        "The umbra is not dark: the filter reaches far past the blocker (world units used as uv).",
        "本影不够暗：滤波范围远远超出遮挡物（把世界单位当成了 uv）。",
    ),
    (
        "Depth does not come back from the map as it went in: pack and unpack disagree.",
        "从贴图读回的深度与写入的不一致：打包和解包不匹配。",
    ),
    (
        "findBlocker's search radius is wrong for the light's size and the receiver's depth.",
        "findBlocker 的搜索半径与光源大小和接收点深度不符。",
    ),
    (
        "PCSS filters over a radius that is not a number (a blocker depth of 0 divided by).",
        "PCSS 的滤波半径不是一个数（用 0 作为遮挡物深度去除）。",
    ),
    ("findBlocker counts the receiver as its own blocker.", "findBlocker 把接收点自己算成了遮挡物。"),
    (
        "The framework's far floor acnes: its RGBA8 round trip reads depths over 0.5 nearer than the bias.",
        "框架地面的远端出现阴影痤疮：RGBA8 往返把 0.5 以上的深度读近得超过了偏移。",
    ),
    (
        "findBlocker returns a depth no blocker has where the disk is blocked.",
        "搜索圆盘被遮挡时，findBlocker 返回的深度不属于任何遮挡物。",
    ),
    (
        "PCSS's filter radius collapses under blockers: the penumbra estimate misses the receiver's depth.",
        "PCSS 的滤波半径在遮挡物下塌缩：半影估计没有用接收点自己的深度。",
    ),
    (
        "PCSS's filter radius scales with the depths beyond similar triangles (near / z_r on an orthographic light).",
        "PCSS 的滤波半径随深度的变化超出了相似三角形（正交光源上多乘了 near / z_r）。",
    ),
    (
        "PCSS's filter radius does not use the blocker's depth: PCF with a radius of its own.",
        "PCSS 的滤波半径没有用到遮挡物深度：等于用自定半径的 PCF。",
    ),
    (
        "The blocker search and the filter behave as lights of different sizes (one length, two units).",
        "遮挡物搜索和滤波相当于两盏大小不同的光源（同一个长度，两种单位）。",
    ),
    (
        "The filter's taps are not spread over a disk around the receiver.",
        "滤波的采样点没有分布在以接收点为中心的圆盘上。",
    ),
    (
        "PCSS draws hard shadows: the filter is under a texel wide.",
        "PCSS 画出了硬阴影：滤波范围不到一个纹素。",
    ),
    (
        "Penumbrae do not widen with the blocker's distance as similar triangles say.",
        "半影没有像相似三角形所说的那样随遮挡物的距离变宽。",
    ),
    (
        "Lit surfaces shadow themselves: shadow acne, a bias too small.",
        "受光的表面遮挡了自己：阴影失真，偏移太小。",
    ),
    ("The picture depends on the texels the framework never clears.", "画面取决于框架从未清除的纹素。"),
    (
        "The light's map projects along another direction than the light looks.",
        "光源的阴影贴图沿着与光源朝向不同的方向投影。",
    ),
];
