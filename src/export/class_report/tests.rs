use super::*;

fn finding(id: &str, severity: Severity, explanation: &str) -> FindingPart {
    FindingPart {
        id: id.into(),
        severity,
        figures: BTreeMap::from([("share".to_string(), Some(0.25)), ("width".to_string(), None)]),
        explanation: explanation.into(),
        lesson: "pcss".into(),
        step: 3,
    }
}

fn checked(name: &str, findings: Vec<FindingPart>) -> ClassRow {
    ClassRow {
        name: name.into(),
        folder: name.into(),
        path: format!("class/{name}"),
        status: Status::Checked,
        message: String::new(),
        report: Some(StudentReport {
            compiled: true,
            visibility_function: Some("PCSS".into()),
            light: Some(LightPart {
                from: "homework1/src/lights/DirectionalLight.js:43".into(),
                error: None,
                frustum: Some(FrustumPart {
                    kind: "orthographic".into(),
                    width_world: Some(200.0),
                    fov_deg: None,
                    depth_range_world: Some(399.99),
                }),
            }),
            light_width: Some(WidthPart {
                implied_light_width_world: Some(1.6847),
                narrower_than_world: None,
                law_holds: Some(true),
            }),
            findings,
            ..StudentReport::default()
        }),
        pictures: PICTURES.to_vec(),
    }
}

fn failed(name: &str, status: Status, message: &str) -> ClassRow {
    ClassRow {
        name: name.into(),
        folder: name.into(),
        path: format!("class/{name}"),
        status,
        message: message.into(),
        report: None,
        pictures: Vec::new(),
    }
}

fn class() -> Vec<ClassRow> {
    vec![
        checked("alice", vec![]),
        checked("bob", vec![finding("nan_blocker_depth", Severity::Latent, "findBlocker returns NaN.")]),
        checked(
            "carol",
            vec![
                finding("umbra_not_dark", Severity::Mistake, "Where no point of the light reaches..."),
                finding("depends_on_uncleared_map", Severity::Mistake, "Your lookups land there."),
            ],
        ),
        checked("dan", vec![finding("umbra_not_dark", Severity::Mistake, "Where no point...")]),
        failed("eve", Status::Refused, "eve.zip: entry ../evil.glsl would land outside the submission"),
    ]
}

#[test]
fn every_finding_of_the_registry_has_a_description_in_both_languages() {
    for kind in FINDINGS {
        let en = description(Lang::En, kind.id)
            .unwrap_or_else(|| panic!("`{}` has no line in class_report.rs's DESCRIPTIONS", kind.id));
        let zh = description(Lang::Zh, kind.id).unwrap_or_default();
        assert_ne!(en, zh, "`{en}` has no Chinese in i18n/class_zh.rs");
    }
    for (id, _) in DESCRIPTIONS {
        assert!(FINDINGS.iter().any(|k| k.id == *id), "`{id}` is not in the registry");
    }
}

#[test]
fn csv_fields_are_quoted_as_rfc_4180_says() {
    assert_eq!(csv_field("alice"), "alice");
    assert_eq!(csv_field("Smith, John"), "\"Smith, John\"");
    assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
    assert_eq!(csv_field(" padded"), "\" padded\"");
    assert_eq!(csv_field("张三"), "张三");
    // Text a spreadsheet would run as a formula is kept as text.
    assert_eq!(csv_text("=HYPERLINK(\"x\")"), "\"'=HYPERLINK(\"\"x\"\")\"");
    assert_eq!(csv_text("@cmd"), "'@cmd");
}

/// Split CSV text into records and fields (RFC 4180), for the tests.
fn parse_csv(text: &str) -> Vec<Vec<String>> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let (mut rows, mut row, mut field) = (Vec::new(), Vec::new(), String::new());
    let (mut quoted, mut chars) = (false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') => quoted = true,
            (false, ',') => row.push(std::mem::take(&mut field)),
            (false, '\r') => {}
            (false, '\n') => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (false, c) => field.push(c),
        }
    }
    rows
}

