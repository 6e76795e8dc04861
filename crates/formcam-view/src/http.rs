//! HTTP/1.1 on one connection: a request's head read within the limits of
//! [`crate::request`], an answer written whole with its length, and the
//! connection kept for the next request or closed.
//!
//! Every connection has a thread of its own for as long as the client keeps
//! it, so no connection waits for another's thread to come free (the stall
//! of the page's parallel fetches behind browsers' idle keep-alive
//! connections, docs/view.md).

use std::io::{self, BufRead, BufReader, Read, Write};
use std::net::{Shutdown, TcpStream};
use std::time::Duration;

use crate::request::{MAX_HEADER_BYTES, MAX_URL_BYTES, Refusal};

/// How long a kept connection waits for its next request, and a slow
/// client for its answer to be taken.
pub(crate) const IDLE: Duration = Duration::from_secs(60);

/// How long a refused request's unread rest is read and dropped before the
/// connection closes (so the refusal is not lost to a reset).
const DRAIN: Duration = Duration::from_secs(2);

/// The most bytes of a refused request read and dropped.
const DRAIN_BYTES: u64 = 1 << 20;

/// The longest request line: the method, the longest URL, the version.
const MAX_LINE_BYTES: usize = MAX_URL_BYTES + 64;

/// A request's head as read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Head {
    /// The method, as sent (`GET`).
    pub method: String,
    /// The request target, as sent (`/api/result?x=1`).
    pub target: String,
    /// Whether the request has a body (`Content-Length` above 0 or a
    /// `Transfer-Encoding`).
    pub body: bool,
    /// Whether the client closes after this request (`Connection: close`,
    /// or HTTP/1.0 without `keep-alive`).
    pub close: bool,
}

/// What reading a head gave.
#[derive(Debug)]
pub(crate) enum Incoming {
    /// A whole head.
    Head(Head),
    /// The connection ended (or idled out) before a request began.
    End,
    /// A head refused before it was read whole; the connection closes.
    Refused(Refusal),
}

/// Reads one request's head from `reader`.
///
/// # Errors
///
/// The connection's I/O error in the middle of a head.
pub(crate) fn read_head<R: BufRead>(reader: &mut R) -> io::Result<Incoming> {
    // The request line; empty lines before it are allowed (RFC 9112 2.2).
    let mut line = Vec::new();
    loop {
        line.clear();
        let n = match read_line(reader, &mut line, MAX_LINE_BYTES) {
            Ok(n) => n,
            Err(e) if before_request(&e) => return Ok(Incoming::End),
            Err(e) => return Err(e),
        };
        if n == 0 {
            return Ok(Incoming::End);
        }
        if !ends_line(&line) {
            return Ok(Incoming::Refused(Refusal::UrlTooLong));
        }
        if trim_end(&line).is_empty() {
            continue;
        }
        break;
    }
    let Some((method, target, version)) = request_line(trim_end(&line)) else {
        return Ok(Incoming::Refused(Refusal::Path));
    };
    let mut head = Head {
        method,
        target,
        body: false,
        close: false,
    };
    let (mut asked_close, mut keep_alive) = (false, false);
    let mut header_bytes = 0;
    loop {
        line.clear();
        let room = (MAX_HEADER_BYTES + 1).saturating_sub(header_bytes);
        let n = read_line(reader, &mut line, room)?;
        header_bytes += n;
        if header_bytes > MAX_HEADER_BYTES {
            return Ok(Incoming::Refused(Refusal::HeadersTooLarge));
        }
        if n == 0 || !ends_line(&line) {
            return Err(io::Error::from(io::ErrorKind::UnexpectedEof));
        }
        let text = trim_end(&line);
        if text.is_empty() {
            break;
        }
        let Some((name, value)) = std::str::from_utf8(text)
            .ok()
            .and_then(|t| t.split_once(':'))
        else {
            return Ok(Incoming::Refused(Refusal::Path));
        };
        let value = value.trim();
        if name.eq_ignore_ascii_case("content-length") {
            head.body |= value != "0";
        } else if name.eq_ignore_ascii_case("transfer-encoding") {
            head.body = true;
        } else if name.eq_ignore_ascii_case("connection") {
            let value = value.to_ascii_lowercase();
            asked_close |= value.contains("close");
            keep_alive |= value.contains("keep-alive");
        }
    }
    head.close = asked_close || (version == HttpVersion::V1_0 && !keep_alive);
    Ok(Incoming::Head(head))
}

/// An answer: status, content type, body, and extra headers.
pub(crate) struct Answer<'a> {
    /// The HTTP status.
    pub status: u16,
    /// `Content-Type`.
    pub kind: &'a str,
    /// The body.
    pub body: &'a [u8],
    /// Whether it says `Allow: GET` (a refused method).
    pub allow_get: bool,
    /// Whether the connection closes after it.
    pub close: bool,
}

/// Writes `answer` whole (head and body) and flushes it.
///
/// # Errors
///
/// The connection's I/O error.
pub(crate) fn write_answer<W: Write>(out: &mut W, answer: &Answer<'_>) -> io::Result<()> {
    let mut head = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\n\
         Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\n",
        answer.status,
        reason(answer.status),
        answer.kind,
        answer.body.len()
    );
    if answer.allow_get {
        head.push_str("Allow: GET\r\n");
    }
    head.push_str(if answer.close {
        "Connection: close\r\n\r\n"
    } else {
        "Connection: keep-alive\r\n\r\n"
    });
    out.write_all(head.as_bytes())?;
    out.write_all(answer.body)?;
    out.flush()
}

