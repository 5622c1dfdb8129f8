//! The command-line help tells a new user what the tool does, what each argument is, the exit
//! codes and where the case keys are documented; defaults print as a person writes them.

use stack_tests::coupler;

fn help(args: &[&str]) -> String {
    let out = coupler(args);
    assert!(out.status.success(), "{args:?}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn help_describes_the_tool_the_case_argument_exit_codes_and_case_keys() {
    let top = help(&["--help"]);
    assert!(
        top.contains("Runs tsunami–structure simulations as cooperating processes"),
        "{top}"
    );
    assert!(
        !top.contains("The user's entry point"),
        "not the crate description: {top}"
    );
    for args in [
        &["--help"][..],
        &["run", "--help"],
        &["check", "--help"],
        &["replay", "--help"],
    ] {
        let text = help(args);
        assert!(
            text.contains("Exit codes: 0") && text.contains("130 interrupted"),
            "{args:?}: {text}"
        );
        assert!(
            text.contains("docs/guide/case-reference.md") && text.contains("`coupler reference`"),
            "{args:?}: where case keys are documented: {text}"
        );
    }
    let check = help(&["check", "--help"]);
    assert!(check.contains("<CASE>  The case file (TOML) to check"), "{check}");
    let run = help(&["run", "--help"]);
    assert!(
        run.contains("--overwrite") && run.contains("--max-output <SIZE>"),
        "{run}"
    );
    assert!(run.contains("[default: 20G]"), "{run}");
    let replay = help(&["replay", "--help"]);
    assert!(replay.contains("[default: 1e-9]"), "{replay}");
    assert!(!replay.contains("0.000000001"), "{replay}");
}
