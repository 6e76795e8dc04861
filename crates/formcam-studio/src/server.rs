//! The studio's HTTP server: on 127.0.0.1 only, on formcam-view's
//! connection loop (`serve_router`: its limits, kept-alive connections and
//! refusals of oversized heads); GET and POST, a POST's body JSON of at
//! most [`MAX_BODY_BYTES`]. Each request is answered by [`Studio::answer`]
//! on a blocking thread (a run's view may take a while to open).

use std::net::SocketAddr;
use std::sync::Arc;
use std::thread;

use axum::Router;
use axum::body::to_bytes;
use axum::extract::{Request, State};
use axum::http::{HeaderValue, Method, header};
use axum::response::Response;
use formcam_view::request::Refusal;
use formcam_view::{Local, has_body, head_refusal, refused, reply};

use crate::{MAX_BODY_BYTES, Studio, StudioError, StudioMethod};

/// A studio listening on 127.0.0.1.
#[derive(Debug)]
pub struct StudioServer {
    local: Local,
    studio: Arc<Studio>,
}

impl StudioServer {
    /// Listens for `studio` on `127.0.0.1:port` (0: any free port).
    ///
    /// # Errors
    ///
    /// [`StudioError::Bind`].
    pub fn bind(studio: Studio, port: u16) -> Result<Self, StudioError> {
        let local = Local::bind(port).map_err(|source| StudioError::Bind { port, source })?;
        Ok(Self {
            local,
            studio: Arc::new(studio),
        })
    }

    /// `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        self.local.url()
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.local.addr()
    }

    /// Answers requests until the process ends.
    pub fn serve(self) {
        let app = self.router();
        self.local.serve(app);
    }

    /// Answers requests on a background thread (tests, embedding).
    pub fn spawn(self) -> thread::JoinHandle<()> {
        let app = self.router();
        self.local.spawn(app)
    }

    fn router(&self) -> Router {
        Router::new()
            .fallback(answer)
            .with_state(Arc::clone(&self.studio))
    }
}

/// Every request: refused by its head, its method or its body, or
/// answered by the studio.
async fn answer(State(studio): State<Arc<Studio>>, request: Request) -> Response {
    if let Some(r) = head_refusal(&request) {
        return refused(r);
    }
    let method = match *request.method() {
        Method::GET if has_body(&request) => return refused(Refusal::Body),
        Method::GET => StudioMethod::Get,
        Method::POST => StudioMethod::Post,
        _ => return closing(405, "only GET and POST are served", Some("GET, POST")),
    };
    let url = request.uri().to_string();
    let body = if method == StudioMethod::Post {
        match post_body(request).await {
            Ok(b) => b,
            Err(r) => return r,
        }
    } else {
        Vec::new()
    };
    let answered = tokio::task::spawn_blocking(move || studio.answer(method, &url, &body)).await;
    let Ok(a) = answered else {
        return reply(500, JSON, br#"{"error":"the answer failed"}"#.to_vec());
    };
    let mut response = reply(a.status, a.kind, a.body);
    if let Some(to) = a.location.and_then(|l| HeaderValue::from_str(&l).ok()) {
        response.headers_mut().insert(header::LOCATION, to);
    }
    response
}

/// A POST's body: JSON, at most [`MAX_BODY_BYTES`]; none for a POST that
/// sends none (cancel).
async fn post_body(request: Request) -> Result<Vec<u8>, Response> {
    if !has_body(&request) {
        return Ok(Vec::new());
    }
    let headers = request.headers();
    let json = headers
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.trim_start().starts_with(JSON));
    if !json {
        return Err(closing(
            415,
            "a POST's body is JSON (application/json)",
            None,
        ));
    }
    let too_long = format!("a POST's body is at most {MAX_BODY_BYTES} bytes");
    let declared = headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<usize>().ok());
    if declared.is_some_and(|n| n > MAX_BODY_BYTES) {
        return Err(closing(413, &too_long, None));
    }
    to_bytes(request.into_body(), MAX_BODY_BYTES)
        .await
        .map(|b| b.to_vec())
        .map_err(|_| closing(413, &too_long, None))
}

/// An error answer that ends the connection (the request's rest unread).
fn closing(status: u16, message: &str, allow: Option<&'static str>) -> Response {
    let body = serde_json::json!({ "error": message }).to_string();
    let mut response = reply(status, JSON, body.into_bytes());
    let headers = response.headers_mut();
    if let Some(a) = allow {
        headers.insert(header::ALLOW, HeaderValue::from_static(a));
    }
    headers.insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}

const JSON: &str = "application/json";
