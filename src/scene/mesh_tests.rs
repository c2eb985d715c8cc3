use super::*;
use crate::scene::primitives::{PRIMITIVES, primitive};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj").join(name)
}

fn load(name: &str) -> Mesh {
    let path = fixture(name);
    load_obj(&path).unwrap_or_else(|e| panic!("{name} should load: {e}"))
}

fn load_err(name: &str) -> String {
    match load_obj(&fixture(name)) {
        Ok(_) => panic!("{name} should fail to load"),
        Err(e) => e.to_string(),
    }
}

/// Writes `files` into a fresh temporary folder and returns its path.
fn temp_files(tag: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shadowlab_mesh_{}_{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create temp dir");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write temp file");
    }
    dir
}

fn assert_unit_normals(mesh: &Mesh) {
    for v in &mesh.vertices {
        let len = Vec3::from(v.normal).length();
        assert!((len - 1.0).abs() < 1e-5, "{}: normal length {len}", mesh.name);
    }
}

fn assert_valid(mesh: &Mesh) {
    assert_eq!(mesh.indices.len() % 3, 0);
    assert!(mesh.indices.iter().all(|&i| (i as usize) < mesh.vertices.len()));
    let covered: u32 = mesh.parts.iter().map(|p| p.index_count).sum();
    assert_eq!(covered as usize, mesh.indices.len(), "{}", mesh.name);
}

#[test]
fn vertex_layout_is_32_bytes() {
    assert_eq!(std::mem::size_of::<Vertex>(), 32);
    assert_eq!(std::mem::offset_of!(Vertex, normal), 12);
    assert_eq!(std::mem::offset_of!(Vertex, uv), 24);
}

#[test]
fn primitives_exist_with_expected_counts() {
    let expected = [
        ("plane", 2),
        ("cube", 12),
        ("sphere", 48 * 24 * 2 - 2 * 48),
        ("cylinder", 48 * 2 + 2 * 48),
        ("torus", 48 * 24 * 2),
    ];
    assert_eq!(PRIMITIVES.len(), expected.len());
    for (name, triangles) in expected {
        assert!(PRIMITIVES.contains(&name));
        let mesh = primitive(name).expect("known primitive");
        assert_eq!(mesh.name, name);
        assert_eq!(mesh.triangle_count(), triangles, "{name}");
        assert_eq!(mesh.parts.len(), 1);
        assert_eq!(mesh.parts[0].material, None);
        assert!(mesh.materials.is_empty());
        assert_valid(&mesh);
    }
    assert_eq!(primitive("cube").map(|m| m.vertices.len()), Some(24));
    assert_eq!(primitive("plane").map(|m| m.vertices.len()), Some(4));
    assert!(primitive("teapot").is_none());
}

#[test]
fn primitive_normals_are_unit_and_outward() {
    for &name in PRIMITIVES {
        let mesh = primitive(name).expect("known primitive");
        assert_unit_normals(&mesh);
        for v in &mesh.vertices {
            let (p, n) = (Vec3::from(v.position), Vec3::from(v.normal));
            let outward = match name {
                "plane" => n.dot(Vec3::Y) > 0.9999,
                // From the nearest point of the tube's centre circle.
                "torus" => n.dot(p - Vec3::new(p.x, 0.0, p.z).normalize() * 0.35) > 0.0,
                _ => n.dot(p) > 0.0,
            };
            assert!(outward, "{name}: normal {n} at {p}");
        }
    }
}

#[test]
fn primitive_winding_agrees_with_normals() {
    for &name in PRIMITIVES {
        let mesh = primitive(name).expect("known primitive");
        for tri in mesh.indices.chunks_exact(3) {
            let v = [0, 1, 2].map(|k| mesh.vertices[tri[k] as usize]);
            let [a, b, c] = v.map(|v| Vec3::from(v.position));
            let geometric = (b - a).cross(c - a).normalize();
            for v in v {
                let d = geometric.dot(Vec3::from(v.normal));
                assert!(d > 0.5, "{name}: triangle {tri:?} faces away ({d})");
            }
        }
    }
}

