//! The event detectors, run after each physics step: contacts and wall touches
//! ([`contacts`]), doors opened / closed and door free spaces entered / left ([`doors`]),
//! breakable joints ([`joints`]), movement, tipping and getting stuck ([`motion`]), stairs
//! climbing ([`stairs`]) and ramp climbing ([`ramps`]).

pub(crate) mod contacts;
pub(crate) mod doors;
pub(crate) mod joints;
pub(crate) mod motion;
pub(crate) mod ramps;
pub(crate) mod stairs;
