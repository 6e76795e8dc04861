//! The page's files: built from `viewer/` (`npm ci && npm run build`) and
//! embedded when formcam is compiled (see `build.rs`).

mod built {
    include!(concat!(env!("OUT_DIR"), "/page.rs"));
}

/// The page's files, served at `/` (`index.html`) and by their paths.
#[derive(Debug, Clone, Default)]
pub struct Page {
    files: Vec<(String, Vec<u8>)>,
}

impl Page {
    /// The page built into this formcam.
    ///
    /// # Errors
    ///
    /// [`crate::ViewError::PageNotBuilt`] when `viewer/dist/` did not exist
    /// at compile time.
    pub fn embedded() -> Result<Self, crate::ViewError> {
        let files = built::PAGE.ok_or(crate::ViewError::PageNotBuilt)?;
        Ok(Self::from_files(
            files
                .iter()
                .map(|(n, b)| ((*n).to_string(), b.to_vec()))
                .collect(),
        ))
    }

    /// Whether a page was built into this formcam.
    pub fn is_embedded() -> bool {
        built::PAGE.is_some()
    }

    /// A page of the given files (path below the page's root, bytes).
    pub fn from_files(files: Vec<(String, Vec<u8>)>) -> Self {
        Self { files }
    }

    /// No page: only the result's files and the API are served.
    pub fn none() -> Self {
        Self::default()
    }

    /// The file at `path` (`""` is `index.html`).
    pub fn get(&self, path: &str) -> Option<&[u8]> {
        let path = if path.is_empty() { "index.html" } else { path };
        self.files
            .iter()
            .find(|(n, _)| n == path)
            .map(|(_, b)| b.as_slice())
    }
}
