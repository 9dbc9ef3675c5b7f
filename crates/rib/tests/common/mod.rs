//! Shared helpers of the reyes-rib integration tests: read a text to requests, to its first
//! error, or to its warnings.

#![allow(dead_code)]

use reyes_rib::{Reader, Request, Source, Warning};

/// The display name every in-memory test source carries.
pub const FILE: &str = "test.rib";

/// Every request of `text`; panics (the test fails) on the first error.
pub fn read(text: &str) -> Vec<Request> {
    let mut r = Reader::new(Source::from_bytes(FILE, text));
    let mut out = Vec::new();
    loop {
        match r.next_request() {
            Ok(Some(q)) => out.push(q),
            Ok(None) => return out,
            Err(e) => panic!("{text:?}: {e}"),
        }
    }
}

/// The only request of `text`.
pub fn one(text: &str) -> Request {
    let mut all = read(text);
    assert_eq!(all.len(), 1, "{text:?}: {all:?}");
    all.remove(0)
}

/// The first error of `text`, displayed.
pub fn first_error(text: &str) -> String {
    let mut r = Reader::new(Source::from_bytes(FILE, text));
    loop {
        match r.next_request() {
            Ok(Some(_)) => {}
            Ok(None) => panic!("{text:?}: no error"),
            Err(e) => return e.to_string(),
        }
    }
}

/// The first error of raw bytes, displayed.
pub fn first_error_bytes(bytes: &[u8]) -> String {
    let mut r = Reader::new(Source::from_bytes(FILE, bytes.to_vec()));
    loop {
        match r.next_request() {
            Ok(Some(_)) => {}
            Ok(None) => panic!("{bytes:?}: no error"),
            Err(e) => return e.to_string(),
        }
    }
}

/// Every error of `text`, displayed, reading on after each (recovery), with the requests read.
pub fn all_errors(text: &str) -> (Vec<String>, Vec<Request>) {
    let mut r = Reader::new(Source::from_bytes(FILE, text));
    let (mut errors, mut requests) = (Vec::new(), Vec::new());
    for _ in 0..10_000 {
        match r.next_request() {
            Ok(Some(q)) => requests.push(q),
            Ok(None) => return (errors, requests),
            Err(e) => errors.push(e.to_string()),
        }
    }
    panic!("{text:?}: the reader did not finish");
}

/// The warnings of `text` (which must read without error), displayed.
pub fn warnings(text: &str) -> Vec<String> {
    let mut r = Reader::new(Source::from_bytes(FILE, text));
    while r.next_request().unwrap_or_else(|e| panic!("{text:?}: {e}")).is_some() {}
    r.warnings().iter().map(Warning::to_string).collect()
}
