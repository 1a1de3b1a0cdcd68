//! Load × speed studies and trend curves.
