//! Reading an input file: regular files only, with a size cap.
