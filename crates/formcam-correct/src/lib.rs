//! Correction of a mould milling program from CMM measurements.
