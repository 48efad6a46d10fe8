//! Panics inside a campaign's queries, as text: the payload and the location the campaign's
//! silent panic hook recorded on the panicking thread.

thread_local! {
    /// Location of the last panic on this thread (set by the campaign's panic hook).
    static PANIC_LOCATION: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

/// A panic payload as text, with the location the hook recorded.
pub(super) fn panic_message(e: &(dyn std::any::Any + Send)) -> String {
    let msg = if let Some(s) = e.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = e.downcast_ref::<String>() {
        s.clone()
    } else {
        "non-string panic payload".to_string()
    };
    let loc = PANIC_LOCATION.with(|l| l.borrow().clone());
    format!("{msg} at {loc}")
}

/// The campaign's panic hook: silent, it records where the panic happened for
/// [`panic_message`].
pub(super) fn record_panic_location(info: &std::panic::PanicHookInfo<'_>) {
    let loc = info
        .location()
        .map(|l| format!("{}:{}", l.file(), l.line()))
        .unwrap_or_default();
    PANIC_LOCATION.with(|l| *l.borrow_mut() = loc);
}
