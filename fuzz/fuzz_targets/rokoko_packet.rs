//! Any bytes as a Rokoko Studio datagram: teleop/tests/suite/rokoko_oracle.
#![no_main]

#[path = "../../teleop/tests/suite/rokoko_oracle/mod.rs"]
mod rokoko_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| rokoko_oracle::check_packet(data));
