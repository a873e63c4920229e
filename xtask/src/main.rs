//! `cargo xtask <page> [ARGS]`: regenerate one measured page of `docs/`
//! (the table in the crate docs of [`xtask`] lists them).

use std::process::ExitCode;

/// Each page's command, its entry point, and what it writes.
const PAGES: [(&str, fn(), &str); 8] = [
    (
        "methods",
        xtask::methods::main,
        "the measured tables behind docs/methods.md, printed as markdown (about a minute; > out/xtask/methods.md)",
    ),
    (
        "contact-loss",
        xtask::contact_loss::main,
        "the measured tables behind docs/contact_loss.md, printed as markdown (`quick`: a cut-down ladder; > out/xtask/contact_loss.md)",
    ),
    (
        "convergence",
        xtask::convergence::main,
        "out/xtask/convergence.md, the tables docs/convergence.md quotes, written in full",
    ),
    (
        "stability",
        xtask::stability::main,
        "the stability report, written in full to out/xtask/stability.md (docs/stability.md explains it)",
    ),
    (
        "reproduction",
        xtask::reproduction::main,
        "out/xtask/reproduction.md and the maps of docs/reproduction/ (`--full`: T7 refined at 41 x 41; `--resume`: keep finished runs)",
    ),
    (
        "published-band",
        xtask::published_band::main,
        "the tables of docs/reproduction.md's last section, printed (about a minute)",
    ),
    (
        "accuracy-check",
        xtask::accuracy_check::main,
        "the tables of docs/accuracy.md, printed (`grid SCENE Q N1,N2,.. DT1,DT2,..` or `check SCENE Q TOL K`)",
    ),
    (
        "uncertainty",
        xtask::uncertainty::main,
        "the coverage tables behind docs/verification.md (solution verification), printed as markdown (`quick`: a few pairs a case; `heldout`: the held-out pairs; > out/xtask/uncertainty.md)",
    ),
];

fn main() -> ExitCode {
    let page = std::env::args().nth(1);
    match PAGES
        .iter()
        .find(|(name, _, _)| Some(*name) == page.as_deref())
    {
        Some((_, run, _)) => {
            run();
            ExitCode::SUCCESS
        }
        None => {
            eprintln!("usage: cargo xtask <page> [ARGS]; the pages:");
            for (name, _, what) in PAGES {
                eprintln!("  {name:<13} {what}");
            }
            ExitCode::from(2)
        }
    }
}