#[test]
fn primitive_bounds_and_uvs() {
    let expected = [
        ("plane", Vec3::new(0.5, 0.0, 0.5)),
        ("cube", Vec3::splat(0.5)),
        ("sphere", Vec3::splat(0.5)),
        ("cylinder", Vec3::splat(0.5)),
        ("torus", Vec3::new(0.5, 0.15, 0.5)),
    ];
    for (name, half) in expected {
        let mesh = primitive(name).expect("known primitive");
        let (lo, hi) = mesh.bounds();
        assert!(lo.abs_diff_eq(-half, 1e-5), "{name}: min {lo}");
        assert!(hi.abs_diff_eq(half, 1e-5), "{name}: max {hi}");
        for v in &mesh.vertices {
            assert!(v.uv.iter().all(|t| (0.0..=1.0).contains(t)), "{name}: uv {:?}", v.uv);
        }
    }
    let empty = Mesh {
        name: String::new(),
        vertices: Vec::new(),
        indices: Vec::new(),
        parts: Vec::new(),
        materials: Vec::new(),
    };
    assert_eq!(empty.bounds(), (Vec3::ZERO, Vec3::ZERO));
}

#[test]
fn quad_and_ngon_are_triangulated() {
    let mesh = load("quad_ngon.obj");
    assert_eq!(mesh.triangle_count(), 5);
    assert_valid(&mesh);
}

#[test]
fn missing_normals_are_smooth_and_outward() {
    let mesh = load("no_normals.obj");
    assert_eq!(mesh.triangle_count(), 12);
    assert_eq!(mesh.vertices.len(), 8);
    assert_valid(&mesh);
    assert_unit_normals(&mesh);
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    for v in &mesh.vertices {
        let (p, n) = (Vec3::from(v.position), Vec3::from(v.normal));
        assert!(n.dot(p - centre) > 0.0, "normal {n} at {p}");
        assert_eq!(v.uv, [0.0, 0.0]);
    }
}

#[test]
fn multi_material_parts_colours_and_texture() {
    let mesh = load("multi_material.obj");
    assert_valid(&mesh);
    assert_eq!(mesh.triangle_count(), 3);
    let names: Vec<&str> = mesh.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["red_quad", "blue_triangle"]);
    let material = |part: usize| &mesh.materials[mesh.parts[part].material.expect("material")];
    let (red, blue) = (material(0), material(1));
    assert_eq!((red.name.as_str(), blue.name.as_str()), ("red_textured", "blue_plain"));
    assert!(red.diffuse.abs_diff_eq(Vec3::new(0.8, 0.1, 0.1), 1e-6));
    assert!(blue.diffuse.abs_diff_eq(Vec3::new(0.1, 0.2, 0.8), 1e-6));
    assert!(blue.diffuse_texture.is_none());
    let texture = red.diffuse_texture.as_ref().expect("red has a texture");
    assert!(texture.path.is_absolute() && texture.path.ends_with("tex_2x2.png"));
    assert_eq!((texture.width, texture.height), (2, 2));
    let pixels: Vec<&[u8]> = texture.rgba8.chunks_exact(4).collect();
    let expected: [&[u8]; 4] = [&[255, 0, 0, 255], &[0, 255, 0, 255], &[0, 0, 255, 255], &[255; 4]];
    assert_eq!(pixels, expected);
    // OBJ v points up; stored uvs have their origin at the top-left.
    let first = &mesh.vertices[mesh.indices[0] as usize];
    assert_eq!(first.uv, [0.0, 1.0]);
    assert!(mesh.vertices[4..].iter().all(|v| v.uv == [0.0, 0.0]));
}

#[test]
fn missing_texture_is_an_error_naming_it() {
    let message = load_err("missing_texture.obj");
    assert!(message.contains("missing_texture.mtl"), "{message}");
    assert!(message.contains("does_not_exist.png"), "{message}");
    assert!(message.contains("not found"), "{message}");
    assert_eq!(message.lines().count(), 1);
}

