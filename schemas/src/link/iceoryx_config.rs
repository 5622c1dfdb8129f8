//! The iceoryx2 configuration of the link, set in code (no config file is read, so no warning).

use super::LinkError;
use iceoryx2::prelude::{
    set_log_level_from_env_or, AllocationStrategy, BackpressureStrategy, Config, FileName, LogLevel,
    SemanticString,
};
use std::sync::Once;

/// Messages a subscriber can hold before its publisher must wait (lock-step needs 1; the rest is slack
/// for a few messages sent in a row).
pub const SUBSCRIBER_BUFFER: usize = 8;

/// Slice length the publisher's shared memory is first sized for; larger messages grow it by powers of two.
pub const INITIAL_MAX_SLICE_LEN: usize = 64 * 1024;

/// One coupler and one participant per service: one publisher, one subscriber, one notifier and one
/// listener, in two nodes. A second process claiming the same side fails instead of cross-talking.
const PORTS_PER_SERVICE: usize = 1;

/// How long one side waits for a service the other side is creating (iceoryx2's default is 1 s).
/// Both sides open-or-create the same services at start-up; on a loaded 2-core machine (CI with
/// the tests' processes in parallel) the creating process can be descheduled for over a second,
/// and the other side then failed with `HangsInCreation` (seen intermittently in the oscillator
/// report test). A creation that really hangs (its process died half-way) is reported after this.
pub const CREATION_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(15);
const NODES_PER_SERVICE: usize = 2;

/// Prefix of every shared-memory file of the link. Keeps the link's nodes apart from other iceoryx2
/// users on the machine (whose dead nodes it would otherwise inspect and clean up).
pub const FILE_PREFIX: &str = "tsunami_";

/// The configuration every node of the link is created with.
pub fn link_config() -> Result<Config, LinkError> {
    let mut config = Config::default();
    config.global.prefix = FileName::new(FILE_PREFIX.as_bytes())
        .map_err(|e| LinkError::Iceoryx(format!("invalid shared-memory prefix {FILE_PREFIX:?}: {e:?}")))?;
    // Dead nodes of a SIGKILLed run are removed when a node is created or a service opened (the
    // 0.10 defaults, set explicitly because the link relies on them).
    config.global.creation_timeout = CREATION_TIMEOUT;
    config.global.node.cleanup_dead_nodes_on_creation = true;
    config.global.node.cleanup_dead_nodes_on_destruction = true;
    config.global.service.cleanup_dead_nodes_on_open = true;

    let ps = &mut config.defaults.publish_subscribe;
    ps.max_publishers = PORTS_PER_SERVICE;
    ps.max_subscribers = PORTS_PER_SERVICE;
    ps.max_nodes = NODES_PER_SERVICE;
    ps.subscriber_max_buffer_size = SUBSCRIBER_BUFFER;
    ps.subscriber_max_borrowed_samples = 1;
    ps.publisher_max_loaned_samples = 1;
    ps.publisher_history_size = 0;
    ps.enable_safe_overflow = false;
    ps.backpressure_strategy = BackpressureStrategy::RetryUntilDelivered;
    ps.publisher_allocation_strategy = AllocationStrategy::PowerOfTwo;

    let ev = &mut config.defaults.event;
    ev.max_listeners = PORTS_PER_SERVICE;
    ev.max_notifiers = PORTS_PER_SERVICE;
    ev.max_nodes = NODES_PER_SERVICE;
    Ok(config)
}

/// Limits iceoryx2's own console messages to errors unless `IOX2_LOG_LEVEL` says otherwise (once per
/// process). Its warnings are routine for the link, e.g. "Detected dead node ... Trying to cleanup
/// stale resources" after a killed run, which the link expects and handles.
pub fn quiet_iceoryx_logs() {
    static QUIET: Once = Once::new();
    QUIET.call_once(|| set_log_level_from_env_or(LogLevel::Error));
}
