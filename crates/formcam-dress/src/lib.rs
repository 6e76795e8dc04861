//! Dressing a grinding wheel for ball-screw nut raceways.
