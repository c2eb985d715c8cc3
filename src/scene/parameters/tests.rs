use super::*;
use crate::i18n::{Lang, tr};
use crate::scene::parse_scene_str;

/// A scene with a light of each kind: light 0 directional, light 1 spot.
const SCENE: &str = "[camera]\nposition = [0.0, 4.0, 10.0]\nfov_deg = 45.0\n\n\
    [[object]]\nmesh = \"plane\"\n\n\
    [[light]]\nkind = \"directional\"\nposition = [5.0, 10.0, 0.0]\nextent = 10.0\n\n\
    [[light]]\nkind = \"spot\"\nposition = [0.0, 10.0, 0.0]\nfov_deg = 60.0\n";

/// The scene with `--set` overrides, in order.
fn build(overrides: &[(&str, String)]) -> Result<crate::scene::Scene, String> {
    let overrides: Vec<(String, String)> =
        overrides.iter().map(|(k, v)| (k.to_string(), v.clone())).collect();
    parse_scene_str(SCENE, std::path::Path::new("."), "table.toml", &overrides).map_err(|e| e.to_string())
}

/// The key a row's `--set` writes: a spot light's field of view on light 1, other light keys on
/// light 0 (the directional one).
fn key_of(row: &Parameter) -> String {
    match row.key.strip_prefix("light.N.") {
        Some("fov_deg") => "light.1.fov_deg".into(),
        Some(rest) => format!("light.0.{rest}"),
        None => row.key.into(),
    }
}

/// A number as TOML writes a float (with its point or exponent), read back as the same f32.
fn float(v: f32) -> String {
    format!("{v:?}")
}

fn point(c: f32) -> String {
    format!("[{}, {}, {}]", float(c), float(c), float(c))
}

/// The names a `[shadow]` choice (or a light's cascade selection) takes.
fn names(row: &Parameter) -> Vec<&'static str> {
    let mut settings = ShadowSettings::default();
    match row.field.map(|field| field(&mut settings)) {
        Some(Field::Technique(_)) => Technique::ALL.iter().map(|t| t.name()).collect(),
        Some(Field::BiasMode(_)) => BiasMode::ALL.iter().map(|b| b.name()).collect(),
        Some(Field::Kernel(_)) => Kernel::ALL.iter().map(|k| k.name()).collect(),
        Some(Field::DepthStorage(_)) => DepthStorage::ALL.iter().map(|d| d.name()).collect(),
        None if row.key == LIGHT_CASCADE_SELECTION.key => {
            crate::scene::CascadeSelection::ALL.iter().map(|s| s.name()).collect()
        }
        _ => Vec::new(),
    }
}

