//! The message of a panic a sweep caught, so one failed episode is reported, not fatal.

/// The message of a caught panic (`catch_unwind`'s payload): its `String` or `&str`, else empty.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}