/// Ends a connection after its last answer: no more is sent, and what the
/// client still sends (a refused request's rest) is read and dropped for a
/// moment, so that closing does not reset the connection before the client
/// has read the answer.
pub(crate) fn close(stream: &TcpStream, unread: bool) {
    let _ = stream.shutdown(Shutdown::Write);
    if unread {
        let _ = stream.set_read_timeout(Some(DRAIN));
        let _ = io::copy(&mut stream.take(DRAIN_BYTES), &mut io::sink());
    }
}

/// A line up to `limit` bytes (with its `\n`) appended to `line`: the bytes
/// read (0 at the end of the stream).
fn read_line<R: BufRead>(reader: &mut R, line: &mut Vec<u8>, limit: usize) -> io::Result<usize> {
    let limit = u64::try_from(limit).unwrap_or(u64::MAX);
    reader.take(limit).read_until(b'\n', line)
}

/// Whether `e` is the end of an idle connection rather than a broken request.
fn before_request(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::WouldBlock
            | io::ErrorKind::TimedOut
            | io::ErrorKind::ConnectionReset
            | io::ErrorKind::ConnectionAborted
            | io::ErrorKind::UnexpectedEof
    )
}

fn ends_line(line: &[u8]) -> bool {
    line.last() == Some(&b'\n')
}

fn trim_end(line: &[u8]) -> &[u8] {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    line.strip_suffix(b"\r").unwrap_or(line)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HttpVersion {
    V1_0,
    V1_1,
}

/// `METHOD TARGET HTTP/1.x`.
fn request_line(line: &[u8]) -> Option<(String, String, HttpVersion)> {
    let text = std::str::from_utf8(line).ok()?;
    let mut parts = text.split(' ');
    let (method, target, version) = (parts.next()?, parts.next()?, parts.next()?);
    if parts.next().is_some() || method.is_empty() || target.is_empty() {
        return None;
    }
    let version = match version {
        "HTTP/1.1" => HttpVersion::V1_1,
        "HTTP/1.0" => HttpVersion::V1_0,
        _ => return None,
    };
    Some((method.to_string(), target.to_string(), version))
}

fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        404 => "Not Found",
        405 => "Method Not Allowed",
        413 => "Content Too Large",
        414 => "URI Too Long",
        431 => "Request Header Fields Too Large",
        _ => "",
    }
}

/// A reader of `stream`'s requests.
pub(crate) fn reader(stream: &TcpStream) -> io::Result<BufReader<TcpStream>> {
    Ok(BufReader::new(stream.try_clone()?))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    fn head(bytes: &[u8]) -> Incoming {
        read_head(&mut io::Cursor::new(bytes.to_vec())).unwrap()
    }

    #[test]
    fn heads_read_one_after_another_on_a_kept_connection() {
        let mut r = io::Cursor::new(
            b"GET /a HTTP/1.1\r\nHost: x\r\n\r\nGET /b?t=1 HTTP/1.1\r\nConnection: close\r\n\r\n"
                .to_vec(),
        );
        let Incoming::Head(a) = read_head(&mut r).unwrap() else {
            panic!("no head")
        };
        assert_eq!((a.method.as_str(), a.target.as_str()), ("GET", "/a"));
        assert!(!a.close && !a.body);
        let Incoming::Head(b) = read_head(&mut r).unwrap() else {
            panic!("no head")
        };
        assert_eq!(b.target, "/b?t=1");
        assert!(b.close);
        assert!(matches!(read_head(&mut r).unwrap(), Incoming::End));
    }

    #[test]
    fn bodies_long_lines_and_big_headers_are_refused() {
        let Incoming::Head(h) = head(b"GET / HTTP/1.1\r\nContent-Length: 5\r\n\r\nhello") else {
            panic!("no head")
        };
        assert!(h.body);
        let long = format!("GET /{} HTTP/1.1\r\n\r\n", "a".repeat(2 * MAX_URL_BYTES));
        assert!(matches!(
            head(long.as_bytes()),
            Incoming::Refused(Refusal::UrlTooLong)
        ));
        let big = format!(
            "GET / HTTP/1.1\r\nX: {}\r\n\r\n",
            "b".repeat(MAX_HEADER_BYTES)
        );
        assert!(matches!(
            head(big.as_bytes()),
            Incoming::Refused(Refusal::HeadersTooLarge)
        ));
        assert!(matches!(
            head(b"GET / HTTP/2.0\r\n\r\n"),
            Incoming::Refused(Refusal::Path)
        ));
        assert!(matches!(head(b"GET / HTTP/1.0\r\n\r\n"), Incoming::Head(h) if h.close));
    }

    #[test]
    fn an_answer_says_its_length() {
        let mut out = Vec::new();
        write_answer(
            &mut out,
            &Answer {
                status: 405,
                kind: "text/plain",
                body: b"no\n",
                allow_get: true,
                close: true,
            },
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.starts_with("HTTP/1.1 405 Method Not Allowed\r\n"),
            "{text}"
        );
        assert!(text.contains("Content-Length: 3\r\n"), "{text}");
        assert!(text.contains("Allow: GET\r\n"), "{text}");
        assert!(text.ends_with("\r\n\r\nno\n"), "{text}");
    }
}
