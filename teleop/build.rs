//! With the `physics` feature, the binaries and tests find MuJoCo's shared library where they
//! were built against it (`MUJOCO_DYNAMIC_LINK_DIR`, set by .cargo/config.toml to the directory
//! `sim/setup_mujoco.sh` fills), without `LD_LIBRARY_PATH`.

fn main() {
    println!("cargo::rerun-if-env-changed=MUJOCO_DYNAMIC_LINK_DIR");
    println!("cargo::rerun-if-env-changed=CARGO_FEATURE_PHYSICS");
    if std::env::var_os("CARGO_FEATURE_PHYSICS").is_none() {
        return;
    }
    if let Some(dir) = std::env::var_os("MUJOCO_DYNAMIC_LINK_DIR") {
        let dir = dir.to_string_lossy();
        println!("cargo::rustc-link-arg-bins=-Wl,-rpath,{dir}");
        println!("cargo::rustc-link-arg-tests=-Wl,-rpath,{dir}");
        println!("cargo::rustc-link-arg-benches=-Wl,-rpath,{dir}");
    }
}
