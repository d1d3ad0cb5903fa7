//! Any bytes as a CDR payload of every `msgs` type: msgs/tests/suite/cdr_oracle.
#![no_main]

#[path = "../../msgs/tests/suite/cdr_oracle/mod.rs"]
mod cdr_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| cdr_oracle::check_payload(data));
