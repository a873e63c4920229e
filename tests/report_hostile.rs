//! `taut report` over folders someone may have tampered with: nothing read
//! from a folder reaches the page as markup, only regular files within a
//! size cap are read (never through a symbolic link, never a FIFO), and a
//! folder still marked `INCOMPLETE` is shown as partial
//! (docs/output.md, "report.html").

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use taut::app::{ReportRequest, report};

/// A table taut could have written, so that a folder has one good output
/// besides the hostile one.
const SPANS_CSV: &str = "span,force_mean_N\n0,120.5\n1,118.25\n";

/// The page made from `dir` (written beside it).
fn page_of(dir: &Path) -> String {
    let out = dir.parent().unwrap().join("report.html");
    report(&ReportRequest {
        dirs: vec![dir.to_path_buf()],
        out: Some(out.clone()),
    })
    .unwrap();
    std::fs::read_to_string(out).unwrap()
}

/// A fresh folder `d` in a temporary one, with a good `spans.csv`.
fn folder() -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("d");
    std::fs::create_dir(&d).unwrap();
    std::fs::write(d.join("spans.csv"), SPANS_CSV).unwrap();
    (tmp, d)
}

/// The page with every `data:` URL's base64 text taken out: what is left is
/// the page's own markup.
fn markup(page: &str) -> String {
    let mut out = String::new();
    let mut rest = page;
    while let Some(at) = rest.find(";base64,") {
        out.push_str(&rest[..at + 8]);
        let tail = &rest[at + 8..];
        let end = tail.find('"').unwrap_or(tail.len());
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn a_hostile_svg_never_reaches_the_page_as_markup() {
    let (_tmp, d) = folder();
    let svg = r#"<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50" onload="document.title='pwned'">
<script>document.title='pwned'</script>
<foreignObject width="100" height="50"><iframe xmlns="http://www.w3.org/1999/xhtml" src="javascript:alert(1)"></iframe></foreignObject>
<image href="http://evil.example/beacon.png" width="10" height="10"/>
<rect width="100" height="50" fill="blue"/>
</svg>
"#;
    std::fs::write(d.join("force.svg"), svg).unwrap();
    let page = page_of(&d);
    let m = markup(&page);
    for bad in [
        "<script",
        "onload",
        "foreignObject",
        "<iframe",
        "javascript:",
        "evil.example",
        "<image",
        "<svg",
    ] {
        assert!(
            !m.to_ascii_lowercase().contains(&bad.to_ascii_lowercase()),
            "{bad} in the page's markup:\n{m}"
        );
    }
    assert!(
        m.contains("<img src=\"data:image/svg+xml;base64,\" alt=\"force.svg: "),
        "the plot is an image:\n{m}"
    );
    assert!(
        page.contains(
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; style-src 'unsafe-inline'\">"
        ),
        "the page forbids script and fetches"
    );
}

#[test]
fn a_file_named_svg_that_is_no_svg_is_left_out_and_named() {
    let (_tmp, d) = folder();
    std::fs::write(
        d.join("force.svg"),
        "<html><body><p id=\"x\">not a plot</p></body></html>\n",
    )
    .unwrap();
    let page = page_of(&d);
    assert!(!page.contains("not a plot"), "{page}");
    assert!(!page.contains("data:image/svg+xml"), "{page}");
    assert!(
        page.contains("Left out of this page") && page.contains("<li>force.svg: not an SVG image"),
        "{page}"
    );
}

#[cfg(unix)]
#[test]
fn a_table_that_is_a_symbolic_link_is_left_out_not_followed() {
    let (tmp, d) = folder();
    let secret = tmp.path().join("secret.txt");
    std::fs::write(&secret, "name,secret\nroot,hunter2\n").unwrap();
    std::os::unix::fs::symlink(&secret, d.join("standard.csv")).unwrap();
    std::os::unix::fs::symlink("/etc/passwd", d.join("supports.csv")).unwrap();
    let page = page_of(&d);
    assert!(
        !page.contains("hunter2") && !page.contains("root:"),
        "{page}"
    );
    assert!(
        page.contains("<li>standard.csv: is a symbolic link")
            && page.contains("<li>supports.csv: is a symbolic link"),
        "{page}"
    );
    // the good table is there
    assert!(page.contains("118.25"), "{page}");
}

#[cfg(unix)]
#[test]
fn a_fifo_named_like_a_table_does_not_hang_the_report() {
    let (_tmp, d) = folder();
    let made = std::process::Command::new("mkfifo")
        .arg(d.join("standard.csv"))
        .status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("skipped: no mkfifo");
        return;
    }
    let (tx, rx) = mpsc::channel();
    let dir = d.clone();
    std::thread::spawn(move || {
        let _ = tx.send(page_of(&dir));
    });
    // opening a FIFO nothing writes blocks for ever; a report takes
    // milliseconds
    let page = rx
        .recv_timeout(Duration::from_secs(30))
        .expect("the report hung on a FIFO");
    assert!(
        page.contains("<li>standard.csv: is a FIFO (named pipe), not a regular file"),
        "{page}"
    );
}

#[test]
fn a_file_over_the_cap_is_left_out_unread() {
    let (_tmp, d) = folder();
    // 64 MiB, four times the cap, as a sparse file (no disk written)
    let f = std::fs::File::create(d.join("standard.csv")).unwrap();
    f.set_len(64 << 20).unwrap();
    drop(f);
    let page = page_of(&d);
    assert!(
        page.contains("<li>standard.csv: is 64 MiB, larger than 16 MiB"),
        "{}",
        &page[..page.len().min(4000)]
    );
    assert!(page.len() < 1 << 20, "the page is {} bytes", page.len());
}

#[test]
fn a_file_that_is_not_utf8_is_left_out_and_named() {
    let (_tmp, d) = folder();
    std::fs::write(d.join("standard.csv"), b"a,b\n1,\xff\n").unwrap();
    let page = page_of(&d);
    assert!(
        page.contains("<li>standard.csv: is not UTF-8 text (byte 6)"),
        "{page}"
    );
}

#[test]
fn an_incomplete_folder_is_shown_as_partial() {
    let (tmp, d) = folder();
    std::fs::write(
        d.join("INCOMPLETE"),
        "taut run stopped while writing its outputs: <disk full>\n",
    )
    .unwrap();
    let whole = tmp.path().join("whole");
    std::fs::create_dir(&whole).unwrap();
    std::fs::write(whole.join("spans.csv"), SPANS_CSV).unwrap();
    let out = tmp.path().join("report.html");
    report(&ReportRequest {
        dirs: vec![d.clone(), whole.clone()],
        out: Some(out.clone()),
    })
    .unwrap();
    let page = std::fs::read_to_string(out).unwrap();
    let (first, second) = page.split_at(page.find("<section id=\"f1\"").unwrap());
    assert!(
        first.contains("— INCOMPLETE</h2>")
            && first.contains("<div class=\"incomplete\"><p>INCOMPLETE:")
            && first.contains("not a result")
            && first.contains("<div class=\"partial\">"),
        "{first}"
    );
    // the marker's text, escaped
    assert!(first.contains("&lt;disk full&gt;"), "{first}");
    assert!(!second.contains("INCOMPLETE"), "{second}");
    // and the header says so
    assert!(page.contains("1 folder INCOMPLETE"), "{page}");
}

#[test]
fn an_incomplete_folder_with_nothing_else_is_shown_not_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("d");
    std::fs::create_dir(&d).unwrap();
    std::fs::write(d.join("INCOMPLETE"), "taut run was writing\n").unwrap();
    let page = page_of(&d);
    assert!(page.contains("<div class=\"incomplete\">"), "{page}");
}
