//! The app's fixed strings in Simplified Chinese. English is the key: the code reads in English
//! and `tr` looks the Chinese up. Lesson text has its own translations (lessons/*.toml).
//! `tests/app.rs` walks the app in Chinese and fails on any English text left on screen.

use crate::lessons::Lang;
use std::collections::HashMap;
use std::sync::OnceLock;

/// English -> Chinese, for every string the panels show.
const ZH: &[(&str, &str)] = &[
    // Top bar, status bar and help.
    ("scene", "场景"),
    ("lesson", "课程"),
    ("(none: explore freely)", "（无：自由探索）"),
    ("Explore freely (no lesson)", "自由探索（不选课程）"),
    ("Scenes", "场景"),
    ("Lessons", "课程"),
    ("file", "文件"),
    ("scene .toml or .obj path", "场景 .toml 或 .obj 路径"),
    ("Open", "打开"),
    ("Play", "播放"),
    ("Pause", "暂停"),
    ("Space", "空格键"),
    ("time (s)", "时间（秒）"),
    ("speed", "速度"),
    ("Screenshot", "截图"),
    ("S: window and each view as PNGs", "S 键：把窗口和每个视图存成 PNG"),
    ("language", "语言"),
    ("F1 Help", "F1 帮助"),
    ("Present (F5)", "演示（F5）"),
    ("camera view, map, diagram and lesson text, large", "放大显示相机视图、贴图、示意图和课文"),
    ("F5", "F5 键"),
    ("present mode (Esc leaves it)", "演示模式（Esc 退出）"),
    ("F5 or Esc: leave present mode", "F5 或 Esc：退出演示模式"),
    ("Error", "错误"),
    ("dismiss", "关闭"),
    ("Shortcuts", "快捷键"),
    ("opened", "已打开"),
    ("taking a screenshot...", "正在截图……"),
    ("saved", "已保存"),
    ("Left / Right", "← / →"),
    ("previous / next lesson step", "上一步 / 下一步"),
    ("play / pause", "播放 / 暂停"),
    ("S", "S 键"),
    ("screenshot (window and each view)", "截图（窗口和每个视图）"),
    ("F1", "F1 键"),
    ("this help", "本帮助"),
    ("R", "R 键"),
    ("reset the camera", "重置相机"),
    ("Left-drag (camera view)", "左键拖动（相机视图）"),
    ("orbit", "环绕"),
    ("Right- or middle-drag", "右键或中键拖动"),
    ("pan", "平移"),
    ("Wheel", "滚轮"),
    ("zoom", "缩放"),
    ("Click", "单击"),
    ("pin the probe", "放置探针"),
    ("Double-click", "双击"),
    ("focus the camera on a point", "让相机对准一个点"),
    ("Drag (shadow map)", "拖动（阴影贴图）"),
    ("move the light", "移动光源"),
    ("Drop a .toml or .obj", "拖入 .toml 或 .obj 文件"),
    ("open it", "打开它"),
    // Lesson panel.
    ("Previous", "上一步"),
    ("Next", "下一步"),
    ("Left arrow", "← 键"),
    ("Right arrow", "→ 键"),
    ("step", "步骤"),
    ("show every panel", "显示所有面板"),
    // Inspector.
    ("Technique", "技术"),
    ("technique", "技术"),
    ("A/B split against", "A/B 对比："),
    ("drag the divider in the camera view", "在相机视图里拖动分隔线"),
    ("right side", "右侧"),
    ("Bias", "偏移"),
    ("bias mode", "偏移模式"),
    ("bias (NDC depth)", "偏移（NDC 深度）"),
    ("slope bias (NDC)", "斜率偏移（NDC）"),
    ("adaptive c (× half texel)", "自适应系数 c（× 半个纹素）"),
    ("normal offset (texels)", "法线偏移（纹素）"),
    ("hardware bias (depth units)", "硬件偏移（深度单位）"),
    ("hardware slope bias", "硬件斜率偏移"),
    ("cull front faces in the shadow pass", "阴影趟中剔除正面"),
    ("outside the light frustum = lit", "光源视锥之外 = 受光"),
    ("PCF", "PCF 滤波"),
    ("kernel", "采样图案"),
    ("samples", "采样数"),
    ("radius (texels)", "半径（纹素）"),
    ("rotate the pattern per pixel", "每个像素旋转采样图案"),
    ("noise seed", "噪声种子"),
    ("PCSS", "PCSS 软阴影"),
    ("blocker samples", "遮挡物搜索采样数"),
    ("min filter radius (texels)", "最小滤波半径（纹素）"),
    ("ground-truth samples", "真实结果采样数"),
    ("Camera", "相机"),
    ("field of view (°)", "视场角（°）"),
    ("Reset camera (R)", "重置相机（R）"),
    ("Overlays", "叠加层"),
    ("blocker-search radius", "遮挡物搜索半径"),
    ("penumbra width", "半影宽度"),
    ("blockers found", "找到的遮挡物"),
    ("shadow-map texel grid", "阴影贴图纹素网格"),
    ("outside the light frustum", "光源视锥之外"),
    ("error vs ground truth", "与真实结果的误差"),
    ("light frustum wireframe", "光源视锥线框"),
    ("Reset to scene/lesson values", "恢复场景/课程的数值"),
    ("screenshot folder", "截图文件夹"),
    ("Lights", "光源"),
    ("light", "光源"),
    ("this scene has no lights", "这个场景没有光源"),
    ("shadow map (texels)", "阴影贴图（纹素）"),
    ("directional light, orthographic map", "平行光，正交投影贴图"),
    ("spot light, perspective map", "聚光灯，透视投影贴图"),
    ("half-width (world units)", "半宽（世界单位）"),
    ("near (world units)", "近平面（世界单位）"),
    ("far (world units)", "远平面（世界单位）"),
    ("light width (world units)", "光源宽度（世界单位）"),
    ("use an angular diameter instead", "改用角直径"),
    ("angular diameter (°)", "角直径（°）"),
    ("use a width instead", "改用宽度"),
    ("intensity", "强度"),
    ("orbit (°/s)", "环绕速度（°/秒）"),
    // Probe.
    ("Probe", "探针"),
    ("click the camera view to pin a probe", "单击相机视图放置探针"),
    ("no surface", "没有表面"),
    ("shadow-map uv", "阴影贴图 uv"),
    ("texel", "纹素"),
    ("texels", "纹素"),
    ("taps", "个采样点"),
    ("world", "世界单位"),
    ("none", "无"),
    ("receiver depth", "接收点深度"),
    ("stored depth", "存储的深度"),
    ("bias", "偏移"),
    ("N·L", "N·L（法线·光线）"),
    ("blocker search", "遮挡物搜索"),
    ("avg blocker depth", "平均遮挡深度"),
    ("filter radius", "滤波半径"),
    ("visibility (CPU twin)", "可见性（CPU 孪生实现）"),
    ("visibility (GPU)", "可见性（GPU）"),
    // Views and panels.
    ("view", "视图"),
    ("What the camera panel shows (`--view` in the CLI)", "相机面板显示的内容（命令行中的 `--view`）"),
    ("No GPU view", "没有 GPU 视图"),
    ("unknown reason", "原因不明"),
    ("rendering...", "渲染中……"),
    ("Shadow map", "阴影贴图"),
    ("no light in this scene", "这个场景没有光源"),
    ("world units from the light", "到光源的世界单位距离"),
    ("· white: nothing stored · wheel: zoom", "· 白色：没有存储 · 滚轮：缩放"),
    (
        "drag to move the light · blue: blocker search · white: filter · green lit, pink blocked",
        "拖动以移动光源 · 蓝色：遮挡物搜索 · 白色：滤波 · 绿色受光，粉色被挡",
    ),
    ("(overlays refresh when you let go)", "（松开鼠标后叠加层才会刷新）"),
    ("(working out the overlays...)", "（正在计算叠加层……）"),
    ("Diagram", "示意图"),
    ("sample pattern", "采样图案"),
];

fn table() -> &'static HashMap<&'static str, &'static str> {
    static TABLE: OnceLock<HashMap<&'static str, &'static str>> = OnceLock::new();
    TABLE.get_or_init(|| ZH.iter().copied().collect())
}

/// `en` in `lang`. A string missing from the table shows in English (and fails the app test).
pub fn tr(lang: Lang, en: &'static str) -> &'static str {
    match lang {
        Lang::En => en,
        Lang::Zh => table().get(en).copied().unwrap_or(en),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_is_translated_once() {
        let mut seen = std::collections::HashSet::new();
        for (en, zh) in ZH {
            assert!(seen.insert(en), "`{en}` is in the table twice");
            assert!(
                zh.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c) || "←→".contains(c)),
                "`{en}` -> `{zh}`"
            );
        }
    }
}
