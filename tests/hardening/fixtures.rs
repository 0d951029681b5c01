//! Every rejected input of tests/bad/ and the text forms a scene may take.

use super::*;

#[test]
fn every_bad_fixture_is_rejected_with_its_line_and_no_output() {
    let mut checked = 0;
    for entry in fs::read_dir(bad_dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        if path.extension().is_none_or(|e| e != "sc") || name == "bom_crlf_valid.sc" {
            continue;
        }
        let out = TempDir::new("bad");
        let o = render_into(&path, &out);
        assert_rejected(&path, expected_line(&path), &o, &out);
        checked += 1;
    }
    assert!(checked >= 27, "only {checked} fixtures");
}

#[test]
fn bom_crlf_valid_scene_renders() {
    let out = TempDir::new("bom");
    let o = render_into(&bad_dir().join("bom_crlf_valid.sc"), &out);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
    assert_eq!(out.entries(), ["depth.npy", "ids.npy", "out.png"]);
    let img = fs::read(out.join("out.png")).unwrap();
    assert_eq!(&img[..8], b"\x89PNG\r\n\x1a\n");
    // Both primitives are visible: ids 0 and 1 appear in the id buffer.
    let ids = fs::read(out.join("ids.npy")).unwrap();
    let ids: Vec<i32> = ids[128..]
        .chunks(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert!(ids.contains(&0) && ids.contains(&1), "{ids:?}");
}

#[test]
fn one_megabyte_line_is_rejected() {
    let input = TempDir::new("long-in");
    let path = input.join("long_line.sc");
    let mut text = String::from(CAM);
    text.push_str("sphere 0 0 0 1 ");
    text.push_str(&"7 ".repeat(512 * 1024));
    text.push('\n');
    assert!(text.len() > 1 << 20);
    fs::write(&path, text).unwrap();
    let out = TempDir::new("long-out");
    let o = render_into(&path, &out);
    assert_rejected(&path, Some(2), &o, &out);
    assert!(stderr(&o).contains("line is"), "{}", stderr(&o));
    // A long line is reported in bytes, not echoed.
    assert!(stderr(&o).len() < 300);
}