/// Values the loader must take for the row, and values just outside it that it must refuse, each
/// with the overrides set before it.
type Case = (Vec<(&'static str, String)>, String);
fn cases(row: &Parameter) -> (Vec<Case>, Vec<Case>) {
    let alone = |v: String| (Vec::new(), v);
    match row.values {
        Values::Real { lo, hi } => {
            // A near plane up to its maximum needs a far plane beyond it.
            let before: Vec<(&str, String)> =
                if row.key == "light.N.near" { vec![("light.0.far", float(1e7))] } else { Vec::new() };
            let with = |v: f32| (before.clone(), float(v));
            (vec![with(lo), with(hi)], vec![with(lo.next_down()), with(hi.next_up())])
        }
        Values::Whole { lo, hi } => (
            vec![alone(lo.to_string()), alone(hi.to_string())],
            vec![alone((lo - 1).to_string()), alone((hi + 1).to_string())],
        ),
        Values::FarPlane { beyond_near, hi } => {
            let near = 0.5_f32;
            let before = vec![("light.0.near", float(near))];
            let with = |v: f32| (before.clone(), float(v));
            let lo = near * beyond_near;
            (vec![with(lo.next_up()), with(hi)], vec![with(lo), with(hi.next_up())])
        }
        Values::Point => (
            vec![alone(point(MAX_COORDINATE)), alone(point(-MAX_COORDINATE))],
            vec![alone(point(MAX_COORDINATE.next_up())), alone(point(-MAX_COORDINATE.next_up()))],
        ),
        Values::Switch => (vec![alone("true".into()), alone("false".into())], vec![alone("1".into())]),
        Values::Name => {
            (names(row).into_iter().map(|n| alone(n.into())).collect(), vec![alone("nope".into())])
        }
    }
}

#[test]
fn the_loader_takes_each_row_at_its_ends_and_refuses_it_just_outside() {
    for row in all() {
        let key = key_of(row);
        let (good, bad) = cases(row);
        assert!(!good.is_empty(), "{}: nothing to try", row.key);
        for (before, value) in good {
            let mut overrides = before;
            overrides.push((&key, value.clone()));
            build(&overrides).unwrap_or_else(|e| panic!("--set {key}={value} refused: {e}"));
        }
        for (before, value) in bad {
            let mut overrides = before;
            overrides.push((&key, value.clone()));
            let e = build(&overrides).err().unwrap_or_else(|| panic!("--set {key}={value} taken"));
            assert!(e.contains(key.as_str()) && e.lines().count() == 1, "--set {key}={value}: {e}");
        }
    }
}

#[test]
fn every_shadow_setting_has_its_row_and_every_row_a_place() {
    let settings = toml::Value::try_from(ShadowSettings::default()).expect("the settings as TOML");
    let mut fields: Vec<&str> = settings.as_table().expect("a table").keys().map(String::as_str).collect();
    let mut rows: Vec<&str> = SHADOW.iter().map(|row| row.key).collect();
    fields.sort_unstable();
    rows.sort_unstable();
    assert_eq!(rows, fields, "a [shadow] key without its row, or a row without its key");
    for row in &SHADOW {
        assert!(row.field.is_some() && !row.key.contains('.'), "{}", row.key);
    }
    for row in LIGHT_AND_CAMERA {
        assert!(row.field.is_none(), "{}", row.key);
        assert!(row.key.starts_with("light.N.") || row.key.starts_with("camera."), "{}", row.key);
    }
    let mut keys: Vec<&str> = all().map(|row| row.key).collect();
    keys.sort_unstable();
    keys.dedup();
    assert_eq!(keys.len(), all().count(), "a key has two rows");
}

#[test]
fn every_control_fits_its_values_and_spans_only_what_the_loader_takes() {
    let mut settings = ShadowSettings::default();
    for row in all() {
        let field = row.field.map(|field| field(&mut settings));
        let fits = match (row.values, row.control) {
            (Values::Real { lo, hi }, Control::Slider { lo: from, hi: to, .. }) => {
                lo <= from && from < to && to <= hi && matches!(field, None | Some(Field::Real(_)))
            }
            (Values::Real { lo, .. }, Control::NearSlider { lo: from, below_far }) => {
                lo <= from && below_far < 1.0
            }
            (Values::FarPlane { beyond_near, hi }, Control::FarSlider { beyond_near: from, hi: to }) => {
                beyond_near <= from && to <= hi
            }
            (Values::Whole { lo, hi }, Control::Slider { lo: from, hi: to, .. }) => {
                lo as f32 <= from
                    && from < to
                    && to <= hi as f32
                    && from.fract() == 0.0
                    && to.fract() == 0.0
                    && matches!(field, None | Some(Field::Int(_) | Field::Count(_)))
            }
            (Values::Whole { .. }, Control::Drag) => matches!(field, Some(Field::Count(_))),
            (Values::Whole { lo, hi }, Control::Sizes(sizes)) => {
                !sizes.is_empty() && sizes.iter().all(|&s| (lo..=hi).contains(&i64::from(s)))
            }
            (Values::Point, Control::Point) => field.is_none(),
            (Values::Switch, Control::Checkbox) => matches!(field, Some(Field::Switch(_))),
            (Values::Name, Control::Combo) => !names(row).is_empty(),
            _ => false,
        };
        assert!(fits, "{}: {:?} edited by {:?}", row.key, row.values, row.control);
    }
}

#[test]
fn every_label_and_heading_has_its_chinese_and_names_its_unit() {
    for row in all() {
        for en in [row.label, row.section] {
            assert!(en.is_empty() || tr(Lang::Zh, en) != en, "`{en}` has no Chinese in src/i18n");
        }
        let points = matches!(row.control, Control::Point);
        assert!(
            row.unit.is_empty() || points || row.label.ends_with(&format!("({})", row.unit)),
            "{}: the label `{}` does not give its unit {}",
            row.key,
            row.label,
            row.unit
        );
    }
}

#[test]
fn a_try_this_names_a_light_key_by_its_row() {
    assert_eq!(named("light.2.width").map(|row| row.label), Some("light width (world units)"));
    assert_eq!(named("samples").map(|row| row.key), Some("samples"));
    assert!(named("light.x.width").is_none() && named("camera.fov_deg").is_none());
    assert!(named("noise_seed").is_none() && named("light.0.fov_deg").is_none());
}
