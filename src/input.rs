//! Reading an input file's text with a size cap.
//!
//! Every file taut reads (a scene, a gate case and the scene it names, a
//! saved contact problem for `replay`, a sweep's `sweep.json` and run
//! records, a folder's lock) goes through [`read_text`]; the files a
//! report reads back from folders through [`read_regular_text`], which
//! also refuses symbolic links. A path can name
//! anything: `/dev/zero`, `/dev/urandom`, a pipe, a 30 GB log. Reading such
//! a file whole grew the process until the kernel killed it, and
//! the UTF-8 check came only after the whole read. Here the file is read in
//! chunks through a reader that stops at the cap, each chunk is checked as
//! it arrives (UTF-8, no NUL byte: no scene, JSON or TOML holds one), and
//! the first bad byte or the first byte past the cap ends the read with an
//! error naming the file, the cap and what to do.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

/// Most bytes a scene file, a gate case, a sweep's spec or a run record may
/// hold (16 MiB). The largest real inputs are far below it: the bundled
/// scenes are under 2 KiB, a scene with 10⁵ probes about 3 MiB, a sweep
/// record (a point's force and loss profiles) a few KiB.
pub const MAX_INPUT_BYTES: u64 = 16 << 20;

/// Most bytes a saved contact problem may hold (64 MiB): its Delassus
/// matrix W has up to [`crate::contact::replay::MAX_REPLAY_CONTACTS`]² =
/// 1024² entries, ≈ 25 bytes each as JSON text.
pub const MAX_REPLAY_BYTES: u64 = 64 << 20;

/// Bytes read at a time: the unit in which a bad byte or an overlong file is
/// noticed.
const CHUNK: usize = 64 << 10;

/// `n` bytes as MiB (or bytes below 1 MiB), for messages.
fn size(n: u64) -> String {
    if n >= 1 << 20 {
        format!("{} MiB", n >> 20)
    } else {
        format!("{n} bytes")
    }
}

fn refused(path: &Path, reason: String) -> Error {
    Error::io(
        path,
        std::io::Error::new(std::io::ErrorKind::InvalidData, reason),
    )
}

/// Refuse a file that is not a regular file (a FIFO, a socket, a device,
/// a folder), naming what it is.
fn refuse_special(path: &Path, t: &std::fs::FileType, what: &str) -> Result<()> {
    if t.is_file() {
        return Ok(());
    }
    let kind = if t.is_dir() {
        "a folder"
    } else {
        special_kind(t)
    };
    Err(refused(
        path,
        format!(
            "is {kind}, not a regular file, so not {what} (taut reads regular files only: a pipe or a device may block or never end)"
        ),
    ))
}

/// What a special file is, for a message.
#[cfg(unix)]
fn special_kind(t: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if t.is_fifo() {
        "a FIFO (named pipe)"
    } else if t.is_socket() {
        "a socket"
    } else if t.is_char_device() {
        "a character device"
    } else if t.is_block_device() {
        "a block device"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special_kind(_: &std::fs::FileType) -> &'static str {
    "a special file"
}

/// The text of the file at `path` (`what` names it in errors: "a scene
/// file", "a gate case"), read at most `limit` bytes: a longer file, a
/// non-UTF-8 byte or a NUL byte is refused as soon as it is read, naming the
/// file; nothing past `limit + CHUNK` bytes is ever read.
pub fn read_text(path: &Path, what: &str, limit: u64) -> Result<String> {
    // only a regular file: opening a FIFO blocks until something writes
    // it, and a device may never end or block on its first read (a FIFO
    // given as a scene, a points file or a run record would hang for
    // ever); checked before the file is opened, and again on the
    // file opened
    let kind = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    refuse_special(path, &kind.file_type(), what)?;
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let opened = file.metadata().map_err(|e| Error::io(path, e))?;
    refuse_special(path, &opened.file_type(), what)?;
    read_opened(file, path, what, limit)
}

/// The text of the file at `path` inside a folder taut was given to read
/// back (a report's inputs: `what` names them in errors), or `None` when
/// there is no such file. Only a regular file is read: a symbolic link is
/// refused, not followed (it may lead out of the folder, to any file the
/// reader may read), and so is a FIFO, socket or device (it may block or
/// never end); the file is opened without following a link and without
/// waiting on a pipe, so one swapped in after the check is refused too. A
/// file of more than `limit` bytes is refused from its size, before a byte
/// is read; the text is checked as [`read_text`] checks it.
pub fn read_regular_text(path: &Path, what: &str, limit: u64) -> Result<Option<String>> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(Error::io(path, e)),
    };
    let link = || {
        refused(
            path,
            format!(
                "is a symbolic link, so not read as {what} (only regular files in the folder are read: a link may lead anywhere)"
            ),
        )
    };
    if meta.file_type().is_symlink() {
        return Err(link());
    }
    refuse_special(path, &meta.file_type(), what)?;
    let file = match open_no_follow(path) {
        Ok(f) => f,
        Err(e) if is_link_error(&e) => return Err(link()),
        Err(e) => return Err(Error::io(path, e)),
    };
    let opened = file.metadata().map_err(|e| Error::io(path, e))?;
    refuse_special(path, &opened.file_type(), what)?;
    if opened.len() > limit {
        return Err(refused(
            path,
            format!(
                "is {}, larger than {}, the most {what} may be (not read)",
                size(opened.len()),
                size(limit)
            ),
        ));
    }
    read_opened(file, path, what, limit).map(Some)
}

