//! The exported slides and their index page in Simplified Chinese. Keys ending in `@slides` are
//! words the app's panels translate differently (see [`super::tr`]).

pub(super) const SLIDES: &[(&str, &str)] = &[
    // Title bar and captions.
    ("step {}/{}", "第 {}/{} 步"),
    ("no light, no shadow map", "没有光源，也就没有阴影贴图"),
    ("Camera view: ", "相机画面："),
    ("  ·  probe + at ({}, {}) in {}×{}", "  ·  探针 + 位于 ({}, {})（{}×{} 画面）"),
    ("orthographic", "正交"),
    ("perspective", "透视"),
    ("Shadow map: light {} · {}² · {}", "阴影贴图：光源 {} · {}² · {}"),
    ("Shadow map: light {} · {} {} of {}²", "阴影贴图：光源 {} · {} 张{}，每张 {}²"),
    ("cube faces", "立方体面"),
    ("cascade maps", "级联贴图"),
    ("depth from the light {} (dark) .. {} (bright)", "到光源的深度 {}（暗）至 {}（亮）"),
    ("frusta: yellow = this light, blue = the others", "视锥：黄 = 本光源，蓝 = 其他光源"),
    // A range in a legend: "a .. b".
    ("..", "至"),
    // The views as the captions name them (the app's view menu's names in Chinese).
    ("shaded", "着色画面"),
    ("shadow map", "阴影贴图"),
    ("average blocker depth", "平均遮挡深度"),
    ("VSM moments", "VSM 矩"),
    // Probe panel ("Probe", "receiver depth", "bias", "filter radius" and the other names the
    // app's probe panel shares are in ui_zh.rs).
    ("no shadows", "无阴影"),
    ("hard shadows", "硬阴影"),
    ("nothing to probe", "没有可探测的表面"),
    ("no surface under the probe", "探针下没有表面"),
    (" (lesson)", "（课程指定）"),
    (" (auto)", "（自动选取）"),
    ("pixel", "像素"),
    ("surface", "表面"),
    ("map uv", "贴图 uv"),
    ("light angle", "光线夹角"),
    ("stored depth@slides", "贴图存的深度"),
    ("bound / true", "上界 / 真实"),
    ("blockers@slides", "遮挡物"),
    ("blocker depth", "遮挡物深度"),
    ("  (truth {})", "（真值 {}）"),
    ("visibility@slides", "可见度"),
    ("outside the light's frustum", "在光源视锥之外"),
    ("no light to probe", "没有光源"),
    // The index page.
    ("shadowlab lessons", "shadowlab 课程"),
    ("{} lessons, {} slides", "{} 课，共 {} 张幻灯片"),
    ("Left / Right arrow keys: previous / next slide", "左右方向键：上一张 / 下一张"),
    ("Step {}/{}: {}", "第 {}/{} 步：{}"),
    ("slide", "幻灯片"),
    ("camera view@slides", "相机画面"),
    ("diagram", "示意图"),
];