#[test]
fn the_csv_has_a_row_per_student_and_a_column_per_finding() {
    let mut rows = class();
    rows[0].name = "Smith, \"Al\"".into();
    let text = csv(&rows);
    assert!(text.starts_with('\u{feff}') && text.ends_with("\r\n"));
    let records = parse_csv(&text);
    assert_eq!(records.len(), rows.len() + 1);
    let header = &records[0];
    assert_eq!(header.len(), 7 + FINDINGS.len() + 1);
    assert!(records.iter().all(|r| r.len() == header.len()), "{records:?}");
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    assert_eq!(records[1][0], "Smith, \"Al\"");
    assert_eq!(records[1][column("status")], "checked");
    assert_eq!(records[1][column("implied light width")], "1.685");
    assert_eq!(records[1][column("light from")], "homework1/src/lights/DirectionalLight.js:43");
    assert_eq!(records[2][column("nan_blocker_depth")], "latent");
    assert_eq!(records[2][column("mistakes")], "0");
    assert_eq!(records[3][column("umbra_not_dark")], "1");
    assert_eq!(records[3][column("self_shadowing")], "0");
    assert_eq!(records[3][column("mistakes")], "2");
    // A submission that was not checked has no finding judged.
    assert_eq!(records[5][column("status")], "refused");
    assert_eq!(records[5][column("umbra_not_dark")], "");
    assert!(records[5][column("message")].contains("../evil.glsl"));
}

#[test]
fn findings_are_ranked_by_students_mistakes_first() {
    let rows = class();
    let ranked = ranked(&rows);
    let order: Vec<(&str, Severity, usize)> =
        ranked.iter().map(|r| (r.id.as_str(), r.severity, r.students.len())).collect();
    assert_eq!(
        order,
        [
            ("umbra_not_dark", Severity::Mistake, 2),
            ("depends_on_uncleared_map", Severity::Mistake, 1),
            ("nan_blocker_depth", Severity::Latent, 1),
        ]
    );
    assert_eq!(ranked[0].students, [2, 3]);
}

#[test]
fn student_text_is_escaped_and_links_are_relative() {
    let mut rows = class();
    rows[0].name = "<script>alert(1)</script> & \"co\"".into();
    rows[0].folder = "a b#c?d%".into();
    rows[2].report.as_mut().expect("a report").findings[0].explanation = "reads <img src=x> `a<b`".into();
    rows[4].message = "x.zip: entry <b>'evil'</b>".into();
    let html = page::html(Lang::En, &rows, Lang::En);
    assert!(!html.contains("<script"), "{html}");
    assert!(!html.contains("<img src=x>") && !html.contains("<b>"));
    assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;co&quot;"));
    assert!(html.contains("reads &lt;img src=x&gt; <code>a&lt;b</code>"));
    assert!(html.contains("&#39;evil&#39;"));
    assert!(html.contains("href=\"a%20b%23c%3Fd%25/student.png\""));
    assert!(html.contains("src=\"carol/difference.png\""));
    assert!(html.contains("href=\"index_zh.html\""));
    assert!(html.contains("lesson pcss, step 6"), "the registry's step for umbra_not_dark");
    assert!(!html.contains("http://") && !html.contains("https://"), "nothing fetched from elsewhere");
}

#[test]
fn the_chinese_page_says_every_fixed_string_in_chinese() {
    let rows = class();
    let zh = page::html(Lang::Zh, &rows, Lang::En);
    assert!(zh.contains("<html lang=\"zh-Hans\">") && zh.contains("href=\"index.html\""));
    for english in [
        "Class report",
        "Findings across the class",
        "share of the class",
        "checked",
        "refused",
        "mistake",
        "latent",
        "lesson pcss",
        "their picture",
        "ground truth",
        "light from",
        "orthographic",
        "No findings",
        // The reports' English explanations give way to the descriptions.
        "Where no point",
    ] {
        assert!(!zh.contains(english), "`{english}` on the Chinese page");
    }
    assert!(zh.contains("课程 pcss，第 6 步"));
    assert!(zh.contains(description(Lang::Zh, "umbra_not_dark").unwrap_or("?")));
    // The English page keeps the reports' own explanations.
    let en = page::html(Lang::En, &rows, Lang::En);
    assert!(en.contains("Where no point of the light reaches..."));
}

