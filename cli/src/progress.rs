//! Progress bars on stderr, only when stderr is a terminal (indicatif hides them otherwise).

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `total` items named `what`; a counter when the total is not known (a stream).
pub fn bar(total: Option<u64>, what: &str) -> ProgressBar {
    let (bar, template) = match total {
        Some(total) => (
            ProgressBar::new(total),
            format!("{{spinner}} {what} [{{bar:30}}] {{pos}}/{{len}} ({{per_sec}}, {{eta}} left)"),
        ),
        None => (
            ProgressBar::no_length(),
            format!("{{spinner}} {what}: {{pos}} ({{per_sec}})"),
        ),
    };
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// A spinner with a message, for steps without a count (loading, building, encoding).
pub fn spinner(message: &str) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    bar.set_message(message.to_owned());
    bar.enable_steady_tick(std::time::Duration::from_millis(100));
    bar
}
