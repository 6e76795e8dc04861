//! A plain HTTP/1.1 client for the servers formcam starts on 127.0.0.1:
//! one request per connection (`Connection: close`), the answer read to
//! its end.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

/// A server's answer: the status, the head (status line and headers) and
/// the body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Answer {
    /// The status code (0 when the answer had no status line).
    pub status: u16,
    /// The status line and the headers, as sent.
    pub head: String,
    /// The body.
    pub body: Vec<u8>,
}

impl Answer {
    /// The body as JSON (`Null` when it is no JSON).
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body).unwrap_or(serde_json::Value::Null)
    }

    /// The body as text (lossy).
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    /// The status line (`HTTP/1.1 200 OK`).
    pub fn status_line(&self) -> &str {
        self.head.lines().next().unwrap_or("")
    }
}

/// Sends `request` to `addr` as it is and reads the answer to its end (at
/// most `timeout` between reads).
pub fn send(addr: SocketAddr, request: &[u8], timeout: Duration) -> Answer {
    let mut out = Vec::new();
    if let Ok(mut s) = TcpStream::connect(addr) {
        let _ = s.set_read_timeout(Some(timeout));
        if s.write_all(request).is_ok() {
            let _ = s.read_to_end(&mut out);
        }
    }
    let (head, body) = match out.windows(4).position(|w| w == b"\r\n\r\n") {
        Some(i) => (
            String::from_utf8_lossy(&out[..i]).into_owned(),
            out[i + 4..].to_vec(),
        ),
        None => (String::from_utf8_lossy(&out).into_owned(), Vec::new()),
    };
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    Answer { status, head, body }
}

/// A GET of `url` (a path) from the server at `addr`, naming `localhost`.
pub fn get(addr: SocketAddr, url: &str) -> Answer {
    let request = format!("GET {url} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n");
    send(addr, request.as_bytes(), Duration::from_secs(120))
}

/// A POST of the JSON text `body` to `url` on the server at `addr`.
pub fn post_json(addr: SocketAddr, url: &str, body: &str) -> Answer {
    let request = format!(
        "POST {url} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    send(addr, request.as_bytes(), Duration::from_secs(120))
}