/// `path` opened to read, never through a symbolic link (`O_NOFOLLOW`) and
/// without waiting for a writer if it is a FIFO (`O_NONBLOCK`; reading a
/// regular file is not changed by it).
#[cfg(unix)]
fn open_no_follow(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
        .open(path)
}

#[cfg(not(unix))]
fn open_no_follow(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

/// Whether opening failed because the path is a symbolic link (`ELOOP`
/// under `O_NOFOLLOW`).
#[cfg(unix)]
fn is_link_error(e: &std::io::Error) -> bool {
    e.raw_os_error() == Some(libc::ELOOP)
}

#[cfg(not(unix))]
fn is_link_error(_: &std::io::Error) -> bool {
    false
}

/// The text of the opened regular `file` (at `path`), read in chunks up to
/// `limit` bytes as [`read_text`] says.
fn read_opened(file: std::fs::File, path: &Path, what: &str, limit: u64) -> Result<String> {
    let mut reader = file.take(limit.saturating_add(1));
    let mut bytes: Vec<u8> = Vec::new();
    let mut chunk = vec![0u8; CHUNK];
    // bytes[..valid] are known to be whole UTF-8 characters
    let mut valid = 0;
    loop {
        let got = match reader.read(&mut chunk) {
            Ok(0) => break,
            Ok(k) => k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(Error::io(path, e)),
        };
        if bytes.len() as u64 + got as u64 > limit {
            return Err(refused(
                path,
                format!(
                    "larger than {}, the most {what} may be: it is not one (reading stopped there)",
                    size(limit)
                ),
            ));
        }
        if let Some(at) = chunk[..got].iter().position(|&b| b == 0) {
            return Err(refused(
                path,
                format!(
                    "holds a NUL byte at byte {}: not a text file, so not {what}",
                    bytes.len() + at
                ),
            ));
        }
        bytes.extend_from_slice(&chunk[..got]);
        match std::str::from_utf8(&bytes[valid..]) {
            Ok(_) => valid = bytes.len(),
            // a character split across chunks: the rest comes next
            Err(e) if e.error_len().is_none() => valid += e.valid_up_to(),
            Err(e) => {
                return Err(refused(
                    path,
                    format!(
                        "is not UTF-8 text (byte {}), so not {what}",
                        valid + e.valid_up_to()
                    ),
                ));
            }
        }
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        refused(
            path,
            format!(
                "ends inside a UTF-8 character (byte {}), so is not {what}",
                e.utf8_error().valid_up_to()
            ),
        )
    })?;
    // a byte order mark (what some editors and spreadsheets put first) is
    // no character of the text: it made the first key of a points file
    // `\u{feff}carrier.mass`
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(bytes: &[u8]) -> tempfile::NamedTempFile {
        use std::io::Write;
        let mut f = tempfile::NamedTempFile::new().unwrap();
        f.write_all(bytes).unwrap();
        f
    }

    #[test]
    fn text_within_the_cap_is_read_whole() {
        // a character split across the chunk boundary is read whole
        let mut text = "a".repeat(CHUNK - 1);
        text.push('é');
        text.push_str(&"b".repeat(CHUNK));
        let f = file(text.as_bytes());
        assert_eq!(read_text(f.path(), "a scene file", 1 << 20).unwrap(), text);
    }

    #[test]
    fn a_file_past_the_cap_is_refused_naming_it_and_the_cap() {
        let f = file(&vec![b'x'; 3 * CHUNK]);
        let e = read_text(f.path(), "a scene file", (2 * CHUNK) as u64)
            .unwrap_err()
            .to_string();
        assert!(e.contains(&f.path().display().to_string()), "{e}");
        assert!(e.contains("the most a scene file may be"), "{e}");
        // exactly the cap is fine
        assert!(read_text(f.path(), "a scene file", (3 * CHUNK) as u64).is_ok());
    }

    #[test]
    fn binary_bytes_are_refused_where_they_are() {
        let f = file(b"[beam]\nlength = \xff\n");
        let e = read_text(f.path(), "a scene file", 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(e.contains("not UTF-8 text (byte 16)"), "{e}");
        let f = file(b"[beam]\0");
        let e = read_text(f.path(), "a scene file", 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(e.contains("NUL byte at byte 6"), "{e}");
        let f = file("ab\u{e9}".as_bytes().split_last().unwrap().1);
        let e = read_text(f.path(), "a gate case", 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(e.contains("ends inside a UTF-8 character"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_fifos_are_refused_without_reading() {
        for dev in ["/dev/zero", "/dev/urandom"] {
            let e = read_text(Path::new(dev), "a scene file", MAX_INPUT_BYTES)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with(dev) && e.contains("a character device"),
                "{e}"
            );
        }
        // a FIFO nothing writes: opening it to read would block for ever
        let tmp = tempfile::tempdir().unwrap();
        let fifo = tmp.path().join("scene.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = read_text(&fifo, "a scene file", MAX_INPUT_BYTES)
                .unwrap_err()
                .to_string();
            assert!(e.contains("a FIFO (named pipe), not a regular file"), "{e}");
        }
        let e = read_text(tmp.path(), "a scene file", MAX_INPUT_BYTES)
            .unwrap_err()
            .to_string();
        assert!(e.contains("a folder"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn a_folders_file_is_read_only_when_regular_and_within_the_cap() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let what = "a report's input";
        assert!(
            read_regular_text(&d.join("none.csv"), what, 1 << 20)
                .unwrap()
                .is_none()
        );
        std::fs::write(d.join("a.csv"), "x,y\n1,2\n").unwrap();
        let a = read_regular_text(&d.join("a.csv"), what, 1 << 20).unwrap();
        assert_eq!(a.as_deref(), Some("x,y\n1,2\n"));
        // a link, even to a readable regular file, is refused
        std::os::unix::fs::symlink("/etc/passwd", d.join("link.csv")).unwrap();
        let e = read_regular_text(&d.join("link.csv"), what, 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(e.contains("is a symbolic link"), "{e}");
        // too large: refused from its size
        std::fs::write(d.join("big.csv"), vec![b'x'; 3000]).unwrap();
        let e = read_regular_text(&d.join("big.csv"), what, 2000)
            .unwrap_err()
            .to_string();
        assert!(e.contains("is 3000 bytes, larger than 2000 bytes"), "{e}");
        let made = std::process::Command::new("mkfifo")
            .arg(d.join("fifo.csv"))
            .status();
        if made.is_ok_and(|s| s.success()) {
            let e = read_regular_text(&d.join("fifo.csv"), what, 1 << 20)
                .unwrap_err()
                .to_string();
            assert!(e.contains("a FIFO (named pipe)"), "{e}");
        }
        // O_NOFOLLOW itself refuses a link (the check before it aside)
        let e = open_no_follow(&d.join("link.csv")).unwrap_err();
        assert!(is_link_error(&e), "{e}");
    }

    #[test]
    fn a_byte_order_mark_is_dropped() {
        let f = file("\u{feff}[beam]\n".as_bytes());
        assert_eq!(
            read_text(f.path(), "a scene file", 1 << 20).unwrap(),
            "[beam]\n"
        );
    }
}