#[test]
fn malformed_and_empty_files_are_errors() {
    let message = load_err("malformed.obj");
    assert!(message.contains("malformed.obj"), "{message}");
    assert!(message.contains("out of bounds"), "{message}");
    let message = load_err("empty.obj");
    assert!(message.contains("empty.obj: contains no triangles"), "{message}");
    let message = load_err("no_such_file.obj");
    assert!(message.contains("no_such_file.obj"), "{message}");
}

#[test]
fn blender_export_keeps_utf8_names() {
    let mesh = load("blender_export.obj");
    assert_valid(&mesh);
    assert_unit_normals(&mesh);
    assert!(mesh.parts.iter().any(|p| p.name.contains("Würfel_立方体")), "{:?}", mesh.parts);
    assert!(mesh.materials.iter().any(|m| m.name == "材质_Matériel"), "{:?}", mesh.materials);
    assert!(mesh.parts.iter().all(|p| p.material.is_some()));
    assert_eq!(mesh.triangle_count(), 12);
    assert!(mesh.materials[0].diffuse.abs_diff_eq(Vec3::splat(0.8), 1e-6));
    assert_eq!(mesh.bounds(), (Vec3::splat(-1.0), Vec3::splat(1.0)));
    // The file's counter-clockwise winding is kept: it agrees with its normals.
    for tri in mesh.indices.chunks_exact(3) {
        let v = [0, 1, 2].map(|k| mesh.vertices[tri[k] as usize]);
        let [a, b, c] = v.map(|v| Vec3::from(v.position));
        assert!((b - a).cross(c - a).dot(Vec3::from(v[0].normal)) > 0.0);
    }
}

