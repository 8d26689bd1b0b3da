//! The seed stage: what every face brings to the merge before any merge (§3.1): its
//! linear operator ([`quadric`]). Clusters of one face each are built from these by
//! `merge::cluster`.

pub(crate) mod quadric;
