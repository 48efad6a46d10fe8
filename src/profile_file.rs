//! TOML profile files. Skeleton.
