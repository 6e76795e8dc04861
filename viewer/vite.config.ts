import { defineConfig } from 'vite';

// The page is served by `formcam view` from the files embedded in the
// binary: everything local, nothing fetched from elsewhere. One script
// (dynamic imports inlined), so `formcam report` can inline the page whole.
// Relative names (`./assets/...`): the same page works at `/` (`formcam
// view`), at `/runs/<name>/` (a run shown in `formcam studio`) and inlined.
export default defineConfig({
  base: './',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 2048,
    rollupOptions: { output: { inlineDynamicImports: true } },
  },
});