#[test]
fn missing_or_broken_material_library_is_an_error() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let missing = format!("mtllib nope.mtl\n{tri}");
    let broken = format!("mtllib broken.mtl\nusemtl a\n{tri}");
    // `Kd` with one value makes tobj panic; it must come back as an error.
    let dir = temp_files(
        "mtl",
        &[("missing.obj", &missing), ("broken.obj", &broken), ("broken.mtl", "newmtl a\nKd 0.5\n")],
    );
    let message = load_obj(&dir.join("missing.obj")).expect_err("missing mtl").to_string();
    assert!(message.contains("nope.mtl"), "{message}");
    let message = load_obj(&dir.join("broken.obj")).expect_err("broken mtl").to_string();
    assert!(message.contains("broken.mtl"), "{message}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn attributes_are_validated_and_converted() {
    let obj = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvt 0.25 0.75\nvn 0 2 0\nf 1/1/1 2/1/1 3/1/1\n";
    let dir = temp_files(
        "attr",
        &[
            ("ok.obj", obj),
            ("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
            ("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"),
            ("textured.mtl", "newmtl t\nmap_Kd -s 1 1 1 -clamp on sub dir\\t.png\n"),
            ("textured.obj", "mtllib textured.mtl\nusemtl t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ],
    );
    let mesh = load_obj(&dir.join("ok.obj")).expect("ok.obj loads");
    assert_eq!(mesh.name, "ok");
    assert!(mesh.vertices.iter().all(|v| v.uv == [0.25, 0.25] && v.normal == [0.0, 1.0, 0.0]));
    assert_eq!(mesh.parts[0].material, None);
    let message = load_obj(&dir.join("nan.obj")).expect_err("nan").to_string();
    assert!(message.contains("nan.obj") && message.contains("non-finite"), "{message}");
    let message = load_obj(&dir.join("lines.obj")).expect_err("lines only").to_string();
    assert!(message.contains("contains no triangles"), "{message}");
    let message = load_obj(&dir.join("textured.obj")).expect_err("no texture").to_string();
    assert!(message.contains("texture `sub dir\\t.png` not found"), "{message}");
    assert!(message.contains("sub dir/t.png"), "{message}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bunny_loads_if_present() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes/bunny.obj");
    let Ok(text) = std::fs::read_to_string(&path) else {
        return;
    };
    // Fan triangulation of every face line.
    let expected: usize = text
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| l.split_whitespace().count().saturating_sub(3))
        .sum();
    let mesh = load_obj(&path).expect("bunny loads");
    assert!(mesh.triangle_count() > 1000, "{}", mesh.triangle_count());
    assert_eq!(mesh.triangle_count(), expected);
    assert_valid(&mesh);
    assert_unit_normals(&mesh);
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

#[test]
fn a_colour_of_fewer_than_three_numbers_names_its_line() {
    let obj = format!("mtllib a.mtl\nusemtl m\n{TRIANGLE}");
    for (mtl, key) in [("newmtl m\n\nKd 0.5\n", "Kd"), ("newmtl m\n# grey\nKa\n", "Ka")] {
        let dir = temp_files("colour", &[("a.obj", &obj), ("a.mtl", mtl)]);
        let message = load_obj(&dir.join("a.obj")).expect_err("a short colour").to_string();
        assert!(message.contains("a.mtl: line 3: `"), "{message}");
        assert!(message.contains(&format!("`{key}` needs three numbers")), "{message}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[cfg(unix)]
#[test]
fn a_library_or_texture_that_is_not_a_regular_file_is_refused() {
    // Reading /dev/zero whole never ended.
    let dir = temp_files(
        "special",
        &[
            ("zero.obj", &format!("mtllib /dev/zero\n{TRIANGLE}")),
            ("folder.obj", &format!("mtllib folder.mtl\nusemtl m\n{TRIANGLE}")),
            ("folder.mtl", "newmtl m\nmap_Kd textures\n"),
        ],
    );
    std::fs::create_dir_all(dir.join("textures")).expect("create folder");
    let message = load_obj(&dir.join("zero.obj")).expect_err("a device").to_string();
    assert!(message.starts_with("/dev/zero: ") && message.contains("not a regular file"), "{message}");
    let message = load_obj(&dir.join("folder.obj")).expect_err("a folder").to_string();
    assert!(message.contains("folder.mtl") && message.contains("is a folder"), "{message}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_texture_wider_than_gpus_take_is_refused_and_one_texel_is_enough() {
    let obj = format!("mtllib t.mtl\nusemtl m\n{TRIANGLE}");
    let dir = temp_files("texture_size", &[("wide.obj", &obj), ("t.mtl", "newmtl m\nmap_Kd wide.png\n")]);
    image::RgbaImage::new(MAX_TEXTURE_SIDE + 1, 1).save(dir.join("wide.png")).expect("write png");
    let message = load_obj(&dir.join("wide.obj")).expect_err("too wide").to_string();
    assert!(message.contains("t.mtl") && message.contains("wide.png"), "{message}");
    assert!(message.contains("8193x1 texels; at most 8192 on a side"), "{message}");
    // A one-texel texture is a plain colour, not an error.
    image::RgbaImage::from_pixel(1, 1, image::Rgba([10, 20, 30, 255]))
        .save(dir.join("wide.png"))
        .expect("png");
    let mesh = load_obj(&dir.join("wide.obj")).expect("a 1x1 texture loads");
    let texture = mesh.materials[0].diffuse_texture.as_ref().expect("the texture");
    assert_eq!((texture.width, texture.height, texture.rgba8.clone()), (1, 1, vec![10, 20, 30, 255]));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_library_named_many_times_is_read_once() {
    // 20000 `mtllib` lines naming a 1 MB file each read and parsed it again (minutes).
    let mut obj = String::from("mtllib a.mtl\nusemtl m\n");
    obj.push_str(TRIANGLE);
    obj.push_str(&"mtllib a.mtl\n".repeat(20_000));
    let mtl = format!("newmtl m\nKd 0.5 0.25 1\n{}", "# padding to make the library large\n".repeat(30_000));
    let dir = temp_files("repeated_library", &[("a.obj", &obj), ("a.mtl", &mtl)]);
    let started = std::time::Instant::now();
    let mesh = load_obj(&dir.join("a.obj")).expect("loads");
    assert!(started.elapsed().as_secs_f64() < 5.0, "took {:?}", started.elapsed());
    assert_eq!(mesh.materials.len(), 1);
    assert_eq!(mesh.materials[0].diffuse, Vec3::new(0.5, 0.25, 1.0));
    assert_eq!(mesh.parts[0].material, Some(0));
    let _ = std::fs::remove_dir_all(dir);
}
