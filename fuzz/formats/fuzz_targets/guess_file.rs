//! Any bytes as a `semsim register --guess` file (16 numbers, a row-major 4x4 matrix): never a
//! panic; a guess read is a finite rigid transform; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "guess.txt";
    let text = String::from_utf8_lossy(data);
    match pipeline::guess_from_text(&text, semsim_fuzz_formats::path(name)) {
        Ok(g) => {
            assert!(g.is_finite());
            let r = g.matrix3;
            let det = r.determinant();
            assert!((det - 1.0).abs() < 1e-2, "not a rotation: det {det}");
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
