//! A run's output folder written whole, never over an input.
