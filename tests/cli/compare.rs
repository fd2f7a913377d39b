//! `subdiv compare`: the engines' agreement, as text and as JSON.

use crate::quad_grid;
use crate::support::{scratch, stderr, stdout, subdiv, write};

#[test]
fn compare_reports_agreement_and_json() {
    let dir = scratch("compare-agreement");
    let input = write(&dir, "compare.obj", &quad_grid());
    let o = subdiv(&["compare", input.to_str().unwrap(), "--levels", "1..3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("the engines agree"), "{text}");
    assert_eq!(
        text.lines()
            .filter(|l| l.trim_end().ends_with(" ok"))
            .count(),
        3,
        "{text}"
    );
    let o = subdiv(&[
        "compare",
        input.to_str().unwrap(),
        "--levels",
        "2",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(json["agrees"], true);
    assert_eq!(json["levels"][0]["level"], 2);
    assert_eq!(json["levels"][0]["native_counts"][0], 81);
    let o = subdiv(&["compare", input.to_str().unwrap(), "--levels", "3..1"]);
    assert_eq!(o.status.code(), Some(2), "clap refuses an empty range");
}
