//! Ray–triangle intersection (Möller–Trumbore).
