//! Deterministic samplers and warps from the unit square to the domains we sample.