#[test]
fn a_report_is_read_from_its_json() {
    let text = r#"{"submission": null, "shader": "a.glsl", "compiled": true, "error": null,
        "visibility_function": "PCSS", "light": {"from": "framework", "error": null,
        "frustum": {"kind": "orthographic", "width_world": 200.0, "fov_deg": null,
        "depth_range_world": 399.99, "texel_world": 0.1}},
        "light_width": {"implied_light_width_world": null},
        "findings": [{"id": "no_penumbra", "severity": "mistake", "function": "PCSS",
        "figures": {"a": 1.5, "b": null}, "explanation": "x", "lesson": "pcss", "step": 5}]}"#;
    let report = StudentReport::parse(text).expect("a report");
    assert!(report.compiled);
    assert_eq!(report.findings[0].figures["b"], None);
    assert_eq!(report.findings[0].severity, Severity::Mistake);
    assert!(StudentReport::parse("{}").is_err(), "a report says whether it compiled");
    assert!(StudentReport::parse("not json").is_err());
}

#[test]
fn numbers_read_as_people_write_them() {
    assert_eq!(number(200.0), "200");
    assert_eq!(number(399.99), "400");
    assert_eq!(number(1.68471), "1.685");
    assert_eq!(number(0.5), "0.5");
    assert_eq!(number(f64::NAN), "n/a");
}

#[test]
fn a_light_width_is_told_only_where_a_light_casts_the_widths() {
    let part = |law_holds, narrower_than_world| WidthPart {
        implied_light_width_world: Some(1.5),
        narrower_than_world,
        law_holds,
    };
    assert_eq!(part(Some(true), None).measured(), Some(1.5));
    assert_eq!(part(None, None).measured(), Some(1.5));
    // Widths of no light's shape: a fit through them is no light's width.
    assert_eq!(part(Some(false), None).measured(), None);
    assert_eq!(part(None, Some(0.4)).measured(), None);
}

#[test]
fn the_bonus_lights_are_counted_and_each_listed_with_its_own_findings() {
    let mut rows = class();
    let light = |made_at: &str, kind: &str, findings: Option<&[&str]>| PageLightPart {
        kind: kind.into(),
        made_at: made_at.into(),
        findings: findings.map(|f| f.iter().map(|id| id.to_string()).collect()),
        at_times: Vec::new(),
    };
    if let Some(report) = rows[1].report.as_mut() {
        report.lights = vec![
            light("homework1/src/engine.js:27", "DirectionalLight", Some(&[])),
            light("homework1/src/engine.js:31", "DirectionalLight", Some(&["light_frustum_clips"])),
            light("homework1/src/engine.js:35", "PointLight", None),
        ];
        // The second light orbits: checked again at 1 s of the page's animation.
        report.lights[1].at_times = vec![TimedPart { time_s: 1.0, findings: Vec::new() }];
    }
    assert_eq!(rows[1].report.as_ref().and_then(|r| r.bonus()), Some((3, 3, 2)));
    assert_eq!(rows[0].report.as_ref().and_then(|r| r.bonus()), None);
    let html = page::html(Lang::En, &rows, Lang::En);
    assert!(
        html.contains(
            "Submissions with several or moving lights (the bonus): 1; of their 3 light checks, 2 without a finding"
        ),
        "{html}"
    );
    assert!(
        html.contains(
            "<li><code>homework1/src/engine.js:31</code> DirectionalLight: light_frustum_clips; at 1 s: no findings</li>"
        )
    );
    assert!(html.contains("engine.js:35</code> PointLight: not checked"));
    let zh = page::html(Lang::Zh, &rows, Lang::En);
    assert!(zh.contains("多光源或动态光源作业（加分项）：1 份") && zh.contains("第 1 秒"), "{zh}");
    let records = parse_csv(&csv(&rows));
    let column = records[0].iter().position(|h| h == "lights").expect("a lights column");
    assert_eq!(
        records[2][column],
        "DirectionalLight homework1/src/engine.js:27: no findings | \
         DirectionalLight homework1/src/engine.js:31: light_frustum_clips; at 1 s: no findings | \
         PointLight homework1/src/engine.js:35: not checked"
    );
    assert_eq!(records[1][column], "");
}
