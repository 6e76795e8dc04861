//! What a request may ask: a GET of a short URL without a body, a path of
//! plain names (no `..`, no hidden or empty segment, no backslash or
//! control character, also when percent-encoded), and a file only where it
//! resolves inside the result folder.

use std::path::{Path, PathBuf};

/// The longest URL served, bytes.
pub const MAX_URL_BYTES: usize = 2048;

/// The most header bytes of a request.
pub const MAX_HEADER_BYTES: usize = 16 * 1024;

/// Why a request is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Refusal {
    /// Not a GET.
    #[error("only GET is served")]
    Method,
    /// The URL is longer than [`MAX_URL_BYTES`].
    #[error("URL longer than {MAX_URL_BYTES} bytes")]
    UrlTooLong,
    /// The headers are longer than [`MAX_HEADER_BYTES`].
    #[error("headers longer than {MAX_HEADER_BYTES} bytes")]
    HeadersTooLarge,
    /// A request with a body.
    #[error("a GET request has no body")]
    Body,
    /// A path that is not a plain relative name.
    #[error(
        "not a plain path: no `..`, `.` or hidden names, no backslash, control characters or bad escapes"
    )]
    Path,
    /// Nothing there (or outside the result folder).
    #[error("not found")]
    NotFound,
    /// A `Host` other than this machine's loopback names: a page of
    /// another site whose name was pointed at 127.0.0.1 (DNS rebinding).
    #[error("only 127.0.0.1, localhost and [::1] are served as the host")]
    Host,
}

impl Refusal {
    /// The HTTP status.
    pub fn status(self) -> u16 {
        match self {
            Refusal::Method => 405,
            Refusal::UrlTooLong => 414,
            Refusal::HeadersTooLarge => 431,
            Refusal::Body => 413,
            Refusal::Path => 400,
            Refusal::NotFound => 404,
            Refusal::Host => 403,
        }
    }
}

/// Whether a request's `Host` header names this machine's loopback
/// (`127.0.0.1`, `localhost` or `[::1]`, any port); no header is taken as
/// the loopback (HTTP/1.0).
pub fn loopback_host(host: Option<&[u8]>) -> bool {
    let Some(host) = host else {
        return true;
    };
    let Ok(host) = std::str::from_utf8(host) else {
        return false;
    };
    let name = match host.strip_prefix('[') {
        // An IPv6 literal: up to its closing bracket.
        Some(rest) => rest.split(']').next().unwrap_or(""),
        None => host.split(':').next().unwrap_or(""),
    };
    name == "127.0.0.1" || name.eq_ignore_ascii_case("localhost") || name == "::1"
}

/// A URL split into its decoded path segments and its query.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    /// The path's segments, percent-decoded.
    pub segments: Vec<String>,
    /// The query (after `?`), as sent.
    pub query: String,
}

impl Target {
    /// Splits and checks a request target (`/a/b?q`).
    ///
    /// # Errors
    ///
    /// [`Refusal::UrlTooLong`], or [`Refusal::Path`] for anything but an
    /// absolute path of plain segments.
    pub fn parse(url: &str) -> Result<Self, Refusal> {
        if url.len() > MAX_URL_BYTES {
            return Err(Refusal::UrlTooLong);
        }
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        let rest = path.strip_prefix('/').ok_or(Refusal::Path)?;
        let mut segments = Vec::new();
        if !rest.is_empty() {
            for raw in rest.split('/') {
                let s = decode(raw).ok_or(Refusal::Path)?;
                let plain = !s.is_empty()
                    && !s.starts_with('.')
                    && !s.contains(['/', '\\', ':'])
                    && !s.chars().any(char::is_control);
                if !plain {
                    return Err(Refusal::Path);
                }
                segments.push(s);
            }
        }
        Ok(Self {
            segments,
            query: query.to_string(),
        })
    }

    /// The value of `key` in the query.
    pub fn param(&self, key: &str) -> Option<&str> {
        self.query
            .split('&')
            .filter_map(|kv| kv.split_once('='))
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v)
    }

    /// The value of `key` in the query, percent-decoded (`None` also for a
    /// bad escape).
    pub fn param_decoded(&self, key: &str) -> Option<String> {
        self.param(key).and_then(decode)
    }
}

/// Percent-decoding into UTF-8; `None` for a bad escape or bytes that are
/// no UTF-8.
fn decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// The regular file `segments` name under `root` (canonical), where it
/// resolves, symlinks followed, inside `root`.
///
/// # Errors
///
/// [`Refusal::NotFound`] for a missing file, a folder, or a file outside.
pub fn file_under(root: &Path, segments: &[String]) -> Result<PathBuf, Refusal> {
    let mut path = root.to_path_buf();
    path.extend(segments);
    let real = path.canonicalize().map_err(|_| Refusal::NotFound)?;
    if !real.starts_with(root) || !real.is_file() {
        return Err(Refusal::NotFound);
    }
    Ok(real)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn only_loopback_hosts_are_served() {
        for ok in [
            None,
            Some("127.0.0.1:8080"),
            Some("127.0.0.1"),
            Some("localhost:41234"),
            Some("LOCALHOST"),
            Some("[::1]:80"),
        ] {
            assert!(loopback_host(ok.map(str::as_bytes)), "{ok:?}");
        }
        for bad in [
            "evil.example:8080",
            "127.0.0.1.evil.example",
            "localhost.evil.example:80",
            "[::2]:80",
            "10.0.0.1:8080",
            "",
        ] {
            assert!(!loopback_host(Some(bad.as_bytes())), "{bad}");
        }
        assert!(!loopback_host(Some(b"\xff:80")));
        assert_eq!(Refusal::Host.status(), 403);
    }

    #[test]
    fn plain_paths_split_and_decode() {
        let t = Target::parse("/files/layer-01/path%20a.csv?x=1&samples=20").unwrap();
        assert_eq!(t.segments, ["files", "layer-01", "path a.csv"]);
        assert_eq!(t.param("samples"), Some("20"));
        assert_eq!(t.param("y"), None);
        let q = Target::parse("/api/studio/job?file=my%20job.toml").unwrap();
        assert_eq!(q.param_decoded("file").as_deref(), Some("my job.toml"));
        assert_eq!(
            Target::parse("/a?file=%zz").unwrap().param_decoded("file"),
            None
        );
        assert!(Target::parse("/").unwrap().segments.is_empty());
    }

    #[test]
    fn traversal_in_any_spelling_is_refused() {
        for url in [
            "/files/../etc/passwd",
            "/files/%2e%2e/etc/passwd",
            "/files/%2E%2E%2Fetc",
            "/files/a%2f..%2f..%2fb",
            "/files/..%5c..%5cb",
            "/files//etc/passwd",
            "/files/.formcam-run",
            "/files/a%00b",
            "/files/%zz",
            "/files/C:%5Cwin",
            "files/x",
            "//etc/passwd",
            "http://evil/x",
        ] {
            assert_eq!(Target::parse(url), Err(Refusal::Path), "{url}");
        }
        let long = format!("/{}", "a".repeat(MAX_URL_BYTES));
        assert_eq!(Target::parse(&long), Err(Refusal::UrlTooLong));
    }
}
