//! plclab's harness: ns per run_round() of each ST file given: the best of 400 batches of 500
//! rounds (on a shared machine a loaded batch is slower; the best is the machine's own speed).
//! Prints JSON {"stem": ns, ...}; a file IronPLC refuses is reported on stderr and left out.
use ironplc_benchmarks::compile_st;
use ironplc_vm::test_support::load_and_start;
use ironplc_vm::VmBuffers;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let rounds: u64 = 500;
    let mut out = Vec::new();
    for path in std::env::args().skip(1) {
        let src = std::fs::read_to_string(&path).unwrap();
        let stem = std::path::Path::new(&path).file_stem().unwrap().to_string_lossy().to_string();
        let container = match std::panic::catch_unwind(|| compile_st(&src)) {
            Ok(c) => c,
            Err(_) => { eprintln!("{stem}: IronPLC does not compile it"); continue; }
        };
        let mut bufs = VmBuffers::from_container(&container);
        let mut vm = load_and_start(&container, &mut bufs).unwrap();
        let mut best = f64::INFINITY;
        let mut t_us: u64 = 0;
        for _ in 0..400 {
            let t0 = Instant::now();
            for _ in 0..rounds {
                t_us += 10_000;
                black_box(vm.run_round(t_us)).unwrap();
            }
            best = best.min(t0.elapsed().as_nanos() as f64 / rounds as f64);
        }
        out.push(format!("\"{stem}\": {best:.1}"));
    }
    println!("{{{}}}", out.join(", "));
}
