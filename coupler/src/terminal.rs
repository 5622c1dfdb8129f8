//! Lines for the user's terminal that never stop a run: a closed standard error or output
//! (`coupler run … 2>&1 | head -3`, a closed terminal) makes `eprintln!` and `println!` panic;
//! these drop the line instead, and the run goes on (the ledger, the recording and the
//! participants' logs keep everything).

/// `eprintln!` that drops the line when standard error is closed.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// `println!` that drops the line when standard output is closed.
#[macro_export]
macro_rules! show {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}
