use super::*;

/// A fresh, empty folder under the system temp dir, removed on drop (also used by
/// `set.rs`'s tests).
pub(super) struct TestDir(pub(super) PathBuf);

impl TestDir {
    pub(super) fn new(name: &str) -> TestDir {
        static N: AtomicU64 = AtomicU64::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("lanecast-output-{}-{n}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        TestDir(dir)
    }

    /// Names of the entries in the folder, sorted (temporary files included).
    pub(super) fn entries(&self) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn test_pixels(w: u32, h: u32) -> Vec<u8> {
    (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect()
}

/// A writer that takes `room` bytes, then fails with `kind`.
struct Failing {
    room: usize,
    kind: io::ErrorKind,
}

impl Write for Failing {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.room == 0 {
            return Err(io::Error::from(self.kind));
        }
        let n = buf.len().min(self.room);
        self.room -= n;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

#[test]
fn encode_errors_keep_the_writers_error_kind() {
    let (w, h) = (300, 200);
    let rgb = test_pixels(w, h);
    for format in [ImageFormat::Png, ImageFormat::Bmp] {
        for room in [0, 10, 5000] {
            for kind in [io::ErrorKind::BrokenPipe, io::ErrorKind::StorageFull] {
                let mut out = Failing { room, kind };
                let e = encode_image(&mut out, format, w, h, &rgb).unwrap_err();
                assert_eq!(e.kind(), kind, "{format:?} after {room} bytes");
            }
        }
    }
}

#[test]
fn png_and_bmp_round_trip() {
    let dir = TestDir::new("images");
    let (w, h) = (17, 5); // odd width exercises BMP row padding
    let rgb = test_pixels(w, h);
    for name in ["a.png", "b.BMP", "c.Png"] {
        let path = dir.0.join(name);
        write_image(&path, w, h, &rgb).unwrap();
        let back = image::open(&path).unwrap().to_rgb8();
        assert_eq!(back.dimensions(), (w, h), "{name}");
        assert_eq!(back.as_raw(), &rgb, "{name}");
    }
    assert_eq!(dir.entries(), ["a.png", "b.BMP", "c.Png"]);
}

#[test]
fn unknown_extension_is_a_usage_error() {
    for name in ["out.jpg", "out", "out.png.txt", ".png"] {
        let err = image_format(Path::new(name)).unwrap_err();
        assert!(matches!(err, Error::Usage(_)), "{name}");
        let msg = err.to_string();
        assert!(
            msg.contains(name) && msg.contains(".png") && msg.contains(".bmp"),
            "{msg}"
        );
    }
    assert_eq!(
        image_format(Path::new("x/y.PNG")).unwrap(),
        ImageFormat::Png
    );
    assert_eq!(image_format(Path::new("y.bmp")).unwrap(), ImageFormat::Bmp);
}

#[test]
fn missing_folder_fails_and_creates_nothing() {
    let dir = TestDir::new("missing");
    let target = dir.0.join("nope").join("out.png");
    let err = write_image(&target, 2, 2, &test_pixels(2, 2)).unwrap_err();
    match &err {
        Error::Io { path, .. } => assert_eq!(path, &target),
        other => panic!("expected an I/O error, got {other:?}"),
    }
    assert_eq!(err.exit_code(), 1);
    // A wrong pixel count is caught before any file is created.
    let short = write_image(&dir.0.join("a.png"), 2, 2, &[0; 11]);
    assert!(matches!(short, Err(Error::Failed(_))));
    assert!(dir.entries().is_empty());
}

#[test]
fn failed_write_keeps_existing_file_and_leaves_no_temp() {
    let dir = TestDir::new("keep");
    let target = dir.0.join("out.bin");
    fs::write(&target, b"old").unwrap();

    // Failure after the temporary file exists (the content producer fails).
    let err = write_atomic_with(&target, |w| {
        w.write_all(&[0; 100_000])?;
        Err(io::Error::other("disk on fire"))
    })
    .unwrap_err();
    assert!(err.to_string().contains("out.bin") && err.to_string().contains("disk on fire"));
    assert_eq!(fs::read(&target).unwrap(), b"old");
    assert_eq!(dir.entries(), ["out.bin"]);

    // Failure at the rename: the target is a folder.
    let sub = dir.0.join("sub.png");
    fs::create_dir(&sub).unwrap();
    assert!(write_image(&sub, 1, 1, &[1, 2, 3]).is_err());
    assert!(sub.is_dir());
    assert_eq!(dir.entries(), ["out.bin", "sub.png"]);

    // Failure because the "folder" is a file.
    assert!(write_atomic(&target.join("x.bin"), b"new").is_err());
    assert_eq!(fs::read(&target).unwrap(), b"old");

    // Success replaces the content and leaves no temporary file either.
    write_atomic(&target, b"new").unwrap();
    assert_eq!(fs::read(&target).unwrap(), b"new");
    assert_eq!(dir.entries(), ["out.bin", "sub.png"]);
}

#[cfg(unix)]
#[test]
fn read_only_folder_keeps_existing_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = TestDir::new("readonly");
    let target = dir.0.join("out.png");
    fs::write(&target, b"old").unwrap();
    fs::set_permissions(&dir.0, fs::Permissions::from_mode(0o555)).unwrap();
    // Root (common in containers) ignores permission bits: nothing to test there.
    let probe = dir.0.join("probe");
    let enforced = File::create(&probe).is_err();
    let _ = fs::remove_file(&probe);
    if enforced {
        assert!(write_image(&target, 1, 1, &[1, 2, 3]).is_err());
        assert_eq!(fs::read(&target).unwrap(), b"old");
    }
    fs::set_permissions(&dir.0, fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(dir.entries(), ["out.png"]);
}

#[test]
fn same_file_with_and_without_existing_target() {
    let dir = TestDir::new("same");
    let a = dir.0.join("scene.txt");
    fs::write(&a, b"x").unwrap();
    let up = dir.0.join("..").join(dir.0.file_name().unwrap());
    assert!(same_file(&a, &up.join(".").join("scene.txt")));
    assert!(!same_file(&a, &dir.0.join("out.png")));
    // Neither exists yet: compared through the canonical parent.
    let b = dir.0.join("new.png");
    assert!(same_file(&b, &dir.0.join(".").join("new.png")));
    assert!(!same_file(&b, &dir.0.join("other.png")));
    #[cfg(unix)]
    {
        let link = dir.0.join("link.txt");
        std::os::unix::fs::symlink(&a, &link).unwrap();
        assert!(same_file(&a, &link));
    }
}
